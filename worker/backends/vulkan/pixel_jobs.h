// The integrators that render pixels (path, pm) on the Vulkan backend, host side: what a job
// uploads (its constants and, for pm, its photon maps: built on the host by the CPU's code from
// the job's seed, so bit for bit the maps every worker builds, and uploaded as hashed grids),
// the camera rays a batch's samples start from, and each pixel's mean of their radiance.
// pixel_trace.comp traces the samples.
#pragma once

#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "core/camera/pixel_sample.h"
#include "core/geometry/tracer.h"
#include "core/job/batch.h"
#include "core/job/job_spec.h"
#include "core/scene/emitters.h"
#include "core/scene/scene.h"
#include "core/scene/scene_features.h"
#include "core/shared/gpu_types.h"

namespace pf::vk {

struct PixelJobData {
    gpu::GpuPixelJob job{};
    // pm: both maps' photons (the global map's, then the caustic map's), each in its grid's
    // order, and both grids' bucket offsets.
    std::vector<gpu::vec4> photon_positions;
    std::vector<gpu::GpuPhotonPower> photon_powers;
    std::vector<uint32_t> photon_buckets;
    uint64_t MapBytes() const {
        return photon_positions.size() * sizeof(gpu::vec4) +
               photon_powers.size() * sizeof(gpu::GpuPhotonPower) +
               photon_buckets.size() * sizeof(uint32_t);
    }
};

// What a job of `spec` (path or pm) over `scene` uploads; pm's maps are traced with `tracer`
// (RESOURCE_EXHAUSTED, as on the CPU, where they would not fit this machine's memory).
absl::StatusOr<PixelJobData> PreparePixelJob(const JobSpec& spec, const Scene& scene,
                                             const Emitters& emitters, const Tracer& tracer,
                                             const SceneFeatures& features, uint64_t seed);

// The film a pixel job renders.
inline Film PixelFilm(const JobSpec& spec) {
    return {spec.width, spec.height, spec.samples_per_pixel};
}

// The batch's camera rays, sample by sample (pixel by pixel, each pixel's in order), into `out`,
// in parallel on the calling TBB arena: the rays RunPixelBatches traces on the CPU.
void MakeCameraRays(const Camera& camera, const Film& film, uint64_t seed, const BatchSpec& spec,
                    gpu::GpuCameraRay* out);

// The batch's result from its pixels' means as pixel_trace.comp writes them (w: the samples
// that came out NaN or Inf).
BatchResult PixelMeans(const BatchSpec& spec, const gpu::vec4* means);

}  // namespace pf::vk
