// For tests that run the Vulkan backend: the Khronos validation layer is on for the whole
// process (and workers it starts) once this is linked, and SkipWithoutVulkan skips a test
// only where no Vulkan device exists at all (lavapipe counts as one) — and fails it instead
// under CI=true, where a missing driver is a broken machine, not a reason to ship untested.
#pragma once

#include <string>

namespace pf::testing {

// True where the suite runs as CI runs it (CI=true): a prerequisite a test would skip for
// must be there, and its absence fails the test.
bool PrerequisitesRequired();

// GTEST_SKIPs the calling test (or, under CI=true, fails it fatally) where the Vulkan context
// cannot be created for want of a loader, driver or usable device; fails it on any other
// error. Callers return when IsSkipped() || HasFatalFailure().
void SkipWithoutVulkan();

// Validation errors the process's Vulkan context reported so far (0 if none exists).
unsigned long long VulkanValidationErrors();

}  // namespace pf::testing
