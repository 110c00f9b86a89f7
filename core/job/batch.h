// The unit of work: a photon batch. A batch is a pure function of (scene, hit points, the
// epoch's radii, job seed, batch index) and returns a sparse tally. An epoch is a fixed,
// numbered range of batches; the estimate is updated once per epoch by merging its tallies in
// batch-index order, so the image for a seed and layout does not depend on who ran what.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "core/math/vec3.h"

namespace pf {

// An epoch's batches and their photons. 0 leaves a count to the job (ResolvedLayout,
// core/job/job_spec.h: it depends on the integrator and the film). The layout, not the thread
// count, fixes the image for a seed.
struct BatchLayout {
    uint32_t photons_per_batch = 0;  // in a full epoch
    uint32_t batches_per_epoch = 0;
    // Small epochs first, for an image soon: the first GrowingEpochs() epochs have fewer
    // photons a batch, each epoch twice the one before, the first at least this many photons
    // (and under twice as many); later epochs are full. 0, or PhotonsPerEpoch() or more: every
    // epoch is full. Left open (0) on a job, ResolvedLayout chooses.
    uint64_t first_epoch_photons = 0;

    // A full epoch's photons.
    uint64_t PhotonsPerEpoch() const { return uint64_t{photons_per_batch} * batches_per_epoch; }
    bool Resolved() const { return photons_per_batch > 0 && batches_per_epoch > 0; }
    // How many epochs grow before the first full one.
    uint32_t GrowingEpochs() const;
    // Epoch `epoch`'s photons a batch and in all.
    uint32_t PhotonsPerBatch(uint64_t epoch) const {
        const uint32_t growing = GrowingEpochs();
        return epoch >= growing ? photons_per_batch
                                : photons_per_batch >> (growing - static_cast<uint32_t>(epoch));
    }
    uint64_t PhotonsInEpoch(uint64_t epoch) const {
        return uint64_t{PhotonsPerBatch(epoch)} * batches_per_epoch;
    }
};

// ppm's defaults (and path's and pm's batch count): batches large enough that sorting a
// batch's deposits gives the gather cache locality (2^18 -> 2^19 photons: +14% end to end at
// 512x512), and epochs of 2^22 photons, a second or two on two cores, so radii shrink and
// progress shows often while the per-epoch grid rebuild stays a small share of the time.
inline constexpr uint32_t kDefaultPhotonsPerBatch = 1u << 19;
inline constexpr uint32_t kDefaultBatchesPerEpoch = 8;
// sppm's batches when left open: small, since its epochs are (one photon per camera sample).
inline constexpr uint32_t kSppmPhotonsPerBatch = 1u << 15;

// A batch runs as chunks of this many photons (the last may be shorter): a worker spreads a
// big batch over its threads, chunk by chunk, and sums the chunks' tallies in chunk order, so
// a batch's tally does not depend on the thread count. Big batches are how a farm keeps the
// coordinator's merge small (its cost is per tally entry, and a tally has at most one entry
// per hit point however many photons went into it). Part of what fixes the image for a seed.
inline constexpr uint32_t kPhotonsPerChunk = 1u << 19;

struct BatchSpec {
    uint64_t index = 0;  // global batch index: epoch * batches_per_epoch + batch_in_epoch
    uint64_t epoch = 0;
    uint32_t photons = 0;  // photon paths to emit
    // Each batch also takes one sample for each item of a slice: for the photon mappers a
    // direct-light sample per hit point, so the direct estimate is refined progressively and
    // shared out like the photons; for the integrators that sample pixels (path, pm) the
    // radiance of each pixel's camera samples, and then photons is 0.
    uint32_t sample_begin = 0, sample_end = 0;
};

// How many chunks `spec` runs as; a batch that renders pixels (no photons) counts as one, for
// leases: it runs its pixels in parallel.
inline uint32_t ChunkCount(const BatchSpec& spec) {
    return spec.photons == 0 ? 1 : (spec.photons + kPhotonsPerChunk - 1) / kPhotonsPerChunk;
}

// Batch `batch_in_epoch` of `epoch` for a job with `hit_point_count` hit points.
BatchSpec MakeBatchSpec(const BatchLayout& layout, uint64_t epoch, uint32_t batch_in_epoch,
                        uint32_t hit_point_count);

// The pixels whose emission batch `spec` samples for ppm, [first, second): those whose first
// slot of the epoch's pass (`slots_per_pixel` a pixel) lies in its direct-light slice, so the
// batches of an epoch share its pixels out, each once.
std::pair<uint64_t, uint64_t> SlicePixels(const BatchSpec& spec, uint64_t slots_per_pixel);

// Photon contributions of one batch, sorted by hit point index, one entry per hit point reached.
struct Tally {
    std::vector<uint32_t> hit_point;
    std::vector<uint32_t> photons;        // M: photons found within the hit point's radius
    std::vector<uint32_t> inner_photons;  // those of them within R / sqrt(2), for the bias estimate
    // Their raw photon flux (W x N_emitted), summed in float in photon order; the merge
    // multiplies it by the hit point's BSDF weight to give Phi_M. Float is exact enough
    // within a batch (see tally_accumulator.h) and halves the wire size.
    std::vector<Rgb> flux;

    size_t Size() const { return hit_point.size(); }
};

struct BatchResult {
    BatchSpec spec;
    Tally tally;
    std::vector<Rgb> samples;  // one per item of the spec's slice (BatchSpec::sample_begin)
    // ppm: the epoch's emission pass (EmissionCameraPass) at the pixels of the slice
    // (SlicePixels): the emission each sees, averaged over its samples, and the coverage of
    // their fixed hit points (CameraPassResult::coverage), in pixel order
    // (PixelHitPoints::ForEachOf). Empty for the other integrators.
    std::vector<Rgb> emission, coverage;
    uint64_t photons_emitted = 0;  // every path emitted, escaped or absorbed ones included
    uint64_t segments_traced = 0;  // photon rays cast, for throughput statistics
    // Photon paths and direct-light samples dropped because a value had become NaN or Inf
    // (a light whose power overflows single precision, say); should stay 0 (docs/numerics.md).
    uint64_t nonfinite_discarded = 0;
};

}  // namespace pf
