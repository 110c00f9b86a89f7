// Batches of the integrators that render pixels (path, pm): each takes every pixel of its
// slice `samples_per_pixel` times and returns the mean per pixel. A pixel's samples in an epoch
// continue its earlier epochs' (PixelSampler::InEpoch: stratified across epochs), their paths
// drawing one after another from a stream seeded by (seed, epoch, pixel) alone, so a batch is a
// pure function of its spec, whoever runs it; the Vulkan backend (pixel_trace.comp, a thread a
// pixel) draws from the same streams in the same order.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "core/camera/pixel_sample.h"
#include "core/geometry/ray.h"
#include "core/job/batch.h"
#include "core/sampling/rng.h"
#include "core/scene/camera.h"

namespace pf {

// The radiance arriving along a camera ray, one sample; called from many threads at once.
using RadianceFunction = std::function<Rgb(const Ray& ray, Rng& rng)>;

// The streams of epoch `epoch`'s pixel samples: pixel p's samples draw from
// Rng(PixelSeeds(seed, epoch).Seed(p)), in order.
SeedFamily PixelSeeds(uint64_t seed, uint64_t epoch);

// Adds a camera sample to its pixel's sum, or counts it in `discarded` where it is NaN or Inf
// (it then counts as black).
inline void AddPixelSample(const Rgb& sample, Rgb& sum, uint64_t& discarded) {
    if (IsFinite(sample))
        sum += sample;
    else
        ++discarded;
}

// Sample s of pixel p's camera ray in epoch `epoch`, for a job of `seed`.
CameraRay PixelBatchRay(const Camera& camera, const Film& film, const FilterSampler& filter,
                        uint64_t seed, uint64_t epoch, uint32_t pixel, int s);

// Runs the batches on the calling TBB arena, pixels in parallel; results in the order of
// `specs`. A sample that comes out NaN or Inf counts as black and is counted in
// nonfinite_discarded.
std::vector<BatchResult> RunPixelBatches(const Camera& camera, const Film& film, uint64_t seed,
                                         std::span<const BatchSpec> specs,
                                         const RadianceFunction& radiance);

}  // namespace pf
