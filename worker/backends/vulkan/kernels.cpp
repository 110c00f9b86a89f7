// Pipelines, their layout and descriptor set.
#include "worker/backends/vulkan/kernels.h"

#include <cstdint>
#include <span>
#include <vector>

#include "core/util/check.h"

namespace pf::vk {
namespace {

// SPIR-V words compiled by glslc at build time (pf_add_shaders).
constexpr uint32_t kGridCountSpirv[] = {
#include "worker/backends/vulkan/shaders/grid_count.comp.spv.inc"
};
constexpr uint32_t kScanBlocksSpirv[] = {
#include "worker/backends/vulkan/shaders/scan_blocks.comp.spv.inc"
};
constexpr uint32_t kScanTotalsSpirv[] = {
#include "worker/backends/vulkan/shaders/scan_totals.comp.spv.inc"
};
constexpr uint32_t kScanAddSpirv[] = {
#include "worker/backends/vulkan/shaders/scan_add.comp.spv.inc"
};
constexpr uint32_t kGridFillSpirv[] = {
#include "worker/backends/vulkan/shaders/grid_fill.comp.spv.inc"
};
constexpr uint32_t kPhotonTraceSpirv[] = {
#include "worker/backends/vulkan/shaders/photon_trace.comp.spv.inc"
};
constexpr uint32_t kDirectLightSpirv[] = {
#include "worker/backends/vulkan/shaders/direct_light.comp.spv.inc"
};
constexpr uint32_t kTallyFlagsSpirv[] = {
#include "worker/backends/vulkan/shaders/tally_flags.comp.spv.inc"
};
constexpr uint32_t kTallyCompactSpirv[] = {
#include "worker/backends/vulkan/shaders/tally_compact.comp.spv.inc"
};
constexpr uint32_t kPixelTraceSpirv[] = {
#include "worker/backends/vulkan/shaders/pixel_trace.comp.spv.inc"
};
constexpr uint32_t kPathWavefrontSpirv[] = {
#include "worker/backends/vulkan/shaders/path_wavefront.comp.spv.inc"
};

// A pipeline: its code, the set that compiles it, and the wavefront's stage and class of
// vertex (kSpecWavefrontStage, kSpecVertexClass; the megakernel shades every class).
struct Pipeline {
    std::span<const uint32_t> spirv;
    KernelSet set;
    uint32_t stage = gpu::kStageStart;
    uint32_t vertex_class = gpu::kVertexAny;
};

// In the order of Kernel.
constexpr Pipeline kPipelines[] = {
    {kGridCountSpirv, KernelSet::kPhotons},
    {kScanBlocksSpirv, KernelSet::kPhotons},
    {kScanTotalsSpirv, KernelSet::kPhotons},
    {kScanAddSpirv, KernelSet::kPhotons},
    {kGridFillSpirv, KernelSet::kPhotons},
    {kPhotonTraceSpirv, KernelSet::kPhotons},
    {kDirectLightSpirv, KernelSet::kPhotons},
    {kTallyFlagsSpirv, KernelSet::kPhotons},
    {kTallyCompactSpirv, KernelSet::kPhotons},
    {kPixelTraceSpirv, KernelSet::kPixels},
    {kPathWavefrontSpirv, KernelSet::kPathWavefront, gpu::kStageStart},
    {kPathWavefrontSpirv, KernelSet::kPathWavefront, gpu::kStageExtendArgs},
    {kPathWavefrontSpirv, KernelSet::kPathWavefront, gpu::kStageExtend},
    {kPathWavefrontSpirv, KernelSet::kPathWavefront, gpu::kStageShadeArgs},
    {kPathWavefrontSpirv, KernelSet::kPathWavefront, gpu::kStageShade, gpu::kVertexDiffuse},
    {kPathWavefrontSpirv, KernelSet::kPathWavefront, gpu::kStageShade, gpu::kVertexCoated},
    {kPathWavefrontSpirv, KernelSet::kPathWavefront, gpu::kStageShade, gpu::kVertexRough},
    {kPathWavefrontSpirv, KernelSet::kPathWavefront, gpu::kStageShade, gpu::kVertexSpecular}};
static_assert(std::size(kPipelines) == static_cast<size_t>(Kernel::kCount));
static_assert(static_cast<size_t>(Kernel::kPathShadeSpecular) ==
              static_cast<size_t>(Kernel::kPathShadeDiffuse) + gpu::kVertexSpecular);

// A shader module destroyed with its scope (pipelines keep what they need).
struct ShaderModule {
    VkDevice device;
    VkShaderModule module = VK_NULL_HANDLE;
    ~ShaderModule() {
        if (module != VK_NULL_HANDLE) vkDestroyShaderModule(device, module, nullptr);
    }
};

}  // namespace

absl::StatusOr<std::unique_ptr<Kernels>> Kernels::Create(const Context& context,
                                                         const SpecConstants& spec, KernelSet set) {
    std::unique_ptr<Kernels> kernels(new Kernels(context.Device()));
    const VkDevice device = context.Device();
    std::vector<VkDescriptorSetLayoutBinding> bindings;
    for (uint32_t b = 0; b < gpu::kBindingCount; ++b)
        bindings.push_back({.binding = b,
                            .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                            .descriptorCount = 1,
                            .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT});
    const VkDescriptorSetLayoutCreateInfo set_layout{
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
        .bindingCount = static_cast<uint32_t>(bindings.size()),
        .pBindings = bindings.data()};
    PF_VK_TRY(vkCreateDescriptorSetLayout(device, &set_layout, nullptr, &kernels->set_layout_));
    const VkPushConstantRange push{
        .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT, .offset = 0, .size = sizeof(gpu::GpuParams)};
    const VkPipelineLayoutCreateInfo layout{.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
                                            .setLayoutCount = 1,
                                            .pSetLayouts = &kernels->set_layout_,
                                            .pushConstantRangeCount = 1,
                                            .pPushConstantRanges = &push};
    PF_VK_TRY(vkCreatePipelineLayout(device, &layout, nullptr, &kernels->layout_));

    const VkDescriptorPoolSize pool_size{.type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                         .descriptorCount = gpu::kBindingCount};
    const VkDescriptorPoolCreateInfo pool{.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
                                          .maxSets = 1,
                                          .poolSizeCount = 1,
                                          .pPoolSizes = &pool_size};
    PF_VK_TRY(vkCreateDescriptorPool(device, &pool, nullptr, &kernels->pool_));
    const VkDescriptorSetAllocateInfo allocate{
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
        .descriptorPool = kernels->pool_,
        .descriptorSetCount = 1,
        .pSetLayouts = &kernels->set_layout_};
    PF_VK_TRY(vkAllocateDescriptorSets(device, &allocate, &kernels->set_));

    std::array<VkSpecializationMapEntry, gpu::kSpecCount> entries;
    for (uint32_t id = 0; id < gpu::kSpecCount; ++id)
        entries[id] = {
            .constantID = id, .offset = id * uint32_t{sizeof(uint32_t)}, .size = sizeof(uint32_t)};
    for (size_t k = 0; k < kernels->pipelines_.size(); ++k) {
        const Pipeline& made = kPipelines[k];
        if (made.set != set) continue;
        // No vertex of these classes is ever queued without the feature (VertexClass).
        if ((made.vertex_class == gpu::kVertexCoated && spec[gpu::kSpecHasCoats] == 0) ||
            (made.vertex_class == gpu::kVertexRough && spec[gpu::kSpecHasRoughConductor] == 0))
            continue;
        SpecConstants values = spec;
        values[gpu::kSpecWavefrontStage] = made.stage;
        values[gpu::kSpecVertexClass] = made.vertex_class;
        const VkSpecializationInfo specialization{.mapEntryCount = gpu::kSpecCount,
                                                  .pMapEntries = entries.data(),
                                                  .dataSize = sizeof(values),
                                                  .pData = values.data()};
        ShaderModule shader{device};
        const VkShaderModuleCreateInfo module{.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
                                              .codeSize = made.spirv.size_bytes(),
                                              .pCode = made.spirv.data()};
        PF_VK_TRY(vkCreateShaderModule(device, &module, nullptr, &shader.module));
        const VkComputePipelineCreateInfo pipeline{
            .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
            .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                      .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                      .module = shader.module,
                      .pName = "main",
                      .pSpecializationInfo = &specialization},
            .layout = kernels->layout_};
        PF_VK_TRY(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &pipeline, nullptr,
                                           &kernels->pipelines_[k]));
    }
    return kernels;
}

Kernels::~Kernels() {
    for (VkPipeline pipeline : pipelines_)
        if (pipeline != VK_NULL_HANDLE) vkDestroyPipeline(device_, pipeline, nullptr);
    if (pool_ != VK_NULL_HANDLE) vkDestroyDescriptorPool(device_, pool_, nullptr);
    if (layout_ != VK_NULL_HANDLE) vkDestroyPipelineLayout(device_, layout_, nullptr);
    if (set_layout_ != VK_NULL_HANDLE) vkDestroyDescriptorSetLayout(device_, set_layout_, nullptr);
}

void Kernels::BindBuffers(const std::array<VkBuffer, gpu::kBindingCount>& buffers) {
    std::array<VkDescriptorBufferInfo, gpu::kBindingCount> infos;
    std::array<VkWriteDescriptorSet, gpu::kBindingCount> writes;
    for (uint32_t b = 0; b < gpu::kBindingCount; ++b) {
        infos[b] = {.buffer = buffers[b], .offset = 0, .range = VK_WHOLE_SIZE};
        writes[b] = {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                     .dstSet = set_,
                     .dstBinding = b,
                     .descriptorCount = 1,
                     .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                     .pBufferInfo = &infos[b]};
    }
    vkUpdateDescriptorSets(device_, gpu::kBindingCount, writes.data(), 0, nullptr);
}

void Kernels::Bind(VkCommandBuffer commands, Kernel kernel, const gpu::GpuParams& params) const {
    PF_CHECK(pipelines_[static_cast<size_t>(kernel)] != VK_NULL_HANDLE);
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE,
                      pipelines_[static_cast<size_t>(kernel)]);
    vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0,
                            nullptr);
    vkCmdPushConstants(commands, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(params), &params);
}

void Kernels::Dispatch(VkCommandBuffer commands, Kernel kernel, const gpu::GpuParams& params,
                       uint32_t groups) const {
    if (groups == 0) return;
    Bind(commands, kernel, params);
    vkCmdDispatch(commands, groups, 1, 1);
}

void Kernels::DispatchIndirect(VkCommandBuffer commands, Kernel kernel,
                               const gpu::GpuParams& params, VkBuffer arguments,
                               VkDeviceSize offset) const {
    Bind(commands, kernel, params);
    vkCmdDispatchIndirect(commands, arguments, offset);
}

}  // namespace pf::vk
