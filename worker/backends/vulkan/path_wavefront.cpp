// Recording the wavefront's rounds.
#include "worker/backends/vulkan/path_wavefront.h"

#include <algorithm>
#include <cstdlib>
#include <string>

#include "absl/strings/str_cat.h"

namespace pf::vk {
namespace {

// Rounds recorded a submission: the host reads the queue's length only between submissions,
// so a batch ends at most this many (empty, cheap) rounds late.
constexpr uint64_t kRoundsPerSubmission = 8;

uint32_t Groups(uint64_t threads) {
    return static_cast<uint32_t>((threads + gpu::kWorkgroupSize - 1) / gpu::kWorkgroupSize);
}

// One round from the ray queue params.path_queue: the closest hits, then each class's vertices;
// the paths that go on, and samples started after others ended, fill the other queue.
void RecordRound(const CommandStream& stream, VkCommandBuffer commands, const Kernels& kernels,
                 VkBuffer counters, const gpu::GpuParams& params) {
    constexpr VkDeviceSize kWord = sizeof(uint32_t);
    kernels.Dispatch(commands, Kernel::kPathExtendArgs, params, 1);
    stream.Barrier();
    kernels.DispatchIndirect(commands, Kernel::kPathExtend, params, counters,
                             gpu::kPathExtendArgs * kWord);
    stream.Barrier();
    kernels.Dispatch(commands, Kernel::kPathShadeArgs, params, 1);
    stream.Barrier();
    for (uint32_t c = 0; c < gpu::kVertexClasses; ++c) {
        const auto shade =
            static_cast<Kernel>(static_cast<uint32_t>(Kernel::kPathShadeDiffuse) + c);
        if (kernels.Has(shade))
            kernels.DispatchIndirect(commands, shade, params, counters,
                                     (gpu::kPathShadeArgs + 4 * c) * kWord);
    }
    stream.Barrier();
}

}  // namespace

absl::StatusOr<PathDesign> PathDesignFromEnvironment() {
    const char* value = std::getenv("PHOTONFARM_VULKAN_PATH");
    const std::string name = value != nullptr ? value : "";
    if (name.empty() || name == "megakernel") return PathDesign::kMegakernel;
    if (name == "wavefront") return PathDesign::kWavefront;
    return absl::InvalidArgumentError(
        absl::StrCat("PHOTONFARM_VULKAN_PATH=", name, ": expected megakernel or wavefront"));
}

absl::StatusOr<VkCommandBuffer> TraceWavefront(CommandStream& stream, VkCommandBuffer commands,
                                               const Kernels& kernels, const JobBuffers& buffers,
                                               gpu::GpuParams params, uint32_t pixels,
                                               uint64_t max_rounds) {
    const VkBuffer counters = buffers.path_counters.Handle();
    // Every pixel's first sample waits in ray queue 0.
    vkCmdFillBuffer(commands, counters, 0, VK_WHOLE_SIZE, 0);
    vkCmdFillBuffer(commands, counters, gpu::kPathCountRays * sizeof(uint32_t), sizeof(uint32_t),
                    pixels);
    stream.Barrier();
    params.end = pixels;
    params.path_queue = 0;
    constexpr uint32_t kMaxThreads = gpu::kWorkgroupSize * gpu::kPathMaxGroups;
    for (uint32_t first = 0; first < pixels; first += kMaxThreads) {
        params.first = first;
        kernels.Dispatch(commands, Kernel::kPathStart, params,
                         Groups(std::min<uint64_t>(pixels - first, kMaxThreads)));
    }
    params.first = 0;
    stream.Barrier();
    for (uint64_t rounds = 0;;) {
        for (uint64_t r = 0; r < kRoundsPerSubmission; ++r, ++rounds) {
            RecordRound(stream, commands, kernels, counters, params);
            params.path_queue ^= 1;
        }
        const VkBufferCopy all{.size = gpu::kPathCounterWords * sizeof(uint32_t)};
        vkCmdCopyBuffer(commands, counters, buffers.path_counters_readback.Handle(), 1, &all);
        stream.Barrier();
        if (absl::Status status = stream.SubmitAndWait(); !status.ok()) return status;
        buffers.path_counters_readback.InvalidateForRead();
        const auto* words = static_cast<const uint32_t*>(buffers.path_counters_readback.Mapped());
        const uint32_t waiting = words[gpu::kPathCountRays + params.path_queue];
        absl::StatusOr<VkCommandBuffer> next = stream.Begin();
        if (!next.ok() || waiting == 0) return next;
        if (rounds >= max_rounds)
            return absl::InternalError(absl::StrCat("the path wavefront still had ", waiting,
                                                    " paths after ", rounds, " rounds"));
        commands = *next;
    }
}

}  // namespace pf::vk
