// Whether an image V is another draw of the estimator of two references A and B, per channel
// and per block. The derivation:
//
// A and B are renders with the same seed (so the same hit points), budget and batch layout,
// each with its own photon stream. If V is another draw of the same estimator, the three are
// independent draws of one random image: the same expectation (bias included) and the same
// covariance C between pixels. Per pixel and channel let E = V - (A + B) / 2 and D = A - B.
// Then Cov(E) = 3/2 C, Cov(D) = 2 C and Cov(E, D) = -C/2 + C/2 = 0: (4/3)^(1/2) E and D have
// the same covariance and are uncorrelated, and over a block of pixels, whose sums are close to
// normal (sums over many photons and light samples), they are independent draws of one
// distribution. So each statistic of E is compared with the same statistic of D, which holds
// the estimator's noise and nothing else; V from another estimator shifts E (a bias) or
// widens it (more noise).
//
// Blocks are 4x4 pixels (64 in a 32x32 image), halved until there are at least 16; leftover
// rows and columns join the last block of their row or column. P pixels, sums S_b(.) over
// block b. The model neglects covariance between blocks (photons whose paths reach several);
// image_agreement_test.cpp checks it against the spread of the means of 12 independent renders
// (BlockModel.PredictsTheSpreadOfIndependentDraws: 0.5 to 1.0 of the prediction measured).
//
// Per channel, three checks, each failing a true draw with probability kFalseAlarm:
//  - mean: mean(E) against sigma^2 = (3/4) sum_b S_b(D)^2 / P^2, the unbiased estimate of its
//    variance (E[S_b(D)^2] = 2 Var(S_b(X)), Var(mean E) = (3/2) sum_b Var(S_b(X)) / P^2).
//    mean(E) is independent of D, so mean(E) / sigma is Student's t with the Satterthwaite
//    degrees of freedom (sum_b w_b)^2 / sum_b w_b^2 of blocks of unequal variance, the weights
//    w_b = S_b(D^2) estimating each block's share. The check that catches a bias: a channel 2%
//    too bright moves mean(E) by 2% of the channel's mean, many sigma at the tests' budgets
//    (DetectableBias says how far; ExpectSameEstimator requires 2% to fail).
//  - blocks: (4/3) sum_b S_b(E)^2 / sum_b S_b(D)^2. Numerator and denominator are independent
//    sums of the same weighted chi-squares: the ratio is F with the degrees of freedom above
//    on both sides (one-sided). It catches a bias in part of the image that the mean averages
//    away (a kernel wrong near edges, one tile of a farm).
//  - spread: the blocks' r_b = log((4/3) S_b(E^2) / S_b(D^2)). For a true draw numerator and
//    denominator are independent draws of one sum of squares, so r_b is symmetric about 0
//    whatever the block's brightness; Student's t of the r_b (blocks - 1 degrees of freedom),
//    two-sided: V noisier than the estimator fails above, V not independent of A and B (a
//    copy of one: E = D / 2, r_b = log(1/3)) below. (4/3) sum E^2 / sum D^2 is reported.
// A channel where A equals B (black, or lit by emission alone) is deterministic: V must equal
// A there to 1e-5 of the channel's largest value; so must V in a block where A equals B (a sky
// seen directly), and the spread's r_b (undefined there) is taken over the other blocks.
#include "tests/support/image_agreement.h"

#include <absl/strings/str_format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace pf::testing {
namespace {

// The continued fraction of the incomplete beta function (Lentz's method, as in Numerical
// Recipes 6.4); converges quickly for x < (a + 1) / (a + b + 2).
double BetaContinuedFraction(double a, double b, double x) {
    constexpr double kTiny = 1e-300;
    double c = 1, d = 1 - (a + b) * x / (a + 1);
    d = 1 / (std::abs(d) < kTiny ? kTiny : d);
    double h = d;
    for (int m = 1; m <= 1000; ++m) {
        for (const double numerator :
             {m * (b - m) * x / ((a + 2 * m - 1) * (a + 2 * m)),
              -(a + m) * (a + b + m) * x / ((a + 2 * m) * (a + 2 * m + 1))}) {
            d = 1 + numerator * d;
            d = 1 / (std::abs(d) < kTiny ? kTiny : d);
            c = 1 + numerator / c;
            if (std::abs(c) < kTiny) c = kTiny;
            h *= d * c;
        }
        if (std::abs(d * c - 1) < 1e-15) break;
    }
    return h;
}

// The regularised incomplete beta function I_x(a, b).
double RegularisedBeta(double x, double a, double b) {
    if (x <= 0) return 0;
    if (x >= 1) return 1;
    const double log_front =
        std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
    if (x < (a + 1) / (a + b + 2)) return std::exp(log_front) * BetaContinuedFraction(a, b, x) / a;
    return 1 - std::exp(log_front) * BetaContinuedFraction(b, a, 1 - x) / b;
}

// The x > 0 where the decreasing `tail` falls to `target`, by bisection of log x.
template <typename Tail>
double InvertTail(double target, Tail tail) {
    double low = std::log(1e-12), high = std::log(1e12);
    for (int i = 0; i < 200; ++i) {
        const double middle = (low + high) / 2;
        (tail(std::exp(middle)) > target ? low : high) = middle;
    }
    return std::exp((low + high) / 2);
}

double Channel(const Rgb& pixel, int c) { return pixel[c]; }

// Block index of each pixel: blocks of `size` pixels, the leftovers in the last block.
std::vector<int> BlockOfPixels(const Image& image, int size, int& blocks) {
    const int across = std::max(1, image.width / size), down = std::max(1, image.height / size);
    blocks = across * down;
    std::vector<int> block(image.pixels.size());
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            block[static_cast<size_t>(y) * image.width + x] =
                std::min(y / size, down - 1) * across + std::min(x / size, across - 1);
    return block;
}

ChannelAgreement CompareChannel(const Image& image, const Image& a, const Image& b, int channel,
                                const std::vector<int>& block_of, int blocks) {
    ChannelAgreement result;
    const double pixels = static_cast<double>(a.pixels.size());
    std::vector<double> block_e(blocks), block_d(blocks), block_e_sq(blocks), block_d_sq(blocks),
        block_worst(blocks);
    double sum_e = 0, sum_a = 0, sum_b = 0, e_sq = 0, d_sq = 0, largest = 0,
           worst_deterministic = 0;
    for (size_t p = 0; p < a.pixels.size(); ++p) {
        const double va = Channel(a.pixels[p], channel), vb = Channel(b.pixels[p], channel);
        const double v = Channel(image.pixels[p], channel);
        const double e = v - (va + vb) / 2, d = va - vb;
        sum_e += e, sum_a += va, sum_b += vb;
        e_sq += e * e, d_sq += d * d;
        const int k = block_of[p];
        block_e[k] += e, block_d[k] += d, block_e_sq[k] += e * e, block_d_sq[k] += d * d;
        largest = std::max({largest, std::abs(va), std::abs(vb)});
        worst_deterministic = std::max(worst_deterministic, std::abs(v - va));
        block_worst[k] = std::max(block_worst[k], std::abs(v - va));
    }
    result.reference_mean = (sum_a + sum_b) / (2 * pixels);
    result.difference = sum_e / pixels;
    result.deterministic_tolerance = 1e-5 * largest;
    if (d_sq == 0) {
        result.deterministic = true;
        result.deterministic_error = worst_deterministic;
        return result;
    }
    double blocks_e_sq = 0, blocks_d_sq = 0, weights = 0, weights_sq = 0;
    for (int k = 0; k < blocks; ++k) {
        blocks_e_sq += block_e[k] * block_e[k];
        blocks_d_sq += block_d[k] * block_d[k];
        weights += block_d_sq[k], weights_sq += block_d_sq[k] * block_d_sq[k];
    }
    result.sigma = std::sqrt(0.75 * blocks_d_sq) / pixels;
    result.mean_dof = std::clamp(weights * weights / weights_sq, 1.0, static_cast<double>(blocks));
    result.mean_limit = StudentTQuantile(kFalseAlarm / 2, result.mean_dof) * result.sigma;
    result.block_ratio = blocks_d_sq > 0 ? (4.0 / 3.0) * blocks_e_sq / blocks_d_sq
                                         : std::numeric_limits<double>::infinity();
    result.block_limit = FQuantile(kFalseAlarm, result.mean_dof, result.mean_dof);
    result.spread_ratio = (4.0 / 3.0) * e_sq / d_sq;
    double x_sum = 0, x_sq = 0;
    int random_blocks = 0;
    for (int k = 0; k < blocks; ++k) {
        if (!(block_d_sq[k] > 0)) {
            ++result.deterministic_blocks;
            result.deterministic_blocks_error =
                std::max(result.deterministic_blocks_error, block_worst[k]);
            continue;
        }
        const double x = std::log((4.0 / 3.0) * block_e_sq[k] / block_d_sq[k]);
        x_sum += x, x_sq += x * x, ++random_blocks;
    }
    if (random_blocks < 2) {  // too few to spread: the mean and block checks decide
        result.spread_limit = std::numeric_limits<double>::infinity();
        return result;
    }
    const double x_mean = x_sum / random_blocks;
    const double x_variance =
        std::max(0.0, x_sq - random_blocks * x_mean * x_mean) / (random_blocks - 1);
    result.spread_t = x_mean / std::sqrt(x_variance / random_blocks);
    result.spread_limit = StudentTQuantile(kFalseAlarm / 2, random_blocks - 1);
    return result;
}

}  // namespace

double StudentTUpperTail(double t, double dof) {
    const double both = RegularisedBeta(dof / (dof + t * t), dof / 2, 0.5);  // P(|T| > |t|)
    return t >= 0 ? both / 2 : 1 - both / 2;
}

double FUpperTail(double f, double dof1, double dof2) {
    if (f <= 0) return 1;
    return RegularisedBeta(dof2 / (dof2 + dof1 * f), dof2 / 2, dof1 / 2);
}

double StudentTQuantile(double upper_tail, double dof) {
    if (upper_tail >= 0.5) return -StudentTQuantile(1 - upper_tail, dof);
    return InvertTail(upper_tail, [&](double t) { return StudentTUpperTail(t, dof); });
}

double FQuantile(double upper_tail, double dof1, double dof2) {
    return InvertTail(upper_tail, [&](double f) { return FUpperTail(f, dof1, dof2); });
}

double ChannelAgreement::DetectableBias() const {
    if (deterministic) return 0;
    if (reference_mean <= 0) return std::numeric_limits<double>::infinity();
    return (mean_limit + 3.1 * sigma) / reference_mean;
}

bool ImageAgreement::Passed() const {
    return error.empty() && std::all_of(channels.begin(), channels.end(),
                                        [](const ChannelAgreement& c) { return c.Passed(); });
}

double ImageAgreement::DetectableBias() const {
    double brightest = 0, worst = 0;
    for (const ChannelAgreement& c : channels) brightest = std::max(brightest, c.reference_mean);
    for (const ChannelAgreement& c : channels)
        if (c.reference_mean >= 1e-3 * brightest) worst = std::max(worst, c.DetectableBias());
    return worst;
}

std::string ImageAgreement::Describe() const {
    if (!error.empty()) return error;
    std::string text = absl::StrFormat("%d blocks of %dx%d pixels", blocks, block_size, block_size);
    for (int c = 0; c < 3; ++c) {
        const ChannelAgreement& s = channels[c];
        text += absl::StrFormat(
            "\n  %c: mean %.6g against %.6g (%+.3f%%), allowed +-%.3f%% (sigma %.3g, %.1f dof)%s;"
            " blocks %.3g <= %.3g%s; spread %.3g (t %.2f, allowed +-%.2f)%s; catches a bias of "
            "%.2f%%",
            "RGB"[c], s.reference_mean + s.difference, s.reference_mean,
            100 * s.difference / s.reference_mean, 100 * s.mean_limit / s.reference_mean, s.sigma,
            s.mean_dof, s.MeanPassed() ? "" : " FAILED", s.block_ratio, s.block_limit,
            s.BlocksPassed() ? "" : " FAILED", s.spread_ratio, s.spread_t, s.spread_limit,
            s.SpreadPassed() ? "" : " FAILED", 100 * s.DetectableBias());
        if (s.deterministic)
            text += absl::StrFormat(" -- A equals B here: |V - A| up to %.3g, allowed %.3g",
                                    s.deterministic_error, s.deterministic_tolerance);
        else if (s.deterministic_blocks > 0)
            text += absl::StrFormat(
                " -- A equals B in %d blocks: |V - A| up to %.3g there, allowed %.3g",
                s.deterministic_blocks, s.deterministic_blocks_error, s.deterministic_tolerance);
    }
    return text;
}

ImageAgreement CompareWithEstimator(const Image& image, const Image& a, const Image& b) {
    ImageAgreement result;
    if (a.pixels.empty() || image.pixels.size() != a.pixels.size() ||
        b.pixels.size() != a.pixels.size() || image.width != a.width || b.width != a.width) {
        result.error =
            absl::StrFormat("cannot compare a %dx%d image with references %dx%d and %dx%d",
                            image.width, image.height, a.width, a.height, b.width, b.height);
        return result;
    }
    result.block_size = 4;
    BlockOfPixels(a, result.block_size, result.blocks);
    while (result.blocks < 16 && result.block_size > 1)
        BlockOfPixels(a, result.block_size /= 2, result.blocks);
    const std::vector<int> block_of = BlockOfPixels(a, result.block_size, result.blocks);
    if (result.blocks < 4) {
        result.error = absl::StrFormat("a %dx%d image is too small to compare (4 pixels or more)",
                                       a.width, a.height);
        return result;
    }
    for (int c = 0; c < 3; ++c)
        result.channels[c] = CompareChannel(image, a, b, c, block_of, result.blocks);
    return result;
}

void ExpectSameEstimator(const Image& image, const Image& a, const Image& b) {
    const ImageAgreement agreement = CompareWithEstimator(image, a, b);
    EXPECT_TRUE(agreement.Passed()) << "the image is not another draw of the references' "
                                       "estimator: "
                                    << agreement.Describe();
    EXPECT_LE(agreement.DetectableBias(), kBiasToCatch)
        << "the comparison is too weak to catch a " << 100 * kBiasToCatch
        << "% bias; raise the renders' budget: " << agreement.Describe();
}

double MeanSquaredDifference(const Image& a, const Image& b) {
    double sum = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double d = double(a.pixels[i][c]) - b.pixels[i][c];
            sum += d * d;
        }
    return sum / (3.0 * static_cast<double>(a.pixels.size()));
}

}  // namespace pf::testing
