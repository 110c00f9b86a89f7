// The path tracer on the device as a wavefront (path_wavefront.comp): the host's side, which
// records its stages round after round until every pixel's samples are traced.
#pragma once

#include <cstdint>

#include "absl/status/statusor.h"
#include "core/shared/gpu_types.h"
#include "worker/backends/vulkan/command_stream.h"
#include "worker/backends/vulkan/job_buffers.h"
#include "worker/backends/vulkan/kernels.h"

namespace pf::vk {

// How the path tracer runs on the device: a thread follows a pixel's paths through one kernel
// (pixel_trace.comp), or paths wait in a buffer between a kernel a stage (path_wavefront.comp).
// Both trace the same paths; docs/integrators.md has the measurements that chose the default.
enum class PathDesign { kMegakernel, kWavefront };

// The design PHOTONFARM_VULKAN_PATH names ("megakernel", the default where unset, or
// "wavefront"); INVALID_ARGUMENT naming the variable for anything else.
absl::StatusOr<PathDesign> PathDesignFromEnvironment();

// Traces a pixel batch of `pixels` paths through the wavefront's kernels (made for
// KernelSet::kPathWavefront, bound to `buffers` with room for the batch's paths), `params` the
// batch's; `commands` is the stream's recording, the batch's camera rays copied in it. Submits
// as it goes; returns the stream's recording again, begun, with every pixel's mean written to
// `direct`. INTERNAL where paths remain after `max_rounds` rounds (a round: every live path
// one vertex further).
absl::StatusOr<VkCommandBuffer> TraceWavefront(CommandStream& stream, VkCommandBuffer commands,
                                               const Kernels& kernels, const JobBuffers& buffers,
                                               gpu::GpuParams params, uint32_t pixels,
                                               uint64_t max_rounds);

}  // namespace pf::vk
