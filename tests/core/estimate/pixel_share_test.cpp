// ppm's fixed hit points count in their pixel by the share of each epoch's fresh camera samples
// they stand for (CameraPassResult::coverage), and the error estimate sees that share's noise
// as it sees the emission's.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <vector>

#include "core/estimate/progressive_estimate.h"
#include "core/job/job_spec.h"

namespace pf {
namespace {

constexpr uint32_t kSharePhotons = 1000;  // emitted per batch
constexpr double kShareRadius = 0.5;

// Weights of an epoch's samples that a hit point stands for, averaged over the samples, as an
// epoch's emission pass gives them (BatchResult::coverage).
using Coverage = std::function<Rgb(uint64_t epoch)>;

// One pixel of two fixed hit points: A, weight (0.4, 0.4, 0.4), and B, weight 0.5; alpha 1, so
// radii hold.
ProgressiveEstimate TwoPointPixel() {
    CameraPassResult camera_pass;
    camera_pass.hit_points = {HitPoint{Vec3(0.0f), Vec3(0, 0, 1), Rgb(0.4f), 0},
                              HitPoint{Vec3(1.0f, 0, 0), Vec3(1, 0, 0), Rgb(0.5f), 0}};
    camera_pass.footprint = {0.01f, 0.01f};
    camera_pass.emission = Image(1, 1);
    EstimateSettings settings;
    settings.alpha = 1;
    settings.initial_radius = kShareRadius;
    settings.samples_per_pixel = 2;
    settings.layout = {kSharePhotons, 2};
    return ProgressiveEstimate(std::move(camera_pass), settings, {});
}

// Merges an epoch whose two batches each bring A the flux 3 and B the flux 1 (W x N_emitted),
// in 4 photons, 2 within R / sqrt(2) (a flat density: no bias), and whose samples' hits stand
// for A with the weights `on_a(epoch)` and for B with `on_b(epoch)`.
void MergeEpoch(ProgressiveEstimate& estimate, const Coverage& on_a, const Coverage& on_b) {
    std::vector<BatchResult> batches;
    for (const BatchSpec& spec : estimate.EpochBatches()) {
        BatchResult& result = batches.emplace_back();
        result.spec = spec;
        result.tally.hit_point = {0, 1};
        result.tally.photons = {4, 4};
        result.tally.inner_photons = {2, 2};
        result.tally.flux = {Rgb(3.0f), Rgb(1.0f)};
        result.samples.assign(spec.sample_end - spec.sample_begin, Rgb(0.0f));
        result.photons_emitted = kSharePhotons;
        // The batch whose slice holds the pixel brings its emission pass (A, B in pixel order).
        if (estimate.EmissionShape(spec).first == 1) {
            result.emission = {Rgb(0.0f)};
            result.coverage = {on_a(spec.epoch), on_b(spec.epoch)};
        }
    }
    estimate.MergeEpoch(batches);
}

// The unweighted densities tau / (w pi R^2 N) at A and B (the same after any number of
// epochs): each hit point's radiance per unit of the weight of the samples it stands for.
const double kDensityA = 3.0 / (kPiD * kShareRadius * kShareRadius * kSharePhotons);
const double kDensityB = 1.0 / (kPiD * kShareRadius * kShareRadius * kSharePhotons);

TEST(PixelShareTest, HitPointsCountByTheWeightOfTheSamplesTheyStandFor) {
    // Three quarters of the samples land near A, on a texel coloured (0.8, 0.4, 0.2) where A's
    // is grey 0.4; a quarter near B, with B's own weight. Fixed hit points alone gave each half.
    ProgressiveEstimate estimate = TwoPointPixel();
    for (int epoch = 0; epoch < 3; ++epoch)
        MergeEpoch(
            estimate, [](uint64_t) { return Rgb(0.8f, 0.4f, 0.2f) * 0.75f; },
            [](uint64_t) { return Rgb(0.5f) * 0.25f; });
    const Rgb pixel = estimate.Resolve().pixels[0];
    const Rgb texel(0.8f, 0.4f, 0.2f);
    for (int c = 0; c < 3; ++c) {
        const double expected = 0.75 * texel[c] * kDensityA + 0.25 * 0.5 * kDensityB;
        EXPECT_NEAR(pixel[c], expected, 1e-6 * expected) << "channel " << c;
    }
}

TEST(PixelShareTest, TheErrorEstimateSeesTheSharesNoise) {
    // Even epochs' samples land on A nine times in ten, odd ones once in ten; the photons'
    // halves agree, so the error is the shares' alone: half the difference between the pixel
    // the even epochs' samples give and the odd ones'.
    ProgressiveEstimate estimate = TwoPointPixel();
    for (int epoch = 0; epoch < 4; ++epoch)
        MergeEpoch(
            estimate, [](uint64_t e) { return Rgb(0.4f) * (e % 2 == 0 ? 0.9f : 0.1f); },
            [](uint64_t e) { return Rgb(0.5f) * (e % 2 == 0 ? 0.1f : 0.9f); });
    const ErrorEstimate error = estimate.EstimateError();
    ASSERT_TRUE(error.known);
    const double even = 0.4 * 0.9 * kDensityA + 0.5 * 0.1 * kDensityB;
    const double odd = 0.4 * 0.1 * kDensityA + 0.5 * 0.9 * kDensityB;
    EXPECT_NEAR(error.rmse, std::abs(even - odd) / 2, 1e-6 * error.rmse);
    EXPECT_NEAR(estimate.Resolve().pixels[0].x, (even + odd) / 2, 1e-6 * (even + odd));
}

}  // namespace
}  // namespace pf
