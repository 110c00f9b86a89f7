// The coordinator-side state of one render: the fixed hit points and, per hit point, the
// progressive estimate (N, R, tau) and the running direct-light sum. Merges whole epochs of
// batch results in batch-index order and resolves the current image. Not thread-safe; its
// methods use the calling TBB arena for data-parallel loops, deterministically.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/film/image.h"
#include "core/ppm/batch.h"
#include "core/ppm/camera_pass.h"
#include "core/ppm/estimator.h"

namespace pf {

struct EstimateSettings {
    double alpha = kDefaultAlpha;  // radius reduction ratio, (0, 1]
    double initial_radius = 0;     // R0, world units, > 0
    int samples_per_pixel = 4;     // k: camera paths per pixel (the resolve divides by it)
    BatchLayout layout;
};

class ProgressiveEstimate {
public:
    ProgressiveEstimate(CameraPassResult camera_pass, const EstimateSettings& settings);

    std::span<const HitPoint> HitPoints() const { return hit_points_; }
    const PointEstimate& Point(size_t hit_point) const { return points_[hit_point]; }
    const EstimateSettings& Settings() const { return settings_; }
    uint64_t Epoch() const { return epoch_; }  // the next epoch to merge; also epochs merged
    uint64_t PhotonsEmitted() const { return photons_emitted_; }

    // This epoch's squared search radii, one per hit point, for the photon pass.
    std::vector<float> SearchRadiusSq() const;
    // The batches of the current epoch, in batch-index order.
    std::vector<BatchSpec> EpochBatches() const;
    // Folds in the current epoch: results[j] must be the result of EpochBatches()[j].
    void MergeEpoch(std::span<const BatchResult> results);
    // The image as of the last merged epoch: emission + direct + tau / (pi R^2 N_emitted),
    // averaged over each pixel's k camera paths.
    Image Resolve() const;

private:
    std::vector<HitPoint> hit_points_;
    Image emission_;
    EstimateSettings settings_;
    std::vector<PointEstimate> points_;
    std::vector<Rgbd> direct_sum_;  // sum of one direct-light sample per merged epoch
    uint64_t epoch_ = 0;
    uint64_t photons_emitted_ = 0;
    // Scratch for MergeEpoch, kept to avoid reallocating per epoch.
    std::vector<uint64_t> epoch_photons_;
    std::vector<Rgbd> epoch_flux_;
};

}  // namespace pf
