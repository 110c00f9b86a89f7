// Every buffer of a Vulkan job, named by what it holds, and the staging uploads that fill
// the device-local ones.
#pragma once

#include <array>
#include <cstddef>
#include <cstring>
#include <memory>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/shared/gpu_types.h"
#include "worker/backends/vulkan/buffer.h"
#include "worker/backends/vulkan/command_stream.h"
#include "worker/backends/vulkan/context.h"
#include "worker/backends/vulkan/gpu_scene.h"
#include "worker/backends/vulkan/pixel_jobs.h"

namespace pf::vk {

// Device buffers filled from host data through staging buffers, all copies in one submission.
class Uploader {
public:
    Uploader(const Context& context, CommandStream& stream) : context_(context), stream_(stream) {}

    absl::StatusOr<Buffer> Upload(std::span<const std::byte> data) {
        if (commands_ == VK_NULL_HANDLE) {
            absl::StatusOr<VkCommandBuffer> commands = stream_.Begin();
            if (!commands.ok()) return commands.status();
            commands_ = *commands;
        }
        absl::StatusOr<Buffer> device = Buffer::Create(context_, data.size(), MemoryUse::kDevice);
        if (!device.ok() || data.empty()) return device;
        absl::StatusOr<Buffer> staging = Buffer::Create(context_, data.size(), MemoryUse::kUpload);
        if (!staging.ok()) return staging.status();
        std::memcpy(staging->Mapped(), data.data(), data.size());
        const VkBufferCopy region{.srcOffset = 0, .dstOffset = 0, .size = data.size()};
        vkCmdCopyBuffer(commands_, staging->Handle(), device->Handle(), 1, &region);
        staging_.push_back(std::move(*staging));
        return device;
    }
    absl::Status Finish() {
        if (commands_ == VK_NULL_HANDLE) return absl::OkStatus();
        stream_.Barrier();
        absl::Status status = stream_.SubmitAndWait();
        staging_.clear();
        commands_ = VK_NULL_HANDLE;
        return status;
    }

private:
    const Context& context_;
    CommandStream& stream_;
    VkCommandBuffer commands_ = VK_NULL_HANDLE;
    std::vector<Buffer> staging_;
};

// Every buffer of a job, named by what it holds; Bindings() lists them in binding order.
struct JobBuffers {
    Buffer nodes, triangles, shading, normals, uvs, tangents, sheen_tables, materials, textures,
        texels, emitters, emitter_cdf, light_image_texels, light_image_tables;
    Buffer hit_points, radius_sq, surface_edges, grid_begin, grid_cursor, grid_entries, scan_blocks,
        tally, direct, counters, direct_points;
    Buffer tally_offsets, tally_entries;
    Buffer radius_upload, edges_upload, hit_point_upload, direct_point_upload, direct_readback,
        counters_readback;
    // Pixel jobs: the constants and pm's maps, and a batch's camera rays; their radiance goes to
    // `direct` and back through `direct_readback`.
    Buffer pixel_job, photon_positions, photon_powers, photon_buckets;
    Buffer camera_rays, camera_ray_upload;
    size_t camera_samples = 0;  // what camera_rays, direct and direct_readback hold
    // The path tracer's wavefront: a path a pixel, its queues and their counters (bound in
    // place of pm's maps), and the counters read back between rounds.
    Buffer path_states, path_queues, path_counters, path_counters_readback;
    size_t path_slots = 0;

    // Makes room for `samples` camera samples a batch (at least one), keeping what is there
    // if it is enough; the buffers' bindings change where it grows. Pixel jobs only.
    absl::Status ReserveCameraSamples(const Context& context, size_t samples);
    // Makes room for `pixels` paths of the wavefront (at least one), as ReserveCameraSamples.
    absl::Status ReservePathSlots(const Context& context, size_t pixels);

    // Uploads what kernels read and makes the rest; RESOURCE_EXHAUSTED where the device runs out.
    // `direct_points`: how many points of an epoch's camera pass direct light is sampled at,
    // uploaded every epoch (0: at the hit points). `pixels`: a pixel job's constants and maps
    // (null for the photon integrators).
    static absl::StatusOr<std::unique_ptr<JobBuffers>> Create(
        const Context& context, CommandStream& stream, const GpuScene& gpu_scene,
        std::span<const gpu::GpuHitPoint> hit_points, uint32_t buckets, bool hit_points_per_epoch,
        size_t direct_points, const PixelJobData* pixels);

    // The buffers in binding order (core/shared/gpu_types.h).
    std::array<VkBuffer, gpu::kBindingCount> Bindings() const;
};

}  // namespace pf::vk
