// Balanced radius reduction (EstimateSettings::balanced): each epoch's alpha chosen from the
// estimate's own bias and noise, on hand-made tallies whose answer is worked out below.
#include <gtest/gtest.h>

#include <vector>

#include "core/estimate/progressive_estimate.h"
#include "core/job/job_spec.h"
#include "tests/core/estimate/one_point_estimate.h"

namespace pf {
namespace {

ProgressiveEstimate OnePointEstimate(bool balanced) {
    return testing::OnePointEstimate(kDefaultAlpha, balanced);
}
BatchResult Batch(const ProgressiveEstimate& estimate, uint32_t batch_in_epoch, float flux,
                  uint32_t photons, uint32_t inner) {
    return testing::OnePointBatch(estimate, batch_in_epoch, flux, photons, inner);
}

// Merges an epoch of the two batches and returns the ratio it shrank R^2 by.
double MergeAndShrink(ProgressiveEstimate& estimate, const BatchResult& even,
                      const BatchResult& odd) {
    const double before = estimate.Point(0).radius_sq;
    estimate.MergeEpoch(std::vector{even, odd});
    return estimate.Point(0).radius_sq / before;
}

// R^2's ratio for an epoch of `m` photons at a point that had `n` (PPM's rule).
double PpmRatio(double n, double m, double alpha) { return (n + alpha * m) / (n + m); }

TEST(BalancedAlphaTest, FlatDensityWithNoiseShrinksAtTheSlowestRatio) {
    // Half of every epoch's photons fall in the inner disc (a flat density: no bias) and the
    // halves differ (noise): the radius should hold as well as it can while staying
    // consistent, kBalancedAlphaMost. The first two epochs have no error estimate yet (it needs
    // an odd epoch's camera samples): the settings' 2/3.
    ProgressiveEstimate estimate = OnePointEstimate(true);
    double n = 0;
    for (int epoch = 0; epoch < 4; ++epoch) {
        const double expected_alpha = epoch < 2 ? kDefaultAlpha : kBalancedAlphaMost;
        const double ratio = MergeAndShrink(estimate, Batch(estimate, 0, 3, 400, 200),
                                            Batch(estimate, 1, 1, 400, 200));
        EXPECT_NEAR(ratio, PpmRatio(n, 800, expected_alpha), 1e-12) << "epoch " << epoch;
        EXPECT_NEAR(estimate.Point(0).photon_count, n + expected_alpha * 800, 1e-9);
        n = estimate.Point(0).photon_count;
    }
}

TEST(BalancedAlphaTest, BiasWithoutNoiseShrinksAtTheFastestRatio) {
    // Equal halves (no noise), three quarters of the photons in the inner disc of half the
    // area (bias, ErrorEstimateTest): the radius should shrink as fast as it may.
    ProgressiveEstimate estimate = OnePointEstimate(true);
    double n = 0;
    for (int epoch = 0; epoch < 4; ++epoch) {
        const double expected_alpha = epoch < 2 ? kDefaultAlpha : kBalancedAlphaLeast;
        const double ratio = MergeAndShrink(estimate, Batch(estimate, 0, 2, 2000, 1500),
                                            Batch(estimate, 1, 2, 2000, 1500));
        EXPECT_NEAR(ratio, PpmRatio(n, 4000, expected_alpha), 1e-12) << "epoch " << epoch;
        n = estimate.Point(0).photon_count;
    }
}

TEST(BalancedAlphaTest, BiasAgainstNoiseLiesBetweenAndMovesWithTheirBalance) {
    // Both: the ratio lies strictly between the bounds, and more bias for the same noise
    // shrinks faster.
    // Inner fractions of 0.52 and 0.53 against halves 3 : 2 give r of about 0.3 and 0.7.
    const auto third_epoch_ratio = [](uint32_t inner) {
        ProgressiveEstimate estimate = OnePointEstimate(true);
        for (int epoch = 0; epoch < 2; ++epoch)
            estimate.MergeEpoch(std::vector{Batch(estimate, 0, 3, 2000, inner),
                                            Batch(estimate, 1, 2, 2000, inner)});
        const double n = estimate.Point(0).photon_count;
        const double ratio = MergeAndShrink(estimate, Batch(estimate, 0, 3, 2000, inner),
                                            Batch(estimate, 1, 2, 2000, inner));
        return std::pair{ratio, n};
    };
    const auto [some_bias, n] = third_epoch_ratio(1040);
    EXPECT_LT(some_bias, PpmRatio(n, 4000, kBalancedAlphaMost));
    EXPECT_GT(some_bias, PpmRatio(n, 4000, kBalancedAlphaLeast));
    const double more_bias = third_epoch_ratio(1060).first;
    EXPECT_LT(more_bias, some_bias);
}

TEST(BalancedAlphaTest, AFixedAlphaIsKeptWhateverTheError) {
    ProgressiveEstimate estimate = OnePointEstimate(false);
    double n = 0;
    for (int epoch = 0; epoch < 3; ++epoch) {
        const double ratio = MergeAndShrink(estimate, Batch(estimate, 0, 2, 2000, 1500),
                                            Batch(estimate, 1, 2, 2000, 1500));
        EXPECT_NEAR(ratio, PpmRatio(n, 4000, kDefaultAlpha), 1e-12);
        n = estimate.Point(0).photon_count;
    }
}

TEST(BalancedAlphaTest, JobsLeaveAlphaBalancedUnlessGiven) {
    EXPECT_EQ(JobSpec{}.alpha, 0);
    JobSpec spec;
    spec.until_cancelled = true;
    EXPECT_TRUE(CheckJobSpec(spec, SettingNames::kFields).ok());
    spec.alpha = 1e-9;
    EXPECT_TRUE(CheckJobSpec(spec, SettingNames::kFields).ok());
    for (double bad : {-0.5, 1.5}) {
        spec.alpha = bad;
        EXPECT_FALSE(CheckJobSpec(spec, SettingNames::kFields).ok()) << bad;
    }
}

}  // namespace
}  // namespace pf
