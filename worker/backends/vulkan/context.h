// A Vulkan instance and the device photonfarm computes on, shared by every job of a process:
// the device is chosen discrete GPU first, then integrated, then a CPU implementation
// (lavapipe) with a warning. With validation on (PHOTONFARM_VULKAN_VALIDATION=1, or the
// option) the Khronos layer checks every call and its messages are counted.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "worker/backends/vulkan/vk_api.h"

namespace pf::vk {

struct DeviceInfo {
    uint32_t index = 0;  // in the loader's enumeration
    std::string name;
    std::string type;  // "discrete", "integrated", "virtual", "cpu", "other"
    std::string api_version;
    uint64_t device_local_bytes = 0;  // the largest device-local heap
    std::string unusable;             // why photonfarm cannot use it; empty where it can
};

// Every device the loader reports, usable or not, in enumeration order.
absl::StatusOr<std::vector<DeviceInfo>> ListDevices();
// The device Context::Create picks among `devices`: PHOTONFARM_VULKAN_DEVICE's index where
// set (INVALID_ARGUMENT if out of range, FAILED_PRECONDITION if unusable), else the most
// preferred usable one; FAILED_PRECONDITION, listing why, where none is usable.
absl::StatusOr<uint32_t> ChooseDevice(const std::vector<DeviceInfo>& devices);

struct ContextOptions {
    bool validation = false;  // also on where PHOTONFARM_VULKAN_VALIDATION=1
};

class Context {
public:
    // FAILED_PRECONDITION where there is no loader, no driver, or no usable device.
    static absl::StatusOr<std::shared_ptr<Context>> Create(const ContextOptions& options = {});
    // The process's context, created on first use and kept while anything holds it.
    static absl::StatusOr<std::shared_ptr<Context>> Shared();
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkDevice Device() const { return device_; }
    VkQueue Queue() const { return queue_; }
    uint32_t QueueFamily() const { return queue_family_; }
    const DeviceInfo& Info() const { return info_; }
    const VkPhysicalDeviceLimits& Limits() const { return limits_; }
    const VkPhysicalDeviceMemoryProperties& Memory() const { return memory_; }
    // Validation errors reported so far by any context of this process (0 without
    // validation); warnings are only logged.
    static uint64_t ValidationErrors();
    bool Validating() const { return messenger_ != VK_NULL_HANDLE; }

private:
    Context() = default;
    static VKAPI_ATTR VkBool32 VKAPI_CALL OnMessage(
        VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
        const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);

    VkInstance instance_ = VK_NULL_HANDLE;  // the process's, not this context's own
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    PFN_vkDestroyDebugUtilsMessengerEXT destroy_messenger_ = nullptr;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queue_family_ = 0;
    DeviceInfo info_;
    VkPhysicalDeviceLimits limits_{};
    VkPhysicalDeviceMemoryProperties memory_{};
};

}  // namespace pf::vk
