// Pixel batches, in parallel over pixels.
#include "core/render/pixel_pass.h"

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include "core/util/check.h"

namespace pf {

namespace {

constexpr uint64_t kPixelSampleStream = 0x736f626f6cull;

}  // namespace

SeedFamily PixelSeeds(uint64_t seed, uint64_t epoch) {
    constexpr uint64_t kPixelStream = 0x706978656c73ull;
    return SeedFamily(seed, kPixelStream, epoch);
}

CameraRay PixelBatchRay(const Camera& camera, const Film& film, const FilterSampler& filter,
                        uint64_t seed, uint64_t epoch, uint32_t pixel, int s) {
    PixelSampler sampler =
        PixelSampler::InEpoch(seed, kPixelSampleStream, pixel, epoch, film.samples_per_pixel, s);
    return PixelSampleRay(camera, film, filter, static_cast<int>(pixel % film.width),
                          static_cast<int>(pixel / film.width), sampler);
}

std::vector<BatchResult> RunPixelBatches(const Camera& camera, const Film& film, uint64_t seed,
                                         std::span<const BatchSpec> specs,
                                         const RadianceFunction& radiance) {
    std::vector<BatchResult> results(specs.size());
    const float inverse_spp = 1.0f / static_cast<float>(film.samples_per_pixel);
    const FilterSampler filter(camera.filter);
    for (size_t b = 0; b < specs.size(); ++b) {
        const BatchSpec& spec = specs[b];
        PF_CHECK(spec.sample_begin <= spec.sample_end && spec.sample_end <= film.Pixels());
        BatchResult& result = results[b];
        result.spec = spec;
        result.samples.resize(spec.sample_end - spec.sample_begin);
        const SeedFamily seeds = PixelSeeds(seed, spec.epoch);
        tbb::combinable<uint64_t> discarded([] { return uint64_t{0}; });
        tbb::parallel_for(tbb::blocked_range<uint32_t>(spec.sample_begin, spec.sample_end, 16),
                          [&](const tbb::blocked_range<uint32_t>& pixels) {
                              for (uint32_t pixel = pixels.begin(); pixel < pixels.end(); ++pixel) {
                                  Rng rng(seeds.Seed(pixel));
                                  Rgb sum(0.0f);
                                  for (int s = 0; s < film.samples_per_pixel; ++s) {
                                      const CameraRay camera_ray = PixelBatchRay(
                                          camera, film, filter, seed, spec.epoch, pixel, s);
                                      const Rgb sample =
                                          radiance(camera_ray.ray, rng) * camera_ray.weight;
                                      AddPixelSample(sample, sum, discarded.local());
                                  }
                                  result.samples[pixel - spec.sample_begin] = sum * inverse_spp;
                              }
                          });
        result.nonfinite_discarded = discarded.combine(std::plus<>());
    }
    return results;
}

}  // namespace pf
