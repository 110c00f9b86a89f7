// The image comparison of tests/support/image_agreement.h on real renders (cornell-box, 32x32,
// 1M photons: tests/support/small_render.h): an independent draw passes; the same draw 2%
// brighter or darker, with one channel tinted 2%, with red and blue swapped, biased in one
// quarter, noisier, or a copy of a reference fails. Also the distributions it uses against
// tabled values, and its block model against the spread of 12 independent renders.
#include "tests/support/image_agreement.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "tests/support/small_render.h"

namespace pf::testing {
namespace {

// A draw of the estimator: cornell-box (coloured walls, so a channel swap shows) with photon
// stream `stream`, the same seed and hit points for every stream.
Image Draw(uint64_t stream) {
    return RenderSmall(std::string(PF_SOURCE_DIR) + "/scenes/cornell-box.gltf", "cpu", stream);
}

Image Scaled(Image image, const Rgb& factor) {
    for (Rgb& pixel : image.pixels) pixel = pixel * factor;
    return image;
}

// The pixels with x in [x0, x0 + size) and y in [y0, y0 + size) multiplied by `factor`.
Image ScaledSquare(Image image, int x0, int y0, int size, const Rgb& factor) {
    for (int y = y0; y < y0 + size; ++y)
        for (int x = x0; x < x0 + size; ++x) image.At(x, y) = image.At(x, y) * factor;
    return image;
}

Rgb SquareSum(const Image& image, int x0, int y0, int size) {
    Rgb sum(0.0f);
    for (int y = y0; y < y0 + size; ++y)
        for (int x = x0; x < x0 + size; ++x) sum = sum + image.At(x, y);
    return sum;
}

class ImageAgreementTest : public ::testing::Test {
protected:
    void SetUp() override {
        a_ = Draw(1), b_ = Draw(2), v_ = Draw(3);
        ASSERT_FALSE(a_.pixels.empty() || b_.pixels.empty() || v_.pixels.empty());
    }

    Image a_, b_, v_;
};

TEST(Distributions, MatchTabledQuantiles) {
    // Student's t and F quantiles from the standard tables (Abramowitz & Stegun 26.7, 26.6).
    EXPECT_NEAR(StudentTQuantile(0.025, 1), 12.7062, 1e-4);
    EXPECT_NEAR(StudentTQuantile(0.005, 3), 5.84091, 1e-4);
    EXPECT_NEAR(StudentTQuantile(0.025, 10), 2.22814, 1e-5);
    EXPECT_NEAR(StudentTQuantile(0.975, 10), -2.22814, 1e-5);
    EXPECT_NEAR(StudentTQuantile(0.025, 1e7), 1.95996, 1e-5);  // the normal's
    EXPECT_NEAR(FQuantile(0.05, 5, 5), 5.05033, 1e-4);
    EXPECT_NEAR(FQuantile(0.01, 10, 20), 3.36819, 1e-4);
    EXPECT_NEAR(FQuantile(0.5, 7, 7), 1.0, 1e-9);  // the median of F(n, n)
    EXPECT_NEAR(StudentTUpperTail(0, 4), 0.5, 1e-12);
    EXPECT_NEAR(FUpperTail(FQuantile(1e-5, 16, 16), 16, 16), 1e-5, 1e-9);
}

TEST_F(ImageAgreementTest, IndependentDrawPassesAndCouldCatchATwoPercentBias) {
    const ImageAgreement agreement = CompareWithEstimator(v_, a_, b_);
    EXPECT_TRUE(agreement.Passed()) << agreement.Describe();
    EXPECT_LE(agreement.DetectableBias(), kBiasToCatch) << agreement.Describe();
    std::printf("%s\n", agreement.Describe().c_str());
}

TEST_F(ImageAgreementTest, TwoPercentBrighterOrDarkerFailsInEveryChannel) {
    for (const float factor : {1.02f, 0.98f}) {
        const ImageAgreement agreement = CompareWithEstimator(Scaled(v_, Rgb(factor)), a_, b_);
        EXPECT_FALSE(agreement.Passed()) << factor << ": " << agreement.Describe();
        for (int c = 0; c < 3; ++c)
            EXPECT_FALSE(agreement.channels[c].MeanPassed())
                << factor << ", channel " << c << ": " << agreement.Describe();
    }
}

TEST_F(ImageAgreementTest, OneChannelTintedTwoPercentFailsInThatChannel) {
    for (int c = 0; c < 3; ++c) {
        Rgb tint(1.0f);
        tint[c] = 1.02f;
        const ImageAgreement agreement = CompareWithEstimator(Scaled(v_, tint), a_, b_);
        EXPECT_FALSE(agreement.channels[c].MeanPassed()) << c << ": " << agreement.Describe();
        EXPECT_FALSE(agreement.Passed());
        for (int other = 0; other < 3; ++other) {
            if (other == c) continue;
            EXPECT_TRUE(agreement.channels[other].Passed()) << agreement.Describe();
        }
    }
}

TEST_F(ImageAgreementTest, RedAndBlueSwappedFails) {
    // The average of the channels, which the comparison once used, does not change.
    Image swapped = v_;
    for (Rgb& pixel : swapped.pixels) std::swap(pixel.x, pixel.z);
    const ImageAgreement agreement = CompareWithEstimator(swapped, a_, b_);
    EXPECT_FALSE(agreement.channels[0].MeanPassed()) << agreement.Describe();
    EXPECT_FALSE(agreement.channels[2].MeanPassed()) << agreement.Describe();
}

TEST_F(ImageAgreementTest, BiasInOneQuarterFailsTheBlockCheckThoughTheMeanHolds) {
    // The top-left quarter 3% brighter, the bottom-right darker by as much light per channel:
    // every channel's mean is unchanged, so only the blocks can see it.
    const Rgb added = SquareSum(v_, 0, 0, 16) * 0.03f;
    const Rgb bottom_right = SquareSum(v_, 16, 16, 16);
    Rgb compensate(1.0f);
    for (int c = 0; c < 3; ++c) compensate[c] = 1.0f - added[c] / bottom_right[c];
    const Image moved =
        ScaledSquare(ScaledSquare(v_, 0, 0, 16, Rgb(1.03f)), 16, 16, 16, compensate);
    const ImageAgreement agreement = CompareWithEstimator(moved, a_, b_);
    const ImageAgreement original = CompareWithEstimator(v_, a_, b_);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(agreement.channels[c].difference, original.channels[c].difference,
                    1e-5 * original.channels[c].reference_mean);
        EXPECT_FALSE(agreement.channels[c].BlocksPassed()) << c << ": " << agreement.Describe();
    }
}

TEST_F(ImageAgreementTest, NoisierDrawFailsTheSpreadCheck) {
    // V plus the difference of two more draws: unbiased, with three times the variance.
    const Image c = Draw(4), d = Draw(5);
    Image noisier = v_;
    for (size_t p = 0; p < noisier.pixels.size(); ++p)
        noisier.pixels[p] = noisier.pixels[p] + c.pixels[p] - d.pixels[p];
    const ImageAgreement agreement = CompareWithEstimator(noisier, a_, b_);
    for (int channel = 0; channel < 3; ++channel)
        EXPECT_FALSE(agreement.channels[channel].SpreadPassed())
            << channel << ": " << agreement.Describe();
}

TEST_F(ImageAgreementTest, CopyOfAReferenceFailsTheSpreadCheck) {
    // Not an independent draw: E = D / 2, so the spread ratio is 1/3 exactly.
    const ImageAgreement agreement = CompareWithEstimator(a_, a_, b_);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(agreement.channels[c].spread_ratio, 1.0 / 3.0, 1e-9);
        EXPECT_FALSE(agreement.channels[c].SpreadPassed()) << agreement.Describe();
    }
}

TEST_F(ImageAgreementTest, NanPixelFails) {
    Image broken = v_;
    broken.pixels[100].y = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(CompareWithEstimator(broken, a_, b_).Passed());
}

TEST(ImageAgreement, DeterministicChannelsMustMatchAndSizesMustAgree) {
    // Blue black in both references, red and green random: V's blue must be black too.
    Image a(16, 16), b(16, 16);
    for (size_t p = 0; p < a.pixels.size(); ++p) {
        a.pixels[p] = Rgb(1.0f + 0.1f * std::sin(p), 1.0f + 0.1f * std::cos(p), 0.0f);
        b.pixels[p] = Rgb(1.0f + 0.1f * std::sin(p + 7.0), 1.0f + 0.1f * std::cos(p + 7.0), 0.0f);
    }
    Image v = a;
    for (size_t p = 0; p < v.pixels.size(); ++p)
        v.pixels[p] = Rgb(1.0f + 0.1f * std::sin(p + 3.0), 1.0f + 0.1f * std::cos(p + 3.0), 0.0f);
    const ImageAgreement agreement = CompareWithEstimator(v, a, b);
    EXPECT_TRUE(agreement.channels[2].deterministic);
    EXPECT_TRUE(agreement.channels[2].Passed()) << agreement.Describe();
    v.pixels[5].z = 1e-3f;
    EXPECT_FALSE(CompareWithEstimator(v, a, b).channels[2].Passed());
    EXPECT_FALSE(CompareWithEstimator(Image(8, 32), a, b).error.empty());
    EXPECT_FALSE(CompareWithEstimator(v, a, Image(16, 8)).Passed());
}

TEST_F(ImageAgreementTest, BlocksWhereTheReferencesAgreeMustMatchExactly) {
    // A sky seen directly: the top rows equal in both references (and in V) are deterministic
    // blocks; the spread check runs over the rest, and V must equal them there.
    const auto with_sky = [](Image image) {
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < image.width; ++x) image.At(x, y) = Rgb(0.3f, 0.4f, 0.9f);
        return image;
    };
    const Image a = with_sky(a_), b = with_sky(b_), v = with_sky(v_);
    const ImageAgreement agreement = CompareWithEstimator(v, a, b);
    EXPECT_TRUE(agreement.Passed()) << agreement.Describe();
    EXPECT_GT(agreement.channels[0].deterministic_blocks, 0);
    EXPECT_TRUE(std::isfinite(agreement.channels[0].spread_t)) << agreement.Describe();
    Image off = v;
    off.At(3, 2).y *= 1.001f;
    EXPECT_FALSE(CompareWithEstimator(off, a, b).Passed());
}

class BlockModel : public ::testing::TestWithParam<std::string> {};

TEST_P(BlockModel, PredictsTheSpreadOfIndependentDraws) {
    // The mean check's variance comes from the blocks of one pair, neglecting covariance
    // between blocks. Twelve independent draws measure the variance of the image mean
    // directly (11 degrees of freedom); the block model, averaged over the six disjoint pairs,
    // predicts it. Their ratio is F(11, sum of the pairs' dof) if the model holds; a model that
    // missed covariance between blocks (photon paths that reach many of them: furnace-glass's
    // walls of albedo 0.5) would put it above the upper limit.
    constexpr int kDraws = 12;
    std::vector<Image> draws;
    for (int k = 0; k < kDraws; ++k)
        draws.push_back(RenderSmall(std::string(PF_SOURCE_DIR) + "/scenes/" + GetParam(), "cpu",
                                    static_cast<uint64_t>(k + 1)));
    for (const Image& draw : draws) ASSERT_FALSE(draw.pixels.empty());
    const double pixels = static_cast<double>(draws[0].pixels.size());
    for (int c = 0; c < 3; ++c) {
        std::vector<double> means;
        for (const Image& draw : draws) {
            double sum = 0;
            for (const Rgb& pixel : draw.pixels) sum += pixel[c];
            means.push_back(sum / pixels);
        }
        double grand = 0, spread = 0;
        for (double m : means) grand += m / kDraws;
        for (double m : means) spread += (m - grand) * (m - grand) / (kDraws - 1);
        // A comparison's sigma is the standard deviation of mean(E), whose variance is 3/2
        // that of one draw's mean.
        double predicted = 0, dof = 0;
        for (int k = 0; k < kDraws; k += 2) {
            const ChannelAgreement pair =
                CompareWithEstimator(draws[k], draws[k], draws[k + 1]).channels[c];
            predicted += pair.sigma * pair.sigma / 1.5 / (kDraws / 2);
            dof += pair.mean_dof;
        }
        const double ratio = spread / predicted;
        std::printf(
            "%s, channel %d: measured / predicted variance of the image mean %.3f "
            "(allowed %.3f to %.3f)\n",
            GetParam().c_str(), c, ratio, 1 / FQuantile(1e-4, dof, kDraws - 1),
            FQuantile(1e-4, kDraws - 1, dof));
        EXPECT_LE(ratio, FQuantile(1e-4, kDraws - 1, dof))
            << "channel " << c << ": the image means spread more than the blocks predict";
        EXPECT_GE(ratio, 1 / FQuantile(1e-4, dof, kDraws - 1)) << "channel " << c;
    }
}

INSTANTIATE_TEST_SUITE_P(Scenes, BlockModel,
                         ::testing::Values("cornell-box.gltf", "furnace-glass.gltf"),
                         [](const ::testing::TestParamInfo<std::string>& scene) {
                             std::string name = scene.param.substr(0, scene.param.find('.'));
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

}  // namespace
}  // namespace pf::testing
