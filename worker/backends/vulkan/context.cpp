// Instance, device choice and device creation.
#include "worker/backends/vulkan/context.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <mutex>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "core/shared/gpu_types.h"

namespace pf::vk {
namespace {

std::atomic<uint64_t> validation_errors{0};

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
constexpr uint32_t kApiVersion = VK_API_VERSION_1_2;

bool ValidationRequested(const ContextOptions& options) {
    const char* env = std::getenv("PHOTONFARM_VULKAN_VALIDATION");
    return options.validation || (env != nullptr && std::strcmp(env, "1") == 0);
}

// An instance destroyed with its scope unless taken from it (ProcessInstance takes it).
struct InstanceHolder {
    VkInstance instance = VK_NULL_HANDLE;
    ~InstanceHolder() {
        if (instance != VK_NULL_HANDLE) vkDestroyInstance(instance, nullptr);
    }
};

absl::Status CheckValidationAvailable() {
    uint32_t count = 0;
    PF_VK_TRY(vkEnumerateInstanceLayerProperties(&count, nullptr));
    std::vector<VkLayerProperties> layers(count);
    PF_VK_TRY(vkEnumerateInstanceLayerProperties(&count, layers.data()));
    for (const VkLayerProperties& layer : layers)
        if (std::strcmp(layer.layerName, kValidationLayer) == 0) return absl::OkStatus();
    return absl::FailedPreconditionError(
        absl::StrCat("Vulkan validation was asked for, but ", kValidationLayer,
                     " is not installed (Debian package vulkan-validationlayers)"));
}

absl::Status CreateInstance(bool validation, InstanceHolder& holder) {
    if (absl::Status status = LoadLoader(); !status.ok()) return status;
    uint32_t version = 0;
    PF_VK_TRY(vkEnumerateInstanceVersion(&version));
    if (version < kApiVersion)
        return absl::FailedPreconditionError(
            absl::StrCat("the Vulkan loader supports Vulkan ", VK_API_VERSION_MAJOR(version), ".",
                         VK_API_VERSION_MINOR(version), "; photonfarm needs 1.2"));
    if (validation)
        if (absl::Status status = CheckValidationAvailable(); !status.ok()) return status;
    const VkApplicationInfo application{.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
                                        .pApplicationName = "photonfarm",
                                        .applicationVersion = 1,
                                        .pEngineName = "photonfarm",
                                        .engineVersion = 1,
                                        .apiVersion = kApiVersion};
    const char* layers[] = {kValidationLayer};
    const char* extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
    const VkInstanceCreateInfo info{.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
                                    .pApplicationInfo = &application,
                                    .enabledLayerCount = validation ? 1u : 0u,
                                    .ppEnabledLayerNames = layers,
                                    .enabledExtensionCount = validation ? 1u : 0u,
                                    .ppEnabledExtensionNames = extensions};
    const VkResult result = vkCreateInstance(&info, nullptr, &holder.instance);
    if (result == VK_ERROR_INCOMPATIBLE_DRIVER)
        return absl::FailedPreconditionError(
            "no Vulkan driver (vkCreateInstance: VK_ERROR_INCOMPATIBLE_DRIVER); install one, or "
            "mesa-vulkan-drivers "
            "for the CPU implementation lavapipe");
    PF_VK_TRY(result);
    return absl::OkStatus();
}

// The process's instance (one with the validation layer, one without), made on first use and
// kept until the process ends. The loader unloads the driver with the last instance, and
// NVIDIA's (libGLX_nvidia, driver 580) does not come back after enough of that: on an H200,
// after some 25 instance lifetimes in one process, vkCreateInstance failed with
// VK_ERROR_INCOMPATIBLE_DRIVER. A worker makes a context per job, tests many. A failure is
// not kept: the next call tries again.
absl::StatusOr<VkInstance> ProcessInstance(bool validation) {
    static std::mutex mutex;
    static VkInstance instances[2] = {VK_NULL_HANDLE, VK_NULL_HANDLE};
    std::lock_guard lock(mutex);
    VkInstance& instance = instances[validation ? 1 : 0];
    if (instance != VK_NULL_HANDLE) return instance;
    InstanceHolder holder;
    if (absl::Status status = CreateInstance(validation, holder); !status.ok()) return status;
    instance = std::exchange(holder.instance, VK_NULL_HANDLE);
    return instance;
}

std::string TypeName(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
            return "discrete";
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
            return "integrated";
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
            return "virtual";
        case VK_PHYSICAL_DEVICE_TYPE_CPU:
            return "cpu";
        default:
            return "other";
    }
}

// Discrete before integrated before virtual before a CPU implementation.
int Preference(const std::string& type) {
    static const char* order[] = {"discrete", "integrated", "virtual", "cpu", "other"};
    return static_cast<int>(std::find(std::begin(order), std::end(order), type) -
                            std::begin(order));
}

// The queue family photonfarm submits to: one with compute, or none (-1).
int ComputeQueueFamily(VkPhysicalDevice device) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
    for (uint32_t i = 0; i < count; ++i)
        if (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) return static_cast<int>(i);
    return -1;
}

DeviceInfo Describe(VkPhysicalDevice device, uint32_t index) {
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(device, &properties);
    VkPhysicalDeviceMemoryProperties memory;
    vkGetPhysicalDeviceMemoryProperties(device, &memory);
    DeviceInfo info;
    info.index = index;
    info.name = properties.deviceName;
    info.type = TypeName(properties.deviceType);
    info.api_version = absl::StrCat(VK_API_VERSION_MAJOR(properties.apiVersion), ".",
                                    VK_API_VERSION_MINOR(properties.apiVersion), ".",
                                    VK_API_VERSION_PATCH(properties.apiVersion));
    for (uint32_t h = 0; h < memory.memoryHeapCount; ++h)
        if (memory.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
            info.device_local_bytes =
                std::max<uint64_t>(info.device_local_bytes, memory.memoryHeaps[h].size);
    VkPhysicalDeviceVulkan12Features features12{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceFeatures2 features{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2,
                                       .pNext = &features12};
    if (properties.apiVersion < kApiVersion) {
        info.unusable = "supports only Vulkan " + info.api_version + " (1.2 needed)";
        return info;
    }
    vkGetPhysicalDeviceFeatures2(device, &features);
    if (!features.features.shaderInt64)
        info.unusable = "no 64-bit integers in shaders (shaderInt64)";
    else if (!features12.shaderBufferInt64Atomics)
        info.unusable = "no 64-bit buffer atomics (shaderBufferInt64Atomics)";
    else if (ComputeQueueFamily(device) < 0)
        info.unusable = "no compute queue";
    else if (properties.limits.maxPerStageDescriptorStorageBuffers < gpu::kBindingCount)
        info.unusable =
            absl::StrCat("binds ", properties.limits.maxPerStageDescriptorStorageBuffers,
                         " storage buffers a kernel, ", gpu::kBindingCount, " needed");
    return info;
}

absl::StatusOr<std::vector<VkPhysicalDevice>> PhysicalDevices(VkInstance instance) {
    uint32_t count = 0;
    PF_VK_TRY(vkEnumeratePhysicalDevices(instance, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    PF_VK_TRY(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
    devices.resize(count);
    return devices;
}

}  // namespace

absl::StatusOr<std::vector<DeviceInfo>> ListDevices() {
    const absl::StatusOr<VkInstance> instance = ProcessInstance(false);
    if (!instance.ok()) return instance.status();
    absl::StatusOr<std::vector<VkPhysicalDevice>> devices = PhysicalDevices(*instance);
    if (!devices.ok()) return devices.status();
    std::vector<DeviceInfo> infos;
    for (uint32_t i = 0; i < devices->size(); ++i) infos.push_back(Describe((*devices)[i], i));
    return infos;
}

absl::StatusOr<uint32_t> ChooseDevice(const std::vector<DeviceInfo>& devices) {
    if (const char* wanted = std::getenv("PHOTONFARM_VULKAN_DEVICE");
        wanted != nullptr && *wanted != '\0') {
        uint32_t index = 0;
        if (!absl::SimpleAtoi(wanted, &index) || index >= devices.size())
            return absl::InvalidArgumentError(
                absl::StrCat("PHOTONFARM_VULKAN_DEVICE=", wanted, ": there are ", devices.size(),
                             " Vulkan devices (photonfarm-worker --list-devices)"));
        if (!devices[index].unusable.empty())
            return absl::FailedPreconditionError(
                absl::StrCat("Vulkan device ", index, " (", devices[index].name,
                             ") cannot run photonfarm: ", devices[index].unusable));
        return index;
    }
    int chosen = -1;
    for (uint32_t i = 0; i < devices.size(); ++i)
        if (devices[i].unusable.empty() &&
            (chosen < 0 || Preference(devices[i].type) < Preference(devices[chosen].type)))
            chosen = static_cast<int>(i);
    if (chosen >= 0) return static_cast<uint32_t>(chosen);
    std::string reasons;
    for (const DeviceInfo& info : devices)
        absl::StrAppend(&reasons, "; ", info.name, ": ", info.unusable);
    return absl::FailedPreconditionError(absl::StrCat("no Vulkan device photonfarm can use (",
                                                      devices.size(), " found", reasons, ")"));
}

absl::StatusOr<std::shared_ptr<Context>> Context::Create(const ContextOptions& options) {
    const bool validation = ValidationRequested(options);
    const absl::StatusOr<VkInstance> instance = ProcessInstance(validation);
    if (!instance.ok()) return instance.status();
    std::shared_ptr<Context> context(new Context());
    context->instance_ = *instance;
    if (validation) {
        const VkDebugUtilsMessengerCreateInfoEXT info{
            .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
            .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
            .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                           VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                           VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
            .pfnUserCallback = &Context::OnMessage};
        const auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(context->instance_, "vkCreateDebugUtilsMessengerEXT"));
        context->destroy_messenger_ = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(context->instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (create == nullptr || context->destroy_messenger_ == nullptr)
            return absl::FailedPreconditionError(
                "the Vulkan loader does not provide VK_EXT_debug_utils for validation");
        PF_VK_TRY(create(context->instance_, &info, nullptr, &context->messenger_));
    }

    absl::StatusOr<std::vector<VkPhysicalDevice>> devices = PhysicalDevices(context->instance_);
    if (!devices.ok()) return devices.status();
    std::vector<DeviceInfo> infos;
    for (uint32_t i = 0; i < devices->size(); ++i) infos.push_back(Describe((*devices)[i], i));
    absl::StatusOr<uint32_t> chosen = ChooseDevice(infos);
    if (!chosen.ok()) return chosen.status();
    context->info_ = infos[*chosen];
    context->physical_ = (*devices)[*chosen];
    if (context->info_.type == "cpu")
        spdlog::warn(
            "Vulkan: no GPU, computing on the CPU implementation '{}' (the cpu backend is faster "
            "here)",
            context->info_.name);
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(context->physical_, &properties);
    context->limits_ = properties.limits;
    vkGetPhysicalDeviceMemoryProperties(context->physical_, &context->memory_);
    context->queue_family_ = static_cast<uint32_t>(ComputeQueueFamily(context->physical_));

    const float priority = 1.0f;
    const VkDeviceQueueCreateInfo queue{.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
                                        .queueFamilyIndex = context->queue_family_,
                                        .queueCount = 1,
                                        .pQueuePriorities = &priority};
    VkPhysicalDeviceVulkan12Features features12{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
        .shaderBufferInt64Atomics = VK_TRUE};
    VkPhysicalDeviceFeatures2 features{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2,
                                       .pNext = &features12};
    features.features.shaderInt64 = VK_TRUE;
    const VkDeviceCreateInfo info{.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
                                  .pNext = &features,
                                  .queueCreateInfoCount = 1,
                                  .pQueueCreateInfos = &queue};
    PF_VK_TRY(vkCreateDevice(context->physical_, &info, nullptr, &context->device_));
    vkGetDeviceQueue(context->device_, context->queue_family_, 0, &context->queue_);
    spdlog::info("Vulkan device: {} ({}, Vulkan {}){}", context->info_.name, context->info_.type,
                 context->info_.api_version, validation ? ", validation on" : "");
    return context;
}

absl::StatusOr<std::shared_ptr<Context>> Context::Shared() {
    static std::mutex mutex;
    static std::weak_ptr<Context> shared;
    std::lock_guard lock(mutex);
    if (std::shared_ptr<Context> context = shared.lock()) return context;
    absl::StatusOr<std::shared_ptr<Context>> context = Create();
    if (context.ok()) shared = *context;
    return context;
}

Context::~Context() {
    if (device_ != VK_NULL_HANDLE) {
        vkDeviceWaitIdle(device_);
        vkDestroyDevice(device_, nullptr);
    }
    if (messenger_ != VK_NULL_HANDLE) destroy_messenger_(instance_, messenger_, nullptr);
    // The instance is the process's (ProcessInstance), kept.
}

uint64_t Context::ValidationErrors() { return validation_errors.load(); }

VKAPI_ATTR VkBool32 VKAPI_CALL Context::OnMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                  VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                                  const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                  void* /*user*/) {
    const char* message = data != nullptr && data->pMessage != nullptr ? data->pMessage : "";
    if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
        ++validation_errors;
        spdlog::error("Vulkan validation: {}", message);
    } else {
        spdlog::warn("Vulkan validation: {}", message);
    }
    return VK_FALSE;
}

}  // namespace pf::vk
