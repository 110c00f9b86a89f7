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
    // The path tracer's wavefront (path_wavefront.comp), a pipeline a stage and class of vertex.
    kPathStart,
    kPathExtendArgs,
    kPathExtend,
    kPathShadeArgs,
    kPathShadeDiffuse,
    kPathShadeCoated,
    kPathShadeRough,
    kPathShadeSpecular,
    kCount
};

// The pipelines a job compiles, so that no job compiles another's: the photon integrators'
// (ppm, sppm, rpm: the photon, direct-light, grid and tally kernels), the pixel megakernel
// (path, pm: kPixelTrace), or the path tracer's wavefront (kPath*).
enum class KernelSet { kPhotons, kPixels, kPathWavefront };

// Specialisation constant values, indexed by the kSpec* ids (0 or 1 but kSpecNearest).
using SpecConstants = std::array<uint32_t, gpu::kSpecCount>;

class Kernels {
public:
    // The pipelines of `set`, specialised with `spec` (the wavefront's each with its stage and
    // class of vertex in place of spec's).
    static absl::StatusOr<std::unique_ptr<Kernels>> Create(const Context& context,
                                                           const SpecConstants& spec,
                                                           KernelSet set);
    ~Kernels();
    Kernels(const Kernels&) = delete;
    Kernels& operator=(const Kernels&) = delete;

    // Points binding b of the set at buffers[b] (whole buffers).
    void BindBuffers(const std::array<VkBuffer, gpu::kBindingCount>& buffers);
    // Whether `kernel` was compiled: its set's, but a wavefront shading pipeline for a class of
    // vertex the scene's features rule out (coats, rough conductors).
    bool Has(Kernel kernel) const {
        return pipelines_[static_cast<size_t>(kernel)] != VK_NULL_HANDLE;
    }
    // Records a dispatch of `groups` workgroups of `kernel` with `params`.
    void Dispatch(VkCommandBuffer commands, Kernel kernel, const gpu::GpuParams& params,
                  uint32_t groups) const;
    // Records a dispatch of `kernel` whose workgroup counts a kernel wrote into `arguments` at
    // byte `offset` (VkDispatchIndirectCommand).
    void DispatchIndirect(VkCommandBuffer commands, Kernel kernel, const gpu::GpuParams& params,
                          VkBuffer arguments, VkDeviceSize offset) const;

private:
    explicit Kernels(VkDevice device) : device_(device) {}
    void Bind(VkCommandBuffer commands, Kernel kernel, const gpu::GpuParams& params) const;

    VkDevice device_;
    VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
    std::array<VkPipeline, static_cast<size_t>(Kernel::kCount)> pipelines_{};
};

}  // namespace pf::vk
