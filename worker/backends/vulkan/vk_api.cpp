// Loading the Vulkan loader at run time.
#include "worker/backends/vulkan/vk_api.h"

#include <dlfcn.h>

#include <mutex>
#include <string>

#include "absl/strings/str_cat.h"

namespace pf::vk {
namespace {

PFN_vkGetInstanceProcAddr get_instance_proc_addr = nullptr;

}  // namespace

absl::Status LoadLoader() {
    static std::once_flag once;
    static absl::Status status;
    std::call_once(once, [] {
        void* library = dlopen("libvulkan.so.1", RTLD_NOW | RTLD_LOCAL);
        if (library == nullptr) {
            status = absl::FailedPreconditionError(
                absl::StrCat("no Vulkan loader (libvulkan.so.1: ", dlerror(), "); install libvulkan1 and a driver"));
            return;
        }
        get_instance_proc_addr = reinterpret_cast<PFN_vkGetInstanceProcAddr>(dlsym(library, "vkGetInstanceProcAddr"));
        if (get_instance_proc_addr == nullptr) {
            status = absl::FailedPreconditionError("libvulkan.so.1 has no vkGetInstanceProcAddr");
            return;
        }
#define PF_VK_LOAD(name) name = reinterpret_cast<PFN_##name>(get_instance_proc_addr(nullptr, #name));
        PF_VK_GLOBAL_FUNCTIONS(PF_VK_LOAD)
#undef PF_VK_LOAD
        if (vkCreateInstance == nullptr || vkEnumerateInstanceVersion == nullptr)
            status = absl::FailedPreconditionError("the Vulkan loader is older than Vulkan 1.1");
    });
    return status;
}

void LoadInstanceFunctions(VkInstance instance) {
#define PF_VK_LOAD(name) name = reinterpret_cast<PFN_##name>(get_instance_proc_addr(instance, #name));
    PF_VK_INSTANCE_FUNCTIONS(PF_VK_LOAD)
#undef PF_VK_LOAD
}

std::string_view ResultName(VkResult result) {
    switch (result) {
#define PF_VK_NAME(code) \
    case code: return #code;
        PF_VK_NAME(VK_SUCCESS)
        PF_VK_NAME(VK_NOT_READY)
        PF_VK_NAME(VK_TIMEOUT)
        PF_VK_NAME(VK_INCOMPLETE)
        PF_VK_NAME(VK_ERROR_OUT_OF_HOST_MEMORY)
        PF_VK_NAME(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        PF_VK_NAME(VK_ERROR_INITIALIZATION_FAILED)
        PF_VK_NAME(VK_ERROR_DEVICE_LOST)
        PF_VK_NAME(VK_ERROR_MEMORY_MAP_FAILED)
        PF_VK_NAME(VK_ERROR_LAYER_NOT_PRESENT)
        PF_VK_NAME(VK_ERROR_EXTENSION_NOT_PRESENT)
        PF_VK_NAME(VK_ERROR_FEATURE_NOT_PRESENT)
        PF_VK_NAME(VK_ERROR_INCOMPATIBLE_DRIVER)
        PF_VK_NAME(VK_ERROR_TOO_MANY_OBJECTS)
        PF_VK_NAME(VK_ERROR_FORMAT_NOT_SUPPORTED)
        PF_VK_NAME(VK_ERROR_OUT_OF_POOL_MEMORY)
#undef PF_VK_NAME
        default: return "VkResult";
    }
}

absl::Status ResultStatus(std::string_view what, VkResult result) {
    std::string message = absl::StrCat(std::string(what), " failed: ", std::string(ResultName(result)));
    if (ResultName(result) == "VkResult") absl::StrAppend(&message, " ", static_cast<int>(result));
    switch (result) {
        case VK_ERROR_OUT_OF_HOST_MEMORY:
        case VK_ERROR_OUT_OF_DEVICE_MEMORY:
        case VK_ERROR_TOO_MANY_OBJECTS:
        case VK_ERROR_OUT_OF_POOL_MEMORY: return absl::ResourceExhaustedError(message);
        case VK_ERROR_INCOMPATIBLE_DRIVER:
        case VK_ERROR_INITIALIZATION_FAILED:
        case VK_ERROR_LAYER_NOT_PRESENT:
        case VK_ERROR_EXTENSION_NOT_PRESENT:
        case VK_ERROR_FEATURE_NOT_PRESENT: return absl::FailedPreconditionError(message);
        case VK_ERROR_DEVICE_LOST: return absl::UnavailableError(message);
        default: return absl::InternalError(message);
    }
}

}  // namespace pf::vk
