// Turns the Khronos validation layer on for this process and the workers it starts (they
// inherit the environment) before any test creates a Vulkan context. Linked into each test
// binary that runs the Vulkan backend.
#include "tests/support/vulkan_validation.h"

#include <gtest/gtest.h>

#include <cstdlib>

#include "worker/backends/vulkan/context.h"

namespace pf::testing {
namespace {

[[maybe_unused]] const bool kValidationOn = setenv("PHOTONFARM_VULKAN_VALIDATION", "1", /*overwrite=*/1) == 0;

}  // namespace

void SkipWithoutVulkan() {
    const absl::StatusOr<std::shared_ptr<vk::Context>> context = vk::Context::Shared();
    if (!context.ok() && absl::IsFailedPrecondition(context.status())) {
        GTEST_SKIP() << "no Vulkan device at all: " << context.status();
    }
    ASSERT_TRUE(context.ok()) << context.status();
    ASSERT_TRUE((*context)->Validating()) << "tests run the Vulkan backend under the Khronos validation layer";
}

unsigned long long VulkanValidationErrors() { return vk::Context::ValidationErrors(); }

}  // namespace pf::testing
