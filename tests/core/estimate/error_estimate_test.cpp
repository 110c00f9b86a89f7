// The error estimated from the even and odd half-estimates (ProgressiveEstimate::EstimateError)
// on hand-made tallies whose answer is worked out below.
#include <gtest/gtest.h>

#include <cmath>

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

TEST(ErrorEstimateTest, PhotonsCrowdingTheInnerDiscShowAsBias) {
    // Equal halves (no variance), but three quarters of the photons fall in the inner disc of
    // half the area: the inner density is 1.5x the whole disc's, so L_inner = 1.5 L and the
    // bias 2 (L - L_inner) = -L, less the little its own noise claims (4000 photons).
    ProgressiveEstimate estimate = OnePointEstimate();
    for (int epoch = 0; epoch < 2; ++epoch)
        estimate.MergeEpoch(std::vector{OnePointBatch(estimate, 0, 3, 1000, 750),
                                        OnePointBatch(estimate, 1, 3, 1000, 750)});
    const double value = estimate.Resolve().pixels[0].x;
    const ErrorEstimate error = estimate.EstimateError();
    ASSERT_TRUE(error.known);
    EXPECT_GT(error.bias_rmse, 0.99 * value);
    EXPECT_LE(error.bias_rmse, value);
    EXPECT_DOUBLE_EQ(error.rmse, error.bias_rmse) << "no variance between equal halves";
    // A flat density (half inside) claims no bias: the noise of the inner fraction outweighs
    // the nothing it shows.
    ProgressiveEstimate flat = OnePointEstimate();
    for (int epoch = 0; epoch < 2; ++epoch)
        flat.MergeEpoch(std::vector{OnePointBatch(flat, 0, 3, 1000, 500),
                                    OnePointBatch(flat, 1, 3, 1000, 500)});
    EXPECT_EQ(flat.EstimateError().bias_rmse, 0.0);
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
