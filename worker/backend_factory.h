// Backends by name, each built for one job's scene and owning what it needs for it.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "absl/status/statusor.h"
#include "core/scene/scene.h"
#include "worker/backend.h"

namespace pf {

// A backend for jobs over `scene` (which must outlive it): "cpu" (Embree, the default) or
// "vulkan" (compute kernels on the process's Vulkan device, shared by its backends).
// INVALID_ARGUMENT for an unknown name; the backend's own errors otherwise.
absl::StatusOr<std::unique_ptr<Backend>> CreateBackend(std::string_view name, const Scene& scene);

// The device a backend computes on, kept open while this lives, so that a worker fails at
// start rather than at its first lease and its jobs share one device.
struct BackendDevice {
    std::shared_ptr<void> handle;  // null for the cpu backend
    std::string description;       // "cpu", or "vulkan: <device name>", for worker listings
};

// Opens the device backend `name` computes on; the device's error (no loader, no driver, no
// usable device) where it cannot.
absl::StatusOr<BackendDevice> OpenBackendDevice(std::string_view name);

// Errors the Vulkan validation layer reported in this process (PHOTONFARM_VULKAN_VALIDATION=1).
uint64_t BackendValidationErrors();

// What each backend would run on here, one line each: the CPU's threads, every Vulkan device
// (the one the vulkan backend picks marked, unusable ones with the reason), or why Vulkan is
// unavailable. For photonfarm-worker --list-devices.
std::string DescribeDevices(int cpu_threads);

}  // namespace pf
