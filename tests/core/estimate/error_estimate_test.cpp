// The error estimated from the even and odd half-estimates (ProgressiveEstimate::EstimateError)
// on hand-made tallies whose answer is worked out below.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/estimate/progressive_estimate.h"
#include "core/job/job_spec.h"
#include "tests/core/estimate/one_point_estimate.h"

namespace pf {
namespace {

constexpr uint32_t kPhotons = testing::kOnePointPhotons;
constexpr double kRadius = testing::kOnePointRadius;

// alpha = 1 keeps the radius, so the estimate is the plain density tau / (pi R^2 N).
ProgressiveEstimate OnePointEstimate() { return testing::OnePointEstimate(1.0); }
using testing::OnePointBatch;

TEST(ErrorEstimateTest, UnknownUntilBothHalvesHavePhotonsAndDirectLight) {
    ProgressiveEstimate estimate = OnePointEstimate();
    EXPECT_FALSE(estimate.EstimateError().known);
    // After one epoch both halves have photons, but the direct light of odd epochs is missing.
    estimate.MergeEpoch(std::vector{OnePointBatch(estimate, 0, 2), OnePointBatch(estimate, 1, 1)});
    EXPECT_FALSE(estimate.EstimateError().known);
    estimate.MergeEpoch(std::vector{OnePointBatch(estimate, 0, 2), OnePointBatch(estimate, 1, 1)});
    EXPECT_TRUE(estimate.EstimateError().known);
}

TEST(ErrorEstimateTest, IsHalfTheDifferenceOfEqualHalves) {
    // Even batches carry flux 2, odd ones 1, over two epochs: each half has 2 batches, so
    // L_even = 4 / (pi R^2 2P), L_odd = 2 / (pi R^2 2P), the full estimate their mean, and its
    // standard error |L_even - L_odd| / 2 in every channel.
    ProgressiveEstimate estimate = OnePointEstimate();
    for (int epoch = 0; epoch < 2; ++epoch)
        estimate.MergeEpoch(
            std::vector{OnePointBatch(estimate, 0, 2), OnePointBatch(estimate, 1, 1)});
    const double area = kPiD * kRadius * kRadius;
    const double even = 4 / (area * 2 * kPhotons), odd = 2 / (area * 2 * kPhotons);
    const double value = (even + odd) / 2;
    ASSERT_NEAR(estimate.Resolve().pixels[0].x, value, 1e-6 * value);
    const ErrorEstimate error = estimate.EstimateError();
    const double expected = std::abs(even - odd) / 2;
    EXPECT_NEAR(error.rmse, expected, 1e-9 * expected);
    EXPECT_NEAR(error.rel_mse, expected * expected / (value * value + 0.01), 1e-9);
}

// Two epochs whose two batches each find 1000 photons of flux 3, `inner` of them within
// R / sqrt(2): equal halves, so no variance, only what the inner fraction says of the bias.
ProgressiveEstimate EqualHalves(uint32_t inner) {
    ProgressiveEstimate estimate = OnePointEstimate();
    for (int epoch = 0; epoch < 2; ++epoch)
        estimate.MergeEpoch(std::vector{OnePointBatch(estimate, 0, 3, 1000, inner),
                                        OnePointBatch(estimate, 1, 3, 1000, inner)});
    return estimate;
}

TEST(ErrorEstimateTest, PhotonsCrowdingTheInnerDiscShowAsBias) {
    // Equal halves (no variance), but three quarters of the photons fall in the inner disc of
    // half the area: the inner density is 1.5x the whole disc's, so L_inner = 1.5 L and the
    // bias 2 (L - L_inner) = -L, in each half alike.
    const ProgressiveEstimate estimate = EqualHalves(750);
    const double value = estimate.Resolve().pixels[0].x;
    const ErrorEstimate error = estimate.EstimateError();
    ASSERT_TRUE(error.known);
    EXPECT_NEAR(error.bias_rmse, value, 1e-6 * value);
    EXPECT_DOUBLE_EQ(error.rmse, error.bias_rmse) << "no variance between equal halves";
    // A flat density (half inside) claims no bias.
    EXPECT_EQ(EqualHalves(500).EstimateError().bias_rmse, 0.0);
}

TEST(ErrorEstimateTest, PhotonsAllInTheOuterRingClaimABiasOfAtMostTheEstimate) {
    // No photon within R / sqrt(2) (a caustic's focus in the disc's outer ring): the quadratic
    // model's 2 (L - L_inner) would be 2 L, but the radiance is not negative, so the estimate
    // can exceed it by L at most.
    const ProgressiveEstimate estimate = EqualHalves(0);
    const double value = estimate.Resolve().pixels[0].x;
    EXPECT_NEAR(estimate.EstimateError().bias_rmse, value, 1e-6 * value);
}

// Pixels of two hit points at one place, so that both discs find the same photons (as a
// pixel's hit points do while the radius is wider than the pixel): `pixels` pixels, alpha 1
// (no shrinking), two epochs of two batches in which each pixel's points find `photons`
// photons of flux 1 each, each within R / sqrt(2) with probability `inner`. Returns the
// estimate's bias part over the pixel value (every pixel's expected value is alike).
double SharedDiscsBias(uint32_t pixels, uint32_t photons, double inner) {
    CameraPassResult camera_pass;
    for (uint32_t p = 0; p < pixels; ++p)
        for (int twice = 0; twice < 2; ++twice)
            camera_pass.hit_points.push_back({Vec3(0.0f), Vec3(0, 0, 1), Rgb(1.0f), p});
    camera_pass.emission = Image(pixels, 1);
    EstimateSettings settings;
    settings.alpha = 1;
    settings.initial_radius = kRadius;
    settings.samples_per_pixel = 2;
    settings.layout = {kPhotons, 2};
    ProgressiveEstimate estimate(std::move(camera_pass), settings, {});
    std::mt19937_64 rng(7);
    std::binomial_distribution<uint32_t> inside(photons, inner);
    for (int epoch = 0; epoch < 2; ++epoch) {
        std::vector<BatchResult> batches;
        for (const BatchSpec& spec : estimate.EpochBatches()) {
            BatchResult& result = batches.emplace_back();
            result.spec = spec;
            for (uint32_t p = 0; p < pixels; ++p) {
                const uint32_t in = inside(rng);
                for (uint32_t i : {2 * p, 2 * p + 1}) {
                    result.tally.hit_point.push_back(i);
                    result.tally.photons.push_back(photons);
                    result.tally.inner_photons.push_back(in);
                    result.tally.flux.push_back(Rgb(float(photons)));
                }
            }
            result.samples.assign(spec.sample_end - spec.sample_begin, Rgb(0.0f));
            result.photons_emitted = kPhotons;
            testing::UniformEmission(estimate, result, 0.0f, Rgb(0.5f));  // half the samples each
        }
        estimate.MergeEpoch(batches);
    }
    const ErrorEstimate error = estimate.EstimateError();
    EXPECT_TRUE(error.known);
    return error.bias_rmse / estimate.Resolve().pixels[0].x;
}

TEST(ErrorEstimateTest, DiscsSharingPhotonsClaimNoBiasWhereTheDensityIsFlat) {
    // Each point's bias estimate 2 (1 - 2f) L has variance 16 L^2 f (1 - f) / N = 4 L^2 / N
    // (N = 400 photons). Squared and less that variance per point, a pixel's mean of two
    // equal estimates would claim a squared bias of 4 L^2 / N - 2 L^2 / N, a bias of
    // L sqrt(2 / N) = 0.071 L. The product of the halves' estimates has mean 0 and, over 2^16
    // pixels, a standard deviation of 8 L^2 / (N 256): four of them, clamped and rooted, are
    // 0.018 L.
    EXPECT_LT(SharedDiscsBias(1 << 16, 100, 0.5), 0.018);
    // A true bias is measured as it is: 60% inside gives 2 (1 - 1.2) L = -0.4 L.
    EXPECT_NEAR(SharedDiscsBias(1 << 12, 100, 0.6), 0.4, 0.02);
}

TEST(ErrorEstimateTest, AgreeingHalvesGiveZeroAndTheTargetEndsTheBudget) {
    ProgressiveEstimate estimate = OnePointEstimate();
    for (int epoch = 0; epoch < 2; ++epoch)
        estimate.MergeEpoch(
            std::vector{OnePointBatch(estimate, 0, 3), OnePointBatch(estimate, 1, 3)});
    const ErrorEstimate error = estimate.EstimateError();
    ASSERT_TRUE(error.known);
    EXPECT_EQ(error.rmse, 0.0);
    JobSpec spec;
    spec.target_error = 0.01;
    EXPECT_EQ(BudgetFraction(spec, 0, 0, 0, std::nullopt), 0.0)
        << "an unknown error spends none of the budget";
    EXPECT_DOUBLE_EQ(BudgetFraction(spec, 0, 0, 0, 0.02), 0.25)
        << "half the error needs four times the photons";
    EXPECT_EQ(BudgetFraction(spec, 0, 0, 0, 0.01), 1.0);
    EXPECT_EQ(BudgetFraction(spec, 0, 0, 0, error.RelativeError()), 1.0)
        << "no noise at all meets any target";
}

}  // namespace
}  // namespace pf
