// Turns the Khronos validation layer on for this process and the workers it starts (they
// inherit the environment) before any test creates a Vulkan context. Linked into each test
// binary that runs the Vulkan backend.
#include "tests/support/vulkan_validation.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <string_view>

#include "worker/backends/vulkan/context.h"

namespace pf::testing {
namespace {

[[maybe_unused]] const bool kValidationOn =
    setenv("PHOTONFARM_VULKAN_VALIDATION", "1", /*overwrite=*/1) == 0;

}  // namespace

bool PrerequisitesRequired() {
    const char* ci = std::getenv("CI");
    return ci != nullptr && std::string_view(ci) == "true";
}

void SkipWithoutVulkan() {
    // Skip only where the loader, a driver or a usable device is missing; anything else (the
    // validation layer missing, say) fails the test. Under CI=true the skip is a failure.
    std::string missing;
    const absl::StatusOr<std::vector<vk::DeviceInfo>> devices = vk::ListDevices();
    if (!devices.ok()) {
        missing = "no Vulkan: " + devices.status().ToString();
    } else if (const absl::StatusOr<uint32_t> chosen = vk::ChooseDevice(*devices); !chosen.ok()) {
        missing = "no usable Vulkan device: " + chosen.status().ToString();
    }
    if (!missing.empty()) {
        if (PrerequisitesRequired()) {
            GTEST_FAIL() << missing
                         << " (CI=true requires Vulkan: install mesa-vulkan-drivers, which "
                            "deploy/install-deps.sh lists, for lavapipe)";
        }
        GTEST_SKIP() << missing;
    }
    const absl::StatusOr<std::shared_ptr<vk::Context>> context = vk::Context::Shared();
    ASSERT_TRUE(context.ok()) << context.status();
    ASSERT_TRUE((*context)->Validating())
        << "tests run the Vulkan backend under the Khronos validation layer";
}

unsigned long long VulkanValidationErrors() { return vk::Context::ValidationErrors(); }

}  // namespace pf::testing
