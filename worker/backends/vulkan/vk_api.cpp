// Loading the Vulkan loader at run time.
#include "worker/backends/vulkan/vk_api.h"

#include <dlfcn.h>

#include <mutex>
#include <string>

#include "absl/strings/str_cat.h"

namespace pf::vk {
absl::Status LoadLoader() {
    static std::once_flag once;
    static absl::Status status;
    std::call_once(once, [] {
        void* library = dlopen("libvulkan.so.1", RTLD_NOW | RTLD_LOCAL);
        if (library == nullptr) {
            status = absl::FailedPreconditionError(
                absl::StrCat("no Vulkan loader (libvulkan.so.1: ", dlerror(),
                             "); install libvulkan1 and a driver"));
            return;
        }
        std::string missing;
#define PF_VK_LOAD(name)                                        \
    name = reinterpret_cast<PFN_##name>(dlsym(library, #name)); \
    if (name == nullptr) absl::StrAppend(&missing, missing.empty() ? "" : ", ", #name);
        PF_VK_CORE_FUNCTIONS(PF_VK_LOAD)
#undef PF_VK_LOAD
        if (!missing.empty())
            status = absl::FailedPreconditionError(absl::StrCat(
                "the Vulkan loader libvulkan.so.1 lacks ", missing, " (older than Vulkan 1.2?)"));
    });
    return status;
}

std::string_view ResultName(VkResult result) {
    switch (result) {
#define PF_VK_NAME(code) \
    case code:           \
        return #code;
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
        default:
            return "VkResult";
    }
}

absl::Status ResultStatus(std::string_view what, VkResult result) {
    std::string message =
        absl::StrCat(std::string(what), " failed: ", std::string(ResultName(result)));
    if (ResultName(result) == "VkResult") absl::StrAppend(&message, " ", static_cast<int>(result));
    switch (result) {
        case VK_ERROR_OUT_OF_HOST_MEMORY:
        case VK_ERROR_OUT_OF_DEVICE_MEMORY:
        case VK_ERROR_TOO_MANY_OBJECTS:
        case VK_ERROR_OUT_OF_POOL_MEMORY:
            return absl::ResourceExhaustedError(message);
        case VK_ERROR_INCOMPATIBLE_DRIVER:
        case VK_ERROR_INITIALIZATION_FAILED:
        case VK_ERROR_LAYER_NOT_PRESENT:
        case VK_ERROR_EXTENSION_NOT_PRESENT:
        case VK_ERROR_FEATURE_NOT_PRESENT:
            return absl::FailedPreconditionError(message);
        case VK_ERROR_DEVICE_LOST:
            return absl::InternalError(absl::StrCat(message, " (the GPU was lost)"));
        default:
            return absl::InternalError(message);
    }
}

}  // namespace pf::vk
