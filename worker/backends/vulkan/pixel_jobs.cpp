// Pixel jobs on the Vulkan backend, host side.
#include "worker/backends/vulkan/pixel_jobs.h"

#include <spdlog/spdlog.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <chrono>

#include "core/camera/camera_pass.h"
#include "core/camera/gather_ray.h"
#include "core/pm/density_estimate.h"
#include "core/pm/photon_grid.h"
#include "core/pm/photon_map.h"
#include "core/render/path_tracer.h"
#include "core/render/pixel_pass.h"
#include "core/util/check.h"

namespace pf::vk {
namespace {

// Appends one map's grid to the upload and says where it lies.
gpu::GpuPhotonMap AddMap(const PhotonGrid& grid, PixelJobData& data) {
    gpu::GpuPhotonMap map{};
    map.first_photon = static_cast<uint32_t>(data.photon_positions.size());
    map.photon_count = static_cast<uint32_t>(grid.Photons().size());
    map.first_bucket = static_cast<uint32_t>(data.photon_buckets.size());
    map.bucket_mask = static_cast<uint32_t>(grid.BucketMask());
    map.cell_size = grid.CellSize();
    map.inverse_cell_size = 1.0f / grid.CellSize();
    for (const StoredPhoton& photon : grid.Photons()) {
        const Vec3& p = photon.position;
        const Vec3& d = photon.direction;
        data.photon_positions.push_back({p.x, p.y, p.z, 0.0f});
        data.photon_powers.push_back(
            {{d.x, d.y, d.z, 0.0f}, {photon.power.x, photon.power.y, photon.power.z, 0.0f}});
    }
    const std::span<const uint32_t> buckets = grid.BucketBegin();
    data.photon_buckets.insert(data.photon_buckets.end(), buckets.begin(), buckets.end());
    return map;
}

}  // namespace

absl::StatusOr<PixelJobData> PreparePixelJob(const JobSpec& spec, const Scene& scene,
                                             const Emitters& emitters, const Tracer& tracer,
                                             const SceneFeatures& features, uint64_t seed) {
    PixelJobData data;
    gpu::GpuPixelJob& job = data.job;
    job.samples_per_pixel = static_cast<uint32_t>(spec.samples_per_pixel);
    if (spec.integrator == Integrator::kPath) {
        job.max_depth = static_cast<uint32_t>(DepthLimit(spec.max_depth, kMaxPathDepth));
        job.roulette_depth = kPathRouletteDepth;
        return data;
    }
    PF_CHECK(spec.integrator == Integrator::kPm);
    // The maps every worker builds from the job's seed (the index aside, which only says how
    // the CPU searches them: the device searches a hashed grid).
    PhotonMapSettings settings = spec.photon_map;
    settings.index = PhotonIndex::kGrid;
    const PhotonMapForecast forecast =
        ForecastPhotonMaps(scene, emitters, tracer, features, settings, seed, spec.max_depth);
    if (absl::Status status = CheckPhotonMapsFit(forecast, settings, AvailableMemoryBytes());
        !status.ok())
        return status;
    const auto start = std::chrono::steady_clock::now();
    const PhotonMaps maps =
        BuildPhotonMaps(scene, emitters, tracer, features, settings, seed, spec.max_depth);
    const auto* global = dynamic_cast<const PhotonGrid*>(maps.global.get());
    const auto* caustic = dynamic_cast<const PhotonGrid*>(maps.caustic.get());
    PF_CHECK(global != nullptr && caustic != nullptr);
    job.global_map = AddMap(*global, data);
    job.caustic_map = AddMap(*caustic, data);
    spdlog::info("photon maps: {} global and {} caustic photons stored ({:.0f} MB) in {:.2f} s",
                 global->Photons().size(), caustic->Photons().size(), maps.Bytes() / 1e6,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    job.max_depth = static_cast<uint32_t>(DepthLimit(spec.max_depth, kMaxCameraDepth));
    job.roulette_depth = kCameraRouletteDepth;
    job.gather_depth = kMaxGatherDepth;
    job.final_gather = settings.final_gather;
    job.density_filter = static_cast<uint32_t>(settings.filter);
    const float max_radius = MaxSearchRadius(settings, scene);
    job.max_radius_sq = max_radius * max_radius;
    job.filter_normalisation = FilterNormalisation(settings.filter);
    job.per_cosine = features.ShadingNormals();
    return data;
}

void MakeCameraRays(const Camera& camera, const Film& film, uint64_t seed, const BatchSpec& spec,
                    gpu::GpuCameraRay* out) {
    const FilterSampler filter(camera.filter);
    const auto spp = static_cast<uint32_t>(film.samples_per_pixel);
    tbb::parallel_for(tbb::blocked_range<uint32_t>(spec.sample_begin, spec.sample_end, 16),
                      [&](const tbb::blocked_range<uint32_t>& pixels) {
                          for (uint32_t pixel = pixels.begin(); pixel < pixels.end(); ++pixel)
                              for (uint32_t s = 0; s < spp; ++s) {
                                  const CameraRay ray = PixelBatchRay(camera, film, filter, seed,
                                                                      spec.epoch, pixel, int(s));
                                  const Vec3& o = ray.ray.origin;
                                  const Vec3& d = ray.ray.direction;
                                  out[uint64_t(pixel - spec.sample_begin) * spp + s] = {
                                      {o.x, o.y, o.z, ray.weight}, {d.x, d.y, d.z, 0.0f}};
                              }
                      });
}

BatchResult PixelMeans(const BatchSpec& spec, const gpu::vec4* means) {
    BatchResult result;
    result.spec = spec;
    result.samples.resize(spec.sample_end - spec.sample_begin);
    for (size_t pixel = 0; pixel < result.samples.size(); ++pixel) {
        const gpu::vec4& mean = means[pixel];
        result.samples[pixel] = {mean.x, mean.y, mean.z};
        result.nonfinite_discarded += static_cast<uint64_t>(mean.w);
    }
    return result;
}

}  // namespace pf::vk
