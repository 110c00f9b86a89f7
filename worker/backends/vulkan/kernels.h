// The backend's compute pipelines, specialised for one scene's features, over one
// descriptor set layout (core/shared/gpu_types.h numbers its bindings) and one push-constant
// block (GpuParams). The SPIR-V is compiled from shaders/ at build time and embedded.
#pragma once

#include <array>
#include <memory>

#include "absl/status/statusor.h"
#include "core/shared/gpu_types.h"
#include "worker/backends/vulkan/context.h"

namespace pf::vk {

enum class Kernel {
    kGridCount,
    kScanBlocks,
    kScanTotals,
    kScanAdd,
    kGridFill,
    kPhotonTrace,
    kDirectLight,
    kTallyFlags,
    kTallyCompact,
    kPixelTrace,
    kCount
};

// Specialisation constant values, indexed by the kSpec* ids (0 or 1 but kSpecNearest).
using SpecConstants = std::array<uint32_t, gpu::kSpecCount>;

class Kernels {
public:
    // The pipelines of a photon job (ppm, sppm, rpm: every kernel but kPixelTrace), or of a
    // pixel job (path, pm: kPixelTrace alone), so that neither compiles the other's.
    static absl::StatusOr<std::unique_ptr<Kernels>> Create(const Context& context,
                                                           const SpecConstants& spec,
                                                           bool pixel_job);
    ~Kernels();
    Kernels(const Kernels&) = delete;
    Kernels& operator=(const Kernels&) = delete;

    // Points binding b of the set at buffers[b] (whole buffers).
    void BindBuffers(const std::array<VkBuffer, gpu::kBindingCount>& buffers);
    // Records a dispatch of `groups` workgroups of `kernel` with `params`.
    void Dispatch(VkCommandBuffer commands, Kernel kernel, const gpu::GpuParams& params,
                  uint32_t groups) const;

private:
    explicit Kernels(VkDevice device) : device_(device) {}

    VkDevice device_;
    VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
    std::array<VkPipeline, static_cast<size_t>(Kernel::kCount)> pipelines_{};
};

}  // namespace pf::vk
