// One pixel seen through one hit point, fed hand-made tallies: the estimate the error and
// balanced-alpha tests work their answers out on.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>

#include "core/estimate/progressive_estimate.h"

namespace pf::testing {

inline constexpr uint32_t kOnePointPhotons = 1000;  // emitted per batch
inline constexpr double kOnePointRadius = 0.5;

// One hit point of weight 1 in a 1x1 image, R0 kOnePointRadius, by default two batches an
// epoch of kOnePointPhotons each. The epochs' passes have one slot a camera sample.
inline ProgressiveEstimate OnePointEstimate(double alpha, bool balanced = false,
                                            const BatchLayout& layout = {kOnePointPhotons, 2}) {
    CameraPassResult camera_pass;
    camera_pass.hit_points = {HitPoint{Vec3(0.0f), Vec3(0, 0, 1), Rgb(1.0f), 0}};
    camera_pass.footprint = {0.01f};
    camera_pass.emission = Image(1, 1);
    EstimateSettings settings;
    settings.alpha = alpha;
    settings.balanced = balanced;
    settings.initial_radius = kOnePointRadius;
    settings.samples_per_pixel = 1;
    settings.layout = layout;
    return ProgressiveEstimate(std::move(camera_pass), settings, {});
}

// The epoch's emission pass as the batch of `result.spec` brings it (BatchResult::emission,
// coverage): `emission` at each of its pixels, `coverage` at each of their hit points (by
// default every camera sample of a pixel stands for each, at weight 1).
inline void UniformEmission(const Estimate& estimate, BatchResult& result, float emission,
                            Rgb coverage = Rgb(1.0f)) {
    const auto [pixels, covered] = estimate.EmissionShape(result.spec);
    result.emission.assign(pixels, Rgb(emission));
    result.coverage.assign(covered, coverage);
}

// Batch `batch_in_epoch` of the estimate's epoch, whose one tally entry carries `flux`
// (W x N_emitted) in `photons` photons, `inner` of them within R / sqrt(2) (by default half of
// them: a flat density, no bias).
inline BatchResult OnePointBatch(const ProgressiveEstimate& estimate, uint32_t batch_in_epoch,
                                 float flux, uint32_t photons = 2, uint32_t inner = 1) {
    BatchResult result;
    result.spec = MakeBatchSpec(estimate.Settings().layout, estimate.Epoch(), batch_in_epoch, 1);
    result.tally.hit_point = {0};
    result.tally.photons = {photons};
    result.tally.inner_photons = {inner};
    result.tally.flux = {Rgb(flux)};
    result.samples.assign(result.spec.sample_end - result.spec.sample_begin, Rgb(0.0f));
    result.photons_emitted = kOnePointPhotons;
    UniformEmission(estimate, result, 0.0f);
    return result;
}

}  // namespace pf::testing
