// Batches on a Vulkan device.
//
// The tally's fixed point: each deposit's flux is converted to an integer number of units of
// max_photon_flux x 2^-31 (the largest flux any photon carries, since albedos are at most 1,
// see GpuScene) and added with 64-bit integer atomics, so a batch's sums are exact and do
// not depend on the order threads reach them. Range: an addend is at most 2^31 units and a
// hit point counts at most 2^32 - 1 photons a batch (its count is 32-bit, as on the CPU), so
// a sum stays below 2^63 whatever the light's power (the unit scales with it: lights x1e-6
// and x1e9 in docs/numerics.md are the same integers). Precision: each addend is rounded to
// the nearest unit, an absolute error of 2^-32 of the largest photon flux, below float's
// own rounding for every deposit above 2^-8 of it; the sum is then exact, where the CPU's
// float sum loses up to 2^-24 per addition. Shading normals and diffuse transmission break the
// bound: Veach's factors (core/shared/shading_normal.h) and a deposit's weight at a hit point
// of its own normal may exceed 1, and so may a translucent surface's R / p or T / p in some
// channel (core/shared/translucent.h: up to 2 a bounce), and a sheen's reflection weight pi f /
// P (core/shared/coat.h: the lobe's value over its mean, tens for a narrow lobe), so the unit
// is then kHeadroom times larger, and only a deposit above that many times the largest flux (a
// photon grazing a surface its shading normal faces, or gaining at many translucent bounces in
// a row) is clamped.
#include "worker/backends/vulkan/vulkan_backend.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cstring>

#include "absl/strings/str_cat.h"
#include "core/camera/camera_pass.h"
#include "core/job/job_spec.h"
#include "core/ppm/direct_light.h"
#include "core/ppm/photon_pass.h"
#include "core/render/pixel_pass.h"
#include "core/util/check.h"
#include "embree/embree_tracer.h"
#include "worker/backends/vulkan/job_buffers.h"
#include "worker/backends/vulkan/pixel_jobs.h"

namespace pf::vk {
namespace {

constexpr float kFixedUnitsPerMaxFlux = 2147483648.0f;  // 2^31
constexpr float kHeadroom = 256.0f;
// The grid's buckets: about two per hit point, at most 2^21 (8 MiB of offsets).
constexpr uint32_t kMaxBuckets = 1u << 21;

double Mib(uint64_t bytes) { return static_cast<double>(bytes) / (1 << 20); }

uint32_t Groups(uint64_t threads, uint32_t per_group) {
    return static_cast<uint32_t>((threads + per_group - 1) / per_group);
}

static_assert(gpu::kNoCoat == kNoCoat);
gpu::GpuHitPoint ToGpu(const HitPoint& h) {
    return {{h.position.x, h.position.y, h.position.z, std::bit_cast<float>(h.coat)},
            {h.normal.x, h.normal.y, h.normal.z, std::bit_cast<float>(h.pixel)},
            {h.weight.x, h.weight.y, h.weight.z, std::bit_cast<float>(h.gathers)}};
}

}  // namespace

absl::Status CheckJobFits(const DeviceCapacity& device, const GpuScene& gpu_scene,
                          size_t hit_points, const PixelJobData* pixels) {
    const PixelJobData none;
    const PixelJobData& maps = pixels != nullptr ? *pixels : none;
    struct Need {
        const char* what;
        uint64_t bytes;
    };
    const Need needs[] = {
        {"BVH nodes", gpu_scene.nodes.size() * sizeof(gpu::GpuBvhNode)},
        {"triangles", gpu_scene.triangles.size() * sizeof(gpu::GpuTriangle)},
        {"texels", gpu_scene.texels.size() * sizeof(gpu::vec4)},
        {"light images", gpu_scene.light_image_texels.size() * sizeof(gpu::vec4)},
        {"hit points", hit_points * sizeof(gpu::GpuHitPoint)},
        {"grid entries", hit_points * sizeof(gpu::GpuGridEntry)},
        {"tally", hit_points * sizeof(gpu::GpuTallySum)},
        {"photon map positions", maps.photon_positions.size() * sizeof(gpu::vec4)},
        {"photon map powers", maps.photon_powers.size() * sizeof(gpu::GpuPhotonPower)},
        {"photon map buckets", maps.photon_buckets.size() * sizeof(uint32_t)},
    };
    uint64_t total = 0;
    for (const Need& need : needs) {
        total += need.bytes;
        if (need.bytes > device.max_buffer_bytes)
            return absl::ResourceExhaustedError(absl::StrCat(
                "job too large for Vulkan device ", device.name, ": its ", need.what, " (",
                maps.MapBytes() > 0 ? absl::StrCat(maps.photon_powers.size(), " photons stored")
                                    : absl::StrCat(hit_points, " hit points"),
                ") need ", Mib(need.bytes), " MiB in one buffer, the device allows ",
                Mib(device.max_buffer_bytes),
                " MiB (maxStorageBufferRange); use fewer pixels, samples or photons, or the cpu "
                "backend"));
    }
    // Direct samples, radii, the grid's buckets and the staging buffers come on top: under
    // 100 bytes a hit point.
    total += hit_points * 100;
    if (total > device.memory_bytes)
        return absl::ResourceExhaustedError(
            absl::StrCat("job too large for Vulkan device ", device.name, ": it needs ", Mib(total),
                         " MiB, the device has ", Mib(device.memory_bytes),
                         " MiB; use fewer pixels, samples or photons, or the cpu backend"));
    return absl::OkStatus();
}

absl::StatusOr<std::unique_ptr<VulkanBackend>> VulkanBackend::Create(
    std::shared_ptr<Context> context, const Scene& scene) {
    absl::StatusOr<PathDesign> path_design = PathDesignFromEnvironment();
    if (!path_design.ok()) return path_design.status();
    absl::StatusOr<CommandStream> stream = CommandStream::Create(*context);
    if (!stream.ok()) return stream.status();
    return std::unique_ptr<VulkanBackend>(
        new VulkanBackend(std::move(context), scene, std::move(*stream), *path_design));
}

VulkanBackend::VulkanBackend(std::shared_ptr<Context> context, const Scene& scene,
                             CommandStream stream, PathDesign path_design)
    : context_(std::move(context)),
      scene_(scene),
      stream_(std::move(stream)),
      path_design_(path_design) {}

VulkanBackend::~VulkanBackend() = default;

absl::Status VulkanBackend::BeginJob(const JobInputs& job) {
    if (job.scene == nullptr || job.emitters == nullptr || !job.emitters->HasPower())
        return absl::InvalidArgumentError("job has no scene or no light");
    if (job.scene != &scene_) return absl::InvalidArgumentError("job's scene is not the backend's");
    buffers_.reset();
    kernels_.reset();
    passes_.reset();
    black_slots_.clear();
    job_ = job;
    size_t direct_points = 0;
    if (job.spec != nullptr && GathersAtHitPoints(job.spec->integrator)) {
        // Each epoch's camera pass is traced on this machine's CPU, as the CPU backend does;
        // the device holds one slot per pixel sample (and rpm's gather rays), black until the
        // first epoch: sppm's and rpm's hit points, or ppm's points of direct light.
        absl::StatusOr<EpochPasses> passes =
            EpochPasses::Create(*job.spec, scene_, *job.emitters, job.hit_points,
                                AnalyseFeatures(scene_, *job.emitters));
        if (!passes.ok()) return passes.status();
        if (absl::StatusOr<const Tracer*> tracer = CameraTracer(); !tracer.ok())
            return tracer.status();
        passes_ = std::move(*passes);
        if (passes_->Stochastic()) {
            black_slots_.assign(passes_->MaxEpochPoints(), {});
            job_.hit_points = black_slots_;
        } else {
            direct_points = passes_->MaxEpochPoints();
        }
    }
    if (job_.hit_points.size() >= (size_t{1} << 31))
        return absl::ResourceExhaustedError("over 2^31 hit points");
    absl::StatusOr<GpuScene> gpu_scene = BuildGpuScene(scene_, *job.emitters);
    if (!gpu_scene.ok()) return gpu_scene.status();
    std::optional<PixelJobData> pixels;
    if (PixelJob()) {
        absl::StatusOr<const Tracer*> tracer = CameraTracer();
        if (!tracer.ok()) return tracer.status();
        absl::StatusOr<PixelJobData> prepared =
            PreparePixelJob(*job.spec, scene_, *job.emitters, **tracer,
                            AnalyseFeatures(scene_, *job.emitters), job.seed);
        if (!prepared.ok()) return prepared.status();
        pixels = std::move(*prepared);
    }
    const DeviceCapacity capacity{context_->Info().name, context_->Limits().maxStorageBufferRange,
                                  context_->Info().device_local_bytes};
    // ppm's points of direct light take what a hit point takes, or less.
    if (absl::Status status =
            CheckJobFits(capacity, *gpu_scene, job_.hit_points.size() + direct_points,
                         pixels ? &*pixels : nullptr);
        !status.ok())
        return status;
    features_ = gpu_scene->features;
    scene_sphere_ = gpu_scene->sphere;
    scene_magnitude_ = gpu_scene->magnitude;
    flux_to_fixed_ =
        kFixedUnitsPerMaxFlux / gpu_scene->max_photon_flux /
        (features_.ShadingNormals() || features_.translucent || features_.sheen ? kHeadroom : 1.0f);
    emitter_count_ = static_cast<uint32_t>(gpu_scene->emitters.size());
    environment_emitter_ = gpu_scene->environment_emitter;
    if (!(gpu_scene->max_photon_flux > 0) || !std::isfinite(flux_to_fixed_))
        return absl::InvalidArgumentError("the scene's lights carry no finite power");

    SpecConstants spec = SpecConstantsFor(features_);
    spec[gpu::kSpecPhotonKinds] = job.spec != nullptr && job.spec->integrator == Integrator::kRpm;
    if (PixelJob() && job.spec->integrator == Integrator::kPm) {
        spec[gpu::kSpecPhotonMapping] = 1;
        spec[gpu::kSpecNearest] = job.spec->photon_map.nearest;
    }
    wavefront_ = PixelJob() && job.spec->integrator == Integrator::kPath &&
                 path_design_ == PathDesign::kWavefront;
    if (wavefront_) wavefront_rounds_per_sample_ = uint64_t{pixels->job.max_depth} + 2;
    const KernelSet set = !PixelJob()  ? KernelSet::kPhotons
                          : wavefront_ ? KernelSet::kPathWavefront
                                       : KernelSet::kPixels;
    absl::StatusOr<std::unique_ptr<Kernels>> kernels = Kernels::Create(*context_, spec, set);
    if (!kernels.ok()) return kernels.status();
    kernels_ = std::move(*kernels);

    const size_t n = job_.hit_points.size();
    std::vector<gpu::GpuHitPoint> hit_points(n);
    std::ranges::transform(job_.hit_points, hit_points.begin(), ToGpu);
    buckets_ = std::clamp<uint32_t>(std::bit_ceil(static_cast<uint32_t>(2 * n + 1)),
                                    gpu::kScanBlock, kMaxBuckets);

    const auto upload_start = std::chrono::steady_clock::now();
    absl::StatusOr<std::unique_ptr<JobBuffers>> buffers =
        JobBuffers::Create(*context_, stream_, *gpu_scene, hit_points, buckets_, StochasticJob(),
                           direct_points, pixels ? &*pixels : nullptr);
    if (!buffers.ok()) return buffers.status();
    kernels_->BindBuffers((*buffers)->Bindings());
    buffers_ = std::move(*buffers);
    const double upload_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - upload_start).count();
    if (pixels && pixels->MapBytes() > 0)
        spdlog::info("photon maps: {:.0f} MB uploaded to the device with the scene in {:.3f} s",
                     pixels->MapBytes() / 1e6, upload_seconds);
    spdlog::debug("Vulkan job: {} hit points, {} triangles, kernels for {}; uploaded in {:.3f} s",
                  n, scene_.triangles.size(), features_.ToString(), upload_seconds);
    return absl::OkStatus();
}

absl::StatusOr<const Tracer*> VulkanBackend::CameraTracer() {
    if (camera_tracer_ == nullptr) {
        absl::StatusOr<std::unique_ptr<embree::EmbreeTracer>> tracer =
            embree::EmbreeTracer::Create(scene_);
        if (!tracer.ok()) return tracer.status();
        camera_tracer_ = std::move(*tracer);
    }
    return camera_tracer_.get();
}

gpu::GpuParams VulkanBackend::BaseParams() const {
    gpu::GpuParams params{};
    params.scene_sphere = scene_sphere_;
    params.scene_magnitude = scene_magnitude_;
    params.grid_inverse_cell = grid_inverse_cell_;
    params.grid_bucket_mask = buckets_ - 1;
    params.hit_point_count = static_cast<uint32_t>(job_.hit_points.size());
    params.flux_to_fixed = flux_to_fixed_;
    params.emitter_count = emitter_count_;
    params.environment_emitter = environment_emitter_;
    params.max_bounces = static_cast<uint32_t>(
        DepthLimit(job_.spec != nullptr ? job_.spec->max_depth : 0, kMaxPhotonBounces));
    return params;
}

absl::Status VulkanBackend::BeginEpoch(uint64_t epoch, const GatherRegions& regions,
                                       const std::vector<HitPoint>* traced) {
    if (buffers_ == nullptr) return absl::FailedPreconditionError("BeginEpoch before a job");
    const size_t n = job_.hit_points.size();
    const std::span<const float> radius_sq = regions.radius_sq;
    if (radius_sq.size() != n || !(regions.edges.empty() || regions.edges.size() == n))
        return absl::InvalidArgumentError("one radius and edge set per hit point expected");
    if (PixelJob()) return absl::OkStatus();  // pixel batches need nothing an epoch
    if (passes_) {  // ppm's passes are traced by parts as batches need them (RunBatches)
        passes_->Begin(epoch, *camera_tracer_, traced);
        if (passes_->Stochastic()) {
            PF_CHECK(passes_->HitPoints().size() == n);
            job_.hit_points = passes_->HitPoints();
            black_slots_ = {};
            std::ranges::transform(
                passes_->HitPoints(),
                static_cast<gpu::GpuHitPoint*>(buffers_->hit_point_upload.Mapped()), ToGpu);
        }
    }
    // Cells two of the largest radius wide, as the CPU grid: the largest over the hit points
    // the grid holds (a radius and a weight).
    float max_radius_sq = 0;
    for (size_t i = 0; i < n; ++i)
        if (MaxComponent(job_.hit_points[i].weight) > 0)
            max_radius_sq = std::max(max_radius_sq, radius_sq[i]);
    grid_inverse_cell_ = max_radius_sq > 0 ? 0.5f / std::sqrt(max_radius_sq) : 1.0f;
    if (n > 0) std::memcpy(buffers_->radius_upload.Mapped(), radius_sq.data(), n * sizeof(float));
    auto* edges = static_cast<uint64_t*>(buffers_->edges_upload.Mapped());
    if (regions.edges.empty())
        std::fill_n(edges, n, gpu::kUnboundedEdges);
    else
        std::ranges::copy(regions.edges, edges);

    absl::StatusOr<VkCommandBuffer> commands = stream_.Begin();
    if (!commands.ok()) return commands.status();
    const VkBufferCopy radii{.size = n * sizeof(float)};
    const VkBufferCopy edge_copy{.size = n * sizeof(uint64_t)};
    if (n > 0) {
        vkCmdCopyBuffer(*commands, buffers_->radius_upload.Handle(), buffers_->radius_sq.Handle(),
                        1, &radii);
        vkCmdCopyBuffer(*commands, buffers_->edges_upload.Handle(),
                        buffers_->surface_edges.Handle(), 1, &edge_copy);
    }
    const VkBufferCopy points{.size = job_.hit_points.size() * sizeof(gpu::GpuHitPoint)};
    if (StochasticJob() && n > 0)
        vkCmdCopyBuffer(*commands, buffers_->hit_point_upload.Handle(),
                        buffers_->hit_points.Handle(), 1, &points);
    vkCmdFillBuffer(*commands, buffers_->grid_begin.Handle(), 0, VK_WHOLE_SIZE, 0);
    stream_.Barrier();
    gpu::GpuParams params = BaseParams();
    const uint32_t hit_point_groups = Groups(n, gpu::kWorkgroupSize);
    kernels_->Dispatch(*commands, Kernel::kGridCount, params, hit_point_groups);
    stream_.Barrier();
    // Exclusive scan of buckets + 1 counts: the last offset is the number of entries.
    RecordScan(*commands, gpu::kScanGridBegin, buckets_ + 1);
    const VkBufferCopy cursor{.size = buckets_ * sizeof(uint32_t)};
    vkCmdCopyBuffer(*commands, buffers_->grid_begin.Handle(), buffers_->grid_cursor.Handle(), 1,
                    &cursor);
    stream_.Barrier();
    kernels_->Dispatch(*commands, Kernel::kGridFill, params, hit_point_groups);
    return stream_.SubmitAndWait();
}

void VulkanBackend::RecordScan(VkCommandBuffer commands, uint32_t target, uint32_t count) {
    gpu::GpuParams params = BaseParams();
    params.scan_target = target;
    params.scan_count = count;
    const uint32_t blocks = Groups(count, gpu::kScanBlock);
    kernels_->Dispatch(commands, Kernel::kScanBlocks, params, blocks);
    stream_.Barrier();
    gpu::GpuParams totals = params;
    totals.scan_count = blocks;
    kernels_->Dispatch(commands, Kernel::kScanTotals, totals, 1);
    stream_.Barrier();
    kernels_->Dispatch(commands, Kernel::kScanAdd, params, blocks);
    stream_.Barrier();
}

void VulkanBackend::RecordThreads(VkCommandBuffer commands, Kernel kernel, gpu::GpuParams params,
                                  uint64_t first, uint64_t threads) {
    const uint64_t per_dispatch = std::min<uint64_t>(
        kMaxThreadsPerDispatch,
        uint64_t{context_->Limits().maxComputeWorkGroupCount[0]} * gpu::kWorkgroupSize);
    for (uint64_t done = 0; done < threads; done += per_dispatch) {
        params.first = static_cast<uint32_t>(first + done);
        kernels_->Dispatch(
            commands, kernel, params,
            Groups(std::min<uint64_t>(per_dispatch, threads - done), gpu::kWorkgroupSize));
    }
}

absl::StatusOr<BatchResult> VulkanBackend::RunPixelBatch(const BatchSpec& spec) {
    const Film film = PixelFilm(*job_.spec);
    const uint64_t samples =
        uint64_t{spec.sample_end - spec.sample_begin} * uint64_t(film.samples_per_pixel);
    if (samples >= (uint64_t{1} << 32))
        return absl::InvalidArgumentError("a pixel batch of 2^32 camera samples or more");
    const size_t room = buffers_->camera_samples;
    if (absl::Status status = buffers_->ReserveCameraSamples(*context_, samples); !status.ok())
        return status;
    const uint32_t pixels = spec.sample_end - spec.sample_begin;
    const size_t slots = buffers_->path_slots;
    if (wavefront_)
        if (absl::Status status = buffers_->ReservePathSlots(*context_, pixels); !status.ok())
            return status;
    if (buffers_->camera_samples != room || buffers_->path_slots != slots)
        kernels_->BindBuffers(buffers_->Bindings());
    MakeCameraRays(scene_.camera, film, job_.seed, spec,
                   static_cast<gpu::GpuCameraRay*>(buffers_->camera_ray_upload.Mapped()));
    absl::StatusOr<VkCommandBuffer> commands = stream_.Begin();
    if (!commands.ok()) return commands.status();
    const VkBufferCopy rays{.size = samples * sizeof(gpu::GpuCameraRay)};
    if (samples > 0)
        vkCmdCopyBuffer(*commands, buffers_->camera_ray_upload.Handle(),
                        buffers_->camera_rays.Handle(), 1, &rays);
    stream_.Barrier();
    gpu::GpuParams params = BaseParams();
    params.seed_prefix = PixelSeeds(job_.seed, spec.epoch).Prefix();
    params.end = pixels;
    params.direct_begin = spec.sample_begin;
    if (wavefront_) {
        commands = TraceWavefront(stream_, *commands, *kernels_, *buffers_, params, pixels,
                                  wavefront_rounds_per_sample_ * uint64_t(film.samples_per_pixel));
        if (!commands.ok()) return commands.status();
    } else {
        RecordThreads(*commands, Kernel::kPixelTrace, params, 0, pixels);
    }
    stream_.Barrier();
    const VkBufferCopy means{.size = pixels * sizeof(gpu::vec4)};
    if (pixels > 0)
        vkCmdCopyBuffer(*commands, buffers_->direct.Handle(), buffers_->direct_readback.Handle(), 1,
                        &means);
    stream_.Barrier();
    if (absl::Status status = stream_.SubmitAndWait(); !status.ok()) return status;
    buffers_->direct_readback.InvalidateForRead();
    return PixelMeans(spec, static_cast<const gpu::vec4*>(buffers_->direct_readback.Mapped()));
}

absl::StatusOr<BatchResult> VulkanBackend::RunBatch(const BatchSpec& spec) {
    if (PixelJob()) return RunPixelBatch(spec);
    absl::StatusOr<VkCommandBuffer> commands = stream_.Begin();
    if (!commands.ok()) return commands.status();
    vkCmdFillBuffer(*commands, buffers_->tally.Handle(), 0, VK_WHOLE_SIZE, 0);
    vkCmdFillBuffer(*commands, buffers_->counters.Handle(), 0, VK_WHOLE_SIZE, 0);
    stream_.Barrier();
    // Photons (adaptive tracing: chains) a thread, in dispatches of at most
    // kMaxThreadsPerDispatch, within the device's workgroup count limit.
    gpu::GpuParams params = BaseParams();
    params.seed_prefix = PhotonSeeds(job_.seed, spec.index).Prefix();
    params.end = spec.photons;
    if (Adaptive()) {
        params.chain_steps = kChainSteps;
        params.proposal_prefix = ProposalSeeds(job_.seed, spec.index).Prefix();
    }
    const uint64_t threads =
        Adaptive() ? (uint64_t{spec.photons} + kChainSteps - 1) / kChainSteps : spec.photons;
    RecordThreads(*commands, Kernel::kPhotonTrace, params, 0, threads);
    const uint32_t direct_count = spec.sample_end - spec.sample_begin;
    gpu::GpuParams direct = BaseParams();
    direct.seed_prefix = DirectLightSeeds(job_.seed, spec.epoch).Prefix();
    direct.end = spec.sample_end;
    direct.direct_begin = spec.sample_begin;
    if (passes_ && passes_->Sequence()) {
        const DirectLightSequence& sequence = *passes_->Sequence();
        direct.direct_samples_per_pixel = static_cast<uint32_t>(sequence.samples_per_pixel);
        direct.direct_sequences = DirectLightSequences(job_.seed);
        direct.direct_first_sample = sequence.first;
        direct.direct_slots_per_sample = static_cast<uint32_t>(sequence.slots_per_sample);
        direct.epoch_parity = static_cast<uint32_t>(spec.epoch & 1);
    }
    RecordThreads(*commands, Kernel::kDirectLight, direct, spec.sample_begin, direct_count);
    stream_.Barrier();
    // The sparse tally, made on the device in hit point order: flags, their prefix sum, and
    // each reached hit point's entry written to host-visible memory.
    const auto n = static_cast<uint32_t>(job_.hit_points.size());
    kernels_->Dispatch(*commands, Kernel::kTallyFlags, BaseParams(),
                       Groups(uint64_t{n} + 1, gpu::kWorkgroupSize));
    stream_.Barrier();
    RecordScan(*commands, gpu::kScanTallyOffsets, n + 1);
    kernels_->Dispatch(*commands, Kernel::kTallyCompact, BaseParams(),
                       Groups(uint64_t{n} + 1, gpu::kWorkgroupSize));
    stream_.Barrier();
    const VkBufferCopy samples{.size = direct_count * sizeof(gpu::vec4)};
    const VkBufferCopy counters{.size = sizeof(gpu::GpuCounters)};
    if (direct_count > 0)
        vkCmdCopyBuffer(*commands, buffers_->direct.Handle(), buffers_->direct_readback.Handle(), 1,
                        &samples);
    vkCmdCopyBuffer(*commands, buffers_->counters.Handle(), buffers_->counters_readback.Handle(), 1,
                    &counters);
    stream_.Barrier();
    if (absl::Status status = stream_.SubmitAndWait(); !status.ok()) return status;

    return ReadResult(spec);
}

BatchResult VulkanBackend::ReadResult(const BatchSpec& spec) const {
    const uint32_t direct_count = spec.sample_end - spec.sample_begin;
    const auto n = static_cast<uint32_t>(job_.hit_points.size());
    BatchResult result;
    result.spec = spec;
    result.photons_emitted = spec.photons;
    buffers_->tally_entries.InvalidateForRead();
    buffers_->direct_readback.InvalidateForRead();
    buffers_->counters_readback.InvalidateForRead();
    const auto* counted =
        static_cast<const gpu::GpuCounters*>(buffers_->counters_readback.Mapped());
    result.segments_traced = counted->segments;
    result.nonfinite_discarded = counted->nonfinite_discarded;
    const auto entries =
        std::span(static_cast<const gpu::GpuTallyEntry*>(buffers_->tally_entries.Mapped()),
                  std::min<uint64_t>(counted->tally_entries, n));
    Tally& out = result.tally;
    out.hit_point.resize(entries.size());
    out.photons.resize(entries.size());
    out.inner_photons.resize(entries.size());
    out.flux.resize(entries.size());
    // Adaptive: each state counts V_c x photons / steps, as on the CPU (RunPhotonChunk).
    const float scale =
        Adaptive() && counted->chain_steps > 0
            ? static_cast<float>(double(counted->visible_photons) / double(counted->chain_steps))
            : 1.0f;
    for (size_t e = 0; e < entries.size(); ++e) {
        out.hit_point[e] = entries[e].hit_point;
        out.photons[e] = entries[e].photons;
        out.inner_photons[e] = entries[e].inner_photons;
        out.flux[e] = Rgb(entries[e].flux[0], entries[e].flux[1], entries[e].flux[2]) * scale;
    }
    const auto* direct_samples = static_cast<const gpu::vec4*>(buffers_->direct_readback.Mapped());
    result.samples.resize(direct_count);
    for (uint32_t i = 0; i < direct_count; ++i)
        result.samples[i] = {direct_samples[i].x, direct_samples[i].y, direct_samples[i].z};
    return result;
}

absl::Status VulkanBackend::UploadDirectPoints(std::span<const BatchSpec> specs) {
    if (!passes_->CoverDirectPoints(*camera_tracer_, specs)) return absl::OkStatus();
    const std::span<const HitPoint> part = passes_->DirectPoints();
    PF_CHECK(passes_->DirectOffset() + part.size() <= passes_->MaxEpochPoints());
    // The part lies in the device's buffer where the whole pass's slots would.
    const VkDeviceSize offset = passes_->DirectOffset() * sizeof(gpu::GpuHitPoint);
    std::ranges::transform(part,
                           static_cast<gpu::GpuHitPoint*>(buffers_->direct_point_upload.Mapped()) +
                               passes_->DirectOffset(),
                           ToGpu);
    absl::StatusOr<VkCommandBuffer> commands = stream_.Begin();
    if (!commands.ok()) return commands.status();
    const VkBufferCopy copy{
        .srcOffset = offset, .dstOffset = offset, .size = part.size() * sizeof(gpu::GpuHitPoint)};
    vkCmdCopyBuffer(*commands, buffers_->direct_point_upload.Handle(),
                    buffers_->direct_points.Handle(), 1, &copy);
    stream_.Barrier();
    return stream_.SubmitAndWait();
}

absl::StatusOr<std::vector<BatchResult>> VulkanBackend::RunBatches(
    std::span<const BatchSpec> specs) {
    if (buffers_ == nullptr) return absl::FailedPreconditionError("RunBatches before a job");
    if (passes_ && !passes_->Stochastic())
        if (absl::Status status = UploadDirectPoints(specs); !status.ok()) return status;
    std::vector<BatchResult> results;
    results.reserve(specs.size());
    for (const BatchSpec& spec : specs) {
        absl::StatusOr<BatchResult> result = RunBatch(spec);
        if (!result.ok()) return result.status();
        results.push_back(std::move(*result));
    }
    if (passes_ && !passes_->Stochastic()) passes_->AddEmission(*camera_tracer_, results);
    return results;
}

}  // namespace pf::vk
