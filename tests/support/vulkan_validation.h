// For tests that run the Vulkan backend: the Khronos validation layer is on for the whole
// process (and workers it starts) once this is linked, and SkipWithoutVulkan skips a test
// only where no Vulkan device exists at all (lavapipe counts as one).
#pragma once

namespace pf::testing {

// GTEST_SKIPs the calling test where the Vulkan context cannot be created for want of a
// loader, driver or usable device; fails it on any other error.
void SkipWithoutVulkan();

// Validation errors the process's Vulkan context reported so far (0 if none exists).
unsigned long long VulkanValidationErrors();

}  // namespace pf::testing
