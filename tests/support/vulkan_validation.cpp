// Linked into every test binary that runs the Vulkan backend: turns the Khronos validation
// layer on for this process and the workers it starts (they inherit the environment), before
// any test creates a Vulkan context. Context::Validating() lets tests check it took.
#include <cstdlib>

namespace {
const bool kValidationOn = setenv("PHOTONFARM_VULKAN_VALIDATION", "1", /*overwrite=*/1) == 0;
}  // namespace
