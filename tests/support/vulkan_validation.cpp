// Turns the Khronos validation layer on for this process and the workers it starts (they
// inherit the environment) before any test creates a Vulkan context. Linked into each test
// binary that runs the Vulkan backend.
#include "tests/support/vulkan_validation.h"

#include <gtest/gtest.h>

#include <cstdlib>

#include "worker/backends/vulkan/context.h"

namespace pf::testing {
namespace {

[[maybe_unused]] const bool kValidationOn =
    setenv("PHOTONFARM_VULKAN_VALIDATION", "1", /*overwrite=*/1) == 0;

}  // namespace

void SkipWithoutVulkan() {
    // Skip only where the loader, a driver or a usable device is missing; anything else (the
    // validation layer missing, say) fails the test.
    const absl::StatusOr<std::vector<vk::DeviceInfo>> devices = vk::ListDevices();
    if (!devices.ok()) {
        GTEST_SKIP() << "no Vulkan: " << devices.status();
    }
    if (const absl::StatusOr<uint32_t> chosen = vk::ChooseDevice(*devices); !chosen.ok()) {
        GTEST_SKIP() << "no usable Vulkan device: " << chosen.status();
    }
    const absl::StatusOr<std::shared_ptr<vk::Context>> context = vk::Context::Shared();
    ASSERT_TRUE(context.ok()) << context.status();
    ASSERT_TRUE((*context)->Validating())
        << "tests run the Vulkan backend under the Khronos validation layer";
}

unsigned long long VulkanValidationErrors() { return vk::Context::ValidationErrors(); }

}  // namespace pf::testing
