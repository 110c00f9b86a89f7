// The Vulkan API as photonfarm loads it: libvulkan.so.1 opened at run time (so a worker
// without a Vulkan loader still starts, and says why the backend cannot), every function
// used listed once, and PF_VK_TRY, the one way a VkResult becomes an absl::Status.
#pragma once

#define VK_NO_PROTOTYPES
#include <vulkan/vulkan.h>

#include <string_view>

#include "absl/status/status.h"

namespace pf::vk {

// Core functions, which the loader exports: taken from libvulkan.so.1 itself, they serve
// every instance and device, as if linked. (Extension functions come per instance, through
// vkGetInstanceProcAddr: Context does that for debug utils.)
#define PF_VK_CORE_FUNCTIONS(X)                 \
    X(vkGetInstanceProcAddr)                    \
    X(vkCreateInstance)                         \
    X(vkEnumerateInstanceVersion)               \
    X(vkEnumerateInstanceLayerProperties)       \
    X(vkDestroyInstance)                        \
    X(vkEnumeratePhysicalDevices)               \
    X(vkGetPhysicalDeviceProperties)            \
    X(vkGetPhysicalDeviceFeatures2)             \
    X(vkGetPhysicalDeviceQueueFamilyProperties) \
    X(vkGetPhysicalDeviceMemoryProperties)      \
    X(vkEnumerateDeviceExtensionProperties)     \
    X(vkCreateDevice)                           \
    X(vkDestroyDevice)                          \
    X(vkGetDeviceQueue)                         \
    X(vkCreateBuffer)                           \
    X(vkDestroyBuffer)                          \
    X(vkGetBufferMemoryRequirements)            \
    X(vkAllocateMemory)                         \
    X(vkFreeMemory)                             \
    X(vkBindBufferMemory)                       \
    X(vkMapMemory)                              \
    X(vkUnmapMemory)                            \
    X(vkInvalidateMappedMemoryRanges)           \
    X(vkFlushMappedMemoryRanges)                \
    X(vkCreateShaderModule)                     \
    X(vkDestroyShaderModule)                    \
    X(vkCreateDescriptorSetLayout)              \
    X(vkDestroyDescriptorSetLayout)             \
    X(vkCreatePipelineLayout)                   \
    X(vkDestroyPipelineLayout)                  \
    X(vkCreateComputePipelines)                 \
    X(vkDestroyPipeline)                        \
    X(vkCreateDescriptorPool)                   \
    X(vkDestroyDescriptorPool)                  \
    X(vkAllocateDescriptorSets)                 \
    X(vkUpdateDescriptorSets)                   \
    X(vkCreateCommandPool)                      \
    X(vkDestroyCommandPool)                     \
    X(vkAllocateCommandBuffers)                 \
    X(vkBeginCommandBuffer)                     \
    X(vkEndCommandBuffer)                       \
    X(vkResetCommandBuffer)                     \
    X(vkCmdBindPipeline)                        \
    X(vkCmdBindDescriptorSets)                  \
    X(vkCmdPushConstants)                       \
    X(vkCmdDispatch)                            \
    X(vkCmdDispatchIndirect)                    \
    X(vkCmdPipelineBarrier)                     \
    X(vkCmdFillBuffer)                          \
    X(vkCmdCopyBuffer)                          \
    X(vkQueueSubmit)                            \
    X(vkCreateFence)                            \
    X(vkDestroyFence)                           \
    X(vkWaitForFences)                          \
    X(vkResetFences)                            \
    X(vkDeviceWaitIdle)

#define PF_VK_DECLARE(name) inline PFN_##name name = nullptr;
PF_VK_CORE_FUNCTIONS(PF_VK_DECLARE)
#undef PF_VK_DECLARE

// Opens the loader and takes its functions, once per process; FAILED_PRECONDITION naming
// libvulkan.so.1 where there is none, or where it lacks a function (older than Vulkan 1.2).
absl::Status LoadLoader();

std::string_view ResultName(VkResult result);
// "what failed: VK_ERROR_..." with the code that fits: out of memory is RESOURCE_EXHAUSTED,
// a missing driver or feature FAILED_PRECONDITION, anything else (a lost device) INTERNAL.
absl::Status ResultStatus(std::string_view what, VkResult result);

}  // namespace pf::vk

// Returns the failure as an absl::Status from the enclosing function.
#define PF_VK_TRY(call)                                                       \
    do {                                                                      \
        if (const VkResult pf_vk_result = (call); pf_vk_result != VK_SUCCESS) \
            return ::pf::vk::ResultStatus(#call, pf_vk_result);               \
    } while (false)
