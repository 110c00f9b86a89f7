// What the coordinator folds a job's batch results into, whatever the integrator: epochs of
// batches folded in batch-index order, an image resolved from the merged epochs, and its
// error estimated without a reference. ProgressiveEstimate (ppm, sppm) keeps N, R, tau per
// hit point; PixelEstimate (path, pm) averages pixel samples. Not thread-safe; methods use
// the calling TBB arena for data-parallel loops, deterministically.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"
#include "core/film/image.h"
#include "core/job/batch.h"
#include "core/job/gather_regions.h"
#include "core/job/hit_point.h"
#include "core/job/integrator.h"
#include "core/util/byte_stream.h"

namespace pf {

// The error of an image estimated without a reference, from two half-estimates: one of the
// even-numbered batches (or epochs), one of the odd. Both share the radii, so their
// difference is the noise of the image, not its bias. Per channel and pixel, the variance of
// the full estimate is (L_even - L_odd)^2 N_even N_odd / N^2. The photon mappers add a bias
// estimate (ProgressiveEstimate::EstimateError).
struct ErrorEstimate {
    bool known = false;    // false until both halves have samples
    double rmse = 0;       // root mean squared error over pixels and channels
    double rel_mse = 0;    // mean of squared error / (value^2 + 0.01), as the reference metrics
    double bias_rmse = 0;  // the part of rmse that is bias: rmse^2 = variance + bias_rmse^2
    double RelativeError() const { return std::sqrt(rel_mse); }
};

// Whether a saved state holds the estimate's fixed part (Estimate::SaveFixed) or leaves it to
// be kept apart, once, and given back to LoadEstimate.
enum class FixedPart { kIncluded, kApart };

class Estimate {
public:
    virtual ~Estimate() = default;

    virtual Integrator Kind() const = 0;
    // How many items a batch's sample slice indexes (hit points or pixels).
    virtual uint64_t ItemCount() const = 0;
    virtual uint64_t Epoch() const = 0;           // the next epoch to merge; also epochs merged
    virtual uint64_t PhotonsEmitted() const = 0;  // over the merged epochs (pm: its maps')
    // Camera samples taken over the merged epochs (ppm: the hit points' paths, once).
    virtual uint64_t CameraSamples() const = 0;
    // Paths and samples the batches dropped for NaN or Inf over the merged epochs; should be 0.
    virtual uint64_t NonfiniteDiscarded() const = 0;
    // Whether any light has reached the image through the merged epochs, beyond emission seen
    // directly: false for a light shut inside a closed object.
    virtual bool LightReachedAnything() const = 0;
    // The initial search radius R0 (world units), 0 where batches gather at no hit points.
    virtual double InitialRadius() const = 0;
    // The hit points the current epoch's batches gather at (none for path and pm), shared with
    // whoever needs them past this object's life.
    virtual std::shared_ptr<const std::vector<HitPoint>> SharedHitPoints() const = 0;

    // This epoch's gather regions, one per hit point; empty where batches gather at no hit
    // points (path, pm).
    virtual GatherRegions Regions() const = 0;
    // The batches of the current epoch, in batch-index order.
    virtual std::vector<BatchSpec> EpochBatches() const = 0;
    // How many emission and coverage values the result of batch `spec` brings
    // (BatchResult::emission, coverage): ppm's share of the epoch's emission pass, none for the
    // others. Reads only what stays as it is over the estimate's life, so may be called while
    // another thread folds.
    virtual std::pair<uint64_t, uint64_t> EmissionShape(const BatchSpec& spec) const {
        (void)spec;
        return {0, 0};
    }
    // Adds the next batch of the current epoch: batches must come in batch-index order, so the
    // sums are the same whoever ran them and whenever they arrived.
    virtual void FoldBatch(const BatchResult& result) = 0;
    virtual uint32_t BatchesFolded() const = 0;  // of the current epoch
    // Once every batch of the epoch is folded: merges it and starts the next epoch.
    virtual void FinishEpoch() = 0;
    // The image as of the last merged epoch.
    virtual Image Resolve() const = 0;
    // The error of Resolve()'s image.
    virtual ErrorEstimate EstimateError() const = 0;

    // The whole state, at an epoch's end or between folds, for a checkpoint; LoadEstimate
    // restores it bit for bit. Its arrays are packed: byte planes or the values as they are,
    // whichever is smaller, compressed with zstd (core/util/packed_arrays.h). With
    // FixedPart::kApart it leaves out what SaveFixed saves.
    virtual void Save(ByteWriter& out, FixedPart fixed) const = 0;
    void Save(ByteWriter& out) const { Save(out, FixedPart::kIncluded); }
    // The part of the state that never changes over the estimate's life, for a checkpoint to
    // keep once per job rather than with every state: a ppm estimate's hit points (sppm
    // traces its anew every epoch; path and pm have none). False, and nothing written, where
    // there is no such part.
    virtual bool SaveFixed(ByteWriter& out) const {
        (void)out;
        return false;
    }

    // FoldBatch for each of results (results[j] the result of EpochBatches()[j]), then FinishEpoch.
    void MergeEpoch(std::span<const BatchResult> results);
};

// An estimate as Save left it, of whichever kind; `fixed`: what SaveFixed wrote, for a state
// saved with FixedPart::kApart, else null. DATA_LOSS naming what is wrong when the bytes
// cannot be one, or `fixed` is missing, not this state's, or given to a state that holds its own.
absl::StatusOr<std::unique_ptr<Estimate>> LoadEstimate(ByteReader& in, ByteReader* fixed = nullptr);

// The half-estimate variance of one value per pixel and channel: `value` the full estimate,
// `difference` L_even - L_odd, scaled by `variance_scale` = N_even N_odd / N^2. Adds to the
// sums of squared error and relative squared error.
inline void AddHalfVariance(double value, double difference, double variance_scale, double* squared,
                            double* relative) {
    const double variance = difference * difference * variance_scale;
    *squared += variance;
    *relative += variance / (value * value + 0.01);
}

}  // namespace pf
