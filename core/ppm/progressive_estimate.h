// The coordinator-side state of one render: the fixed hit points and, per hit point, the
// progressive estimate (N, R, tau) and the running direct-light sum. Folds each epoch's batch
// results in batch-index order, one at a time as they become available, updates the
// estimate at the epoch's end and resolves the current image. Not thread-safe; its methods
// use the calling TBB arena for data-parallel loops, deterministically.
#pragma once

#include <cstdint>
#include <memory>
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

    std::span<const HitPoint> HitPoints() const { return *hit_points_; }
    // The same hit points, shared with whoever needs them past this object's life.
    std::shared_ptr<const std::vector<HitPoint>> SharedHitPoints() const { return hit_points_; }
    const PointEstimate& Point(size_t hit_point) const { return points_[hit_point]; }
    const EstimateSettings& Settings() const { return settings_; }
    uint64_t Epoch() const { return epoch_; }  // the next epoch to merge; also epochs merged
    uint64_t PhotonsEmitted() const { return photons_emitted_; }  // over the merged epochs

    // This epoch's squared search radii, one per hit point, for the photon pass.
    std::vector<float> SearchRadiusSq() const;
    // The batches of the current epoch, in batch-index order.
    std::vector<BatchSpec> EpochBatches() const;
    // Adds the next batch of the current epoch to the epoch's sums: batches must come in
    // batch-index order, so the sums are the same whoever ran them and whenever they arrived.
    void FoldBatch(const BatchResult& result);
    uint32_t BatchesFolded() const { return batches_folded_; }
    // Once every batch of the epoch is folded: updates N, R, tau and starts the next epoch.
    void FinishEpoch();
    // FoldBatch for each of results (results[j] the result of EpochBatches()[j]), then FinishEpoch.
    void MergeEpoch(std::span<const BatchResult> results);
    // The image as of the last merged epoch: emission + direct + tau / (pi R^2 N_emitted),
    // averaged over each pixel's k camera paths.
    Image Resolve() const;

private:
    std::shared_ptr<const std::vector<HitPoint>> hit_points_;
    Image emission_;
    EstimateSettings settings_;
    std::vector<PointEstimate> points_;
    std::vector<Rgbd> direct_sum_;  // sum of one direct-light sample per merged epoch
    uint64_t epoch_ = 0;
    uint64_t photons_emitted_ = 0;
    uint32_t batches_folded_ = 0;  // of the current epoch
    // The current epoch's sums (M and Phi_M per hit point) and direct samples, apart from the
    // merged state so that Resolve() between folds shows the last merged epoch exactly.
    std::vector<uint64_t> epoch_photons_;
    std::vector<Rgbd> epoch_flux_;
    std::vector<Rgb> epoch_direct_;
    uint64_t epoch_photons_emitted_ = 0;
};

}  // namespace pf
