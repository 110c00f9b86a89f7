// Small epochs first (BatchLayout::first_epoch_photons) in the progressive estimate: the growing
// epochs are one pass for the radii, and emission and direct light are weighed by the camera
// samples each epoch took. Hand-made batches whose answers are worked out below.
#include <gtest/gtest.h>

#include <cmath>

#include "core/estimate/progressive_estimate.h"
#include "core/job/job_spec.h"
#include "tests/core/estimate/one_point_estimate.h"

namespace pf {
namespace {

constexpr double kGrowingRadius = testing::kOnePointRadius;

// One pixel seen through one hit point of weight 1.
ProgressiveEstimate OnePoint(const BatchLayout& layout, double alpha) {
    return testing::OnePointEstimate(alpha, false, layout);
}

// The current epoch's batches, each with `found` photons at the hit point (flux 1 each),
// `direct` in every direct-light slot, and the emission pass seeing `emission`.
std::vector<BatchResult> Epoch(const ProgressiveEstimate& estimate, uint32_t found, float direct,
                               float emission = 0.0f) {
    std::vector<BatchResult> results;
    for (const BatchSpec& spec : estimate.EpochBatches()) {
        BatchResult result;
        result.spec = spec;
        if (found > 0) {
            result.tally.hit_point = {0};
            result.tally.photons = {found};
            result.tally.inner_photons = {found / 2};
            result.tally.flux = {Rgb(float(found))};
        }
        result.samples.assign(spec.sample_end - spec.sample_begin, Rgb(direct));
        result.photons_emitted = spec.photons;
        testing::UniformEmission(estimate, result, emission);
        results.push_back(std::move(result));
    }
    return results;
}

TEST(GrowingEpochsTest, RadiiHoldThroughTheGrowingEpochsAndTheLastShrinksThemAsAFirstPass) {
    // 1000 photons a batch, 2 batches; from 250: epochs of 250, 500, 1000, then 2000.
    const BatchLayout layout{1000, 2, 250};
    ASSERT_EQ(layout.GrowingEpochs(), 3u);
    const double alpha = 2.0 / 3.0;
    ProgressiveEstimate estimate = OnePoint(layout, alpha);
    const double r0_sq = kGrowingRadius * kGrowingRadius;
    double found = 0;
    for (uint32_t epoch = 0; epoch < 2; ++epoch) {
        estimate.MergeEpoch(Epoch(estimate, 3 + epoch, 0.0f));
        found += 2 * (3 + epoch);
        EXPECT_EQ(estimate.Point(0).radius_sq, r0_sq) << "epoch " << epoch;
        EXPECT_EQ(estimate.Point(0).photon_count, found);  // every photon kept
    }
    // The last growing epoch: all the pass's photons, shrunk by alpha as a first pass is.
    estimate.MergeEpoch(Epoch(estimate, 5, 0.0f));
    found += 10;
    EXPECT_DOUBLE_EQ(estimate.Point(0).radius_sq, alpha * r0_sq);
    EXPECT_DOUBLE_EQ(estimate.Point(0).photon_count, alpha * found);
    EXPECT_DOUBLE_EQ(estimate.Point(0).flux.x, alpha * found);  // tau' = (tau + Phi) R'^2 / R^2
    // A full epoch: the ordinary update.
    const PointEstimate before = estimate.Point(0);
    estimate.MergeEpoch(Epoch(estimate, 7, 0.0f));
    const PointEstimate expected = UpdateEstimate(before, 14, Rgbd(14.0), alpha);
    EXPECT_DOUBLE_EQ(estimate.Point(0).radius_sq, expected.radius_sq);
    EXPECT_DOUBLE_EQ(estimate.Point(0).photon_count, expected.photon_count);
    // The density estimate stays the photons' over the area of their disc.
    EXPECT_EQ(estimate.PhotonsEmitted(), 250u + 500 + 1000 + 2000);
}

TEST(GrowingEpochsTest, EmissionAndDirectLightAreMeanedOverCameraSamplesNotEpochs) {
    // One pixel, epochs of 8, 16, 32, 64 photons: 4, 8, 16, 32 camera samples a pixel (one
    // per two photons).
    const BatchLayout layout{64, 1, 8};
    ASSERT_EQ(layout.GrowingEpochs(), 3u);
    const int samples[] = {4, 8, 16, 32, 32};
    ProgressiveEstimate estimate = OnePoint(layout, 2.0 / 3.0);
    double weighted = 0, count = 0;
    uint64_t traced = 1;  // the fixed pass's k = 1
    for (uint64_t epoch = 0; epoch < 5; ++epoch) {
        ASSERT_EQ(estimate.ItemCount(), uint64_t(samples[epoch])) << epoch;
        const float direct = 0.5f * float(epoch);
        estimate.MergeEpoch(Epoch(estimate, 0, direct, float(epoch + 1)));
        weighted += samples[epoch] * (double(epoch + 1) + direct);
        count += samples[epoch];
        traced += uint64_t(samples[epoch]);
        EXPECT_NEAR(estimate.Resolve().pixels[0].x, weighted / count, 1e-6) << epoch;
        EXPECT_EQ(estimate.CameraSamples(), traced);
    }
}

}  // namespace
}  // namespace pf
