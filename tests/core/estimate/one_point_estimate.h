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
// epoch of kOnePointPhotons each. The epochs' passes have one slot and see `emission(epoch)`
// (none without it), and every camera sample the hit point.
inline ProgressiveEstimate OnePointEstimate(double alpha, bool balanced = false,
                                            const BatchLayout& layout = {kOnePointPhotons, 2},
                                            std::function<float(uint64_t)> emission = nullptr) {
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
    return ProgressiveEstimate(std::move(camera_pass), settings,
                               [emission = std::move(emission)](
                                   uint64_t epoch, const std::shared_ptr<const PixelHitPoints>&) {
                                   CameraPassResult pass;
                                   pass.emission = Image(1, 1);
                                   if (emission) pass.emission.pixels[0] = Rgb(emission(epoch));
                                   pass.coverage = {Rgb(1.0f)};  // every sample sees it
                                   return pass;
                               });
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
    return result;
}

}  // namespace pf::testing
