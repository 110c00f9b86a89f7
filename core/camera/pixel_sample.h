// Where a pixel's camera samples go, the same for every integrator: a pixel's samples, their
// index counting over the whole run (in the even epochs, and apart in the odd: InEpoch), take
// their point under the pixel's filter, their point on the lens and any further stratified numbers
// from a scrambled (0,2)-sequence of that pixel (core/shared/sobol.h), keyed by (seed, pixel,
// index) alone. Every aligned run of 2^m of them is then stratified over the pixel and over the
// lens, so a pixel's integral of a sharp edge converges at the rate of stratified sampling
// across epochs, and an image is the same whoever traced which sample.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/geometry/ray.h"
#include "core/math/point2.h"
#include "core/sampling/rng.h"
#include "core/sampling/sampling.h"
#include "core/scene/camera.h"
#include "core/scene/pixel_filter.h"
#include "core/shared/sobol.h"

namespace pf {

struct Film {
    int width = 0, height = 0;
    int samples_per_pixel = 1;
    float Aspect() const { return static_cast<float>(width) / static_cast<float>(height); }
    uint64_t Pixels() const { return uint64_t(width) * uint64_t(height); }
};

// The stratified numbers of one camera sample, pair by pair: the first pair places it in the
// pixel, the second on the lens, later ones whatever the integrator stratifies next. Pair d
// of every sample of a sequence comes from one (0,2)-sequence, scrambled and shuffled by a
// hash of (seed, stream, sequence, d); pairs are independent of each other. Indices wrap at
// 2^32.
class PixelSampler {
public:
    PixelSampler(uint64_t seed, uint64_t stream, uint64_t sequence, uint64_t index)
        : seeds_(seed, stream, sequence), index_(static_cast<uint32_t>(index)) {}

    // Sample s of pixel p's k in epoch e. The even epochs' samples and the odd epochs' come
    // from two independent sequences of the pixel, each counting over its own epochs: each
    // half-image the error estimate compares (EstimateError) is then stratified in itself and
    // independent of the other, as the estimate assumes. Over one sequence the halves' errors
    // cancel each other, and their difference would claim twice the image's error.
    static PixelSampler InEpoch(uint64_t seed, uint64_t stream, uint64_t pixel, uint64_t epoch,
                                int k, int s) {
        return InEpochSequence(seed, stream, pixel, epoch,
                               (epoch >> 1) * uint64_t(k) + uint64_t(s));
    }
    // Sample `index` of the sequence of pixel p that epoch e's parity takes, for passes whose
    // samples a pixel change from epoch to epoch (EpochCameraSamples).
    static PixelSampler InEpochSequence(uint64_t seed, uint64_t stream, uint64_t pixel,
                                        uint64_t epoch, uint64_t index) {
        return PixelSampler(seed, stream, SequenceOf(pixel, epoch), index);
    }
    // Which of the sequences of (seed, stream) pixel p's samples in epoch e take.
    static constexpr uint64_t SequenceOf(uint64_t pixel, uint64_t epoch) {
        return 2 * pixel + (epoch & 1);
    }

    Point2 Next2D() {
        return gpu::SequenceSample2D(seeds_.Prefix(), index_, static_cast<uint32_t>(pair_++));
    }

private:
    SeedFamily seeds_;
    uint32_t index_;
    uint64_t pair_ = 0;
};

// A camera ray and the weight its radiance takes in its pixel's mean (the filter's sign where
// it has negative lobes, else 1).
struct CameraRay {
    Ray ray;
    float weight = 1.0f;
};

// The camera ray of pixel (x, y) through the sampler's first pair (its place under the
// pixel's filter, around the pixel's centre) and, only where the camera has a lens, its second
// (the point on the lens).
inline CameraRay PixelSampleRay(const Camera& camera, const Film& film, const FilterSampler& filter,
                                int x, int y, PixelSampler& sampler) {
    const FilterSample place = filter.Sample(sampler.Next2D());
    const float fx =
        (static_cast<float>(x) + 0.5f + place.offset.x) / static_cast<float>(film.width);
    const float fy =
        (static_cast<float>(y) + 0.5f + place.offset.y) / static_cast<float>(film.height);
    if (!camera.HasLens()) return {camera.GenerateRay(fx, fy, film.Aspect()), place.weight};
    const Point2 lens = sampler.Next2D();
    return {camera.GenerateRay(fx, fy, film.Aspect(), SampleUniformDisk(lens.x, lens.y)),
            place.weight};
}

}  // namespace pf
