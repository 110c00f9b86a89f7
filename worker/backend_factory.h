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

// The names CreateBackend accepts, for --backend's help and checks.
std::vector<std::string> BackendNames();

// A backend for jobs over `scene` (which must outlive it): "cpu" (Embree, the default).
// INVALID_ARGUMENT for an unknown name; the backend's own errors otherwise.
absl::StatusOr<std::unique_ptr<Backend>> CreateBackend(std::string_view name, const Scene& scene);

}  // namespace pf
