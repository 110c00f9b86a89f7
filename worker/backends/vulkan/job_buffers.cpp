// Creating and filling a job's buffers.
#include "worker/backends/vulkan/job_buffers.h"

#include <algorithm>
#include <cstring>

namespace pf::vk {
namespace {

template <typename T>
std::span<const std::byte> Bytes(const std::vector<T>& values) {
    return std::as_bytes(std::span(values));
}

uint32_t Groups(uint64_t threads, uint32_t per_group) {
    return static_cast<uint32_t>((threads + per_group - 1) / per_group);
}

}  // namespace

absl::StatusOr<std::unique_ptr<JobBuffers>> JobBuffers::Create(
    const Context& context, CommandStream& stream, const GpuScene& gpu_scene,
    std::span<const gpu::GpuHitPoint> hit_points, uint32_t buckets, bool hit_points_per_epoch,
    size_t direct_points, const PixelJobData* pixels) {
    const size_t n = hit_points.size();
    const size_t direct_count = direct_points > 0 ? direct_points : n;
    auto buffers = std::make_unique<JobBuffers>();
    Uploader uploader(context, stream);
    absl::Status status;
    const auto upload = [&](Buffer& buffer, std::span<const std::byte> data) {
        if (!status.ok()) return;
        absl::StatusOr<Buffer> made = uploader.Upload(data);
        if (made.ok())
            buffer = std::move(*made);
        else
            status = made.status();
    };
    const auto make = [&](Buffer& buffer, uint64_t bytes, MemoryUse use) {
        if (!status.ok()) return;
        absl::StatusOr<Buffer> made = Buffer::Create(context, bytes, use);
        if (made.ok())
            buffer = std::move(*made);
        else
            status = made.status();
    };
    upload(buffers->nodes, Bytes(gpu_scene.nodes));
    upload(buffers->triangles, Bytes(gpu_scene.triangles));
    upload(buffers->shading, Bytes(gpu_scene.shading));
    upload(buffers->normals, Bytes(gpu_scene.normals));
    upload(buffers->uvs, Bytes(gpu_scene.uvs));
    upload(buffers->tangents, Bytes(gpu_scene.tangents));
    upload(buffers->sheen_tables, Bytes(gpu_scene.sheen_tables));
    upload(buffers->materials, Bytes(gpu_scene.materials));
    upload(buffers->textures, Bytes(gpu_scene.textures));
    upload(buffers->texels, Bytes(gpu_scene.texels));
    upload(buffers->emitters, Bytes(gpu_scene.emitters));
    upload(buffers->emitter_cdf, Bytes(gpu_scene.emitter_cdf));
    upload(buffers->light_image_texels, Bytes(gpu_scene.light_image_texels));
    upload(buffers->light_image_tables, Bytes(gpu_scene.light_image_tables));
    upload(buffers->hit_points, std::as_bytes(hit_points));
    const PixelJobData none;
    const PixelJobData& pixel = pixels != nullptr ? *pixels : none;
    upload(buffers->pixel_job, std::as_bytes(std::span(&pixel.job, 1)));
    upload(buffers->photon_positions, Bytes(pixel.photon_positions));
    upload(buffers->photon_powers, Bytes(pixel.photon_powers));
    upload(buffers->photon_buckets, Bytes(pixel.photon_buckets));
    make(buffers->radius_sq, n * sizeof(float), MemoryUse::kDevice);
    make(buffers->surface_edges, n * sizeof(uint64_t), MemoryUse::kDevice);
    make(buffers->grid_begin, (buckets + 1) * sizeof(uint32_t), MemoryUse::kDevice);
    make(buffers->grid_cursor, buckets * sizeof(uint32_t), MemoryUse::kDevice);
    make(buffers->grid_entries, n * sizeof(gpu::GpuGridEntry), MemoryUse::kDevice);
    const uint64_t scanned = std::max<uint64_t>(buckets, n) + 1;  // the longest array scanned
    make(buffers->scan_blocks, Groups(scanned, gpu::kScanBlock) * sizeof(uint32_t),
         MemoryUse::kDevice);
    make(buffers->tally, n * sizeof(gpu::GpuTallySum), MemoryUse::kDevice);
    make(buffers->tally_offsets, (n + 1) * sizeof(uint32_t), MemoryUse::kDevice);
    make(buffers->tally_entries, n * sizeof(gpu::GpuTallyEntry), MemoryUse::kKernelToHost);
    make(buffers->direct, direct_count * sizeof(gpu::vec4), MemoryUse::kDevice);
    if (direct_points > 0) {
        make(buffers->direct_points, direct_points * sizeof(gpu::GpuHitPoint), MemoryUse::kDevice);
        make(buffers->direct_point_upload, direct_points * sizeof(gpu::GpuHitPoint),
             MemoryUse::kUpload);
    }
    make(buffers->counters, sizeof(gpu::GpuCounters), MemoryUse::kDevice);
    make(buffers->radius_upload, n * sizeof(float), MemoryUse::kUpload);
    make(buffers->edges_upload, n * sizeof(uint64_t), MemoryUse::kUpload);
    if (hit_points_per_epoch)
        make(buffers->hit_point_upload, n * sizeof(gpu::GpuHitPoint), MemoryUse::kUpload);
    make(buffers->direct_readback, direct_count * sizeof(gpu::vec4), MemoryUse::kReadback);
    make(buffers->counters_readback, sizeof(gpu::GpuCounters), MemoryUse::kReadback);
    if (pixels == nullptr)
        make(buffers->camera_rays, sizeof(gpu::GpuCameraRay), MemoryUse::kDevice);
    else if (status.ok())
        status = buffers->ReserveCameraSamples(context, 0);
    if (absl::Status finished = uploader.Finish(); status.ok()) status = finished;
    if (!status.ok()) return status;
    return buffers;
}

absl::Status JobBuffers::ReserveCameraSamples(const Context& context, size_t samples) {
    samples = std::max<size_t>(samples, 1);
    if (samples <= camera_samples) return absl::OkStatus();
    absl::StatusOr<Buffer> rays =
        Buffer::Create(context, samples * sizeof(gpu::GpuCameraRay), MemoryUse::kDevice);
    if (!rays.ok()) return rays.status();
    absl::StatusOr<Buffer> upload =
        Buffer::Create(context, samples * sizeof(gpu::GpuCameraRay), MemoryUse::kUpload);
    if (!upload.ok()) return upload.status();
    absl::StatusOr<Buffer> out =
        Buffer::Create(context, samples * sizeof(gpu::vec4), MemoryUse::kDevice);
    if (!out.ok()) return out.status();
    absl::StatusOr<Buffer> readback =
        Buffer::Create(context, samples * sizeof(gpu::vec4), MemoryUse::kReadback);
    if (!readback.ok()) return readback.status();
    camera_rays = std::move(*rays);
    camera_ray_upload = std::move(*upload);
    direct = std::move(*out);
    direct_readback = std::move(*readback);
    camera_samples = samples;
    return absl::OkStatus();
}

absl::Status JobBuffers::ReservePathSlots(const Context& context, size_t pixels) {
    pixels = std::max<size_t>(pixels, 1);
    if (pixels <= path_slots) return absl::OkStatus();
    absl::StatusOr<Buffer> states =
        Buffer::Create(context, pixels * sizeof(gpu::GpuPathState), MemoryUse::kDevice);
    if (!states.ok()) return states.status();
    absl::StatusOr<Buffer> queues =
        Buffer::Create(context, pixels * gpu::kPathQueues * sizeof(uint32_t), MemoryUse::kDevice);
    if (!queues.ok()) return queues.status();
    if (path_counters.Handle() == VK_NULL_HANDLE) {
        const size_t bytes = gpu::kPathCounterWords * sizeof(uint32_t);
        absl::StatusOr<Buffer> words = Buffer::Create(context, bytes, MemoryUse::kDevice);
        if (!words.ok()) return words.status();
        absl::StatusOr<Buffer> readback = Buffer::Create(context, bytes, MemoryUse::kReadback);
        if (!readback.ok()) return readback.status();
        path_counters = std::move(*words);
        path_counters_readback = std::move(*readback);
    }
    path_states = std::move(*states);
    path_queues = std::move(*queues);
    path_slots = pixels;
    return absl::OkStatus();
}

std::array<VkBuffer, gpu::kBindingCount> JobBuffers::Bindings() const {
    std::array<VkBuffer, gpu::kBindingCount> b{};
    b[gpu::kBindingBvhNodes] = nodes.Handle(), b[gpu::kBindingTriangles] = triangles.Handle();
    b[gpu::kBindingShading] = shading.Handle(), b[gpu::kBindingNormals] = normals.Handle();
    b[gpu::kBindingUvs] = uvs.Handle(), b[gpu::kBindingMaterials] = materials.Handle();
    b[gpu::kBindingTextures] = textures.Handle(), b[gpu::kBindingTexels] = texels.Handle();
    b[gpu::kBindingEmitters] = emitters.Handle(), b[gpu::kBindingEmitterCdf] = emitter_cdf.Handle();
    b[gpu::kBindingHitPoints] = hit_points.Handle(), b[gpu::kBindingRadiusSq] = radius_sq.Handle();
    b[gpu::kBindingSurfaceEdges] = surface_edges.Handle();
    b[gpu::kBindingGridBegin] = grid_begin.Handle(),
    b[gpu::kBindingGridCursor] = grid_cursor.Handle();
    b[gpu::kBindingGridEntries] = grid_entries.Handle(),
    b[gpu::kBindingScanBlocks] = scan_blocks.Handle();
    b[gpu::kBindingTally] = tally.Handle(), b[gpu::kBindingDirect] = direct.Handle();
    b[gpu::kBindingCounters] = counters.Handle();
    b[gpu::kBindingTallyOffsets] = tally_offsets.Handle(),
    b[gpu::kBindingTallyEntries] = tally_entries.Handle();
    b[gpu::kBindingLightImageTexels] = light_image_texels.Handle();
    b[gpu::kBindingLightImageTables] = light_image_tables.Handle();
    b[gpu::kBindingTangents] = tangents.Handle();
    b[gpu::kBindingSheenTables] = sheen_tables.Handle();
    b[gpu::kBindingCameraRays] = camera_rays.Handle();
    b[gpu::kBindingPixelJob] = pixel_job.Handle();
    b[gpu::kBindingPhotonPositions] = photon_positions.Handle();
    b[gpu::kBindingPhotonPowers] = photon_powers.Handle();
    b[gpu::kBindingPhotonBuckets] = photon_buckets.Handle();
    if (path_slots > 0) {  // a wavefront path job: no maps
        b[gpu::kBindingPathStates] = path_states.Handle();
        b[gpu::kBindingPathQueues] = path_queues.Handle();
        b[gpu::kBindingPathCounters] = path_counters.Handle();
    }
    b[gpu::kBindingDirectPoints] =
        direct_points.Handle() != VK_NULL_HANDLE ? direct_points.Handle() : hit_points.Handle();
    return b;
}

}  // namespace pf::vk
