// Loading glTF 2.0 scenes (.gltf and .glb) into a world-space Scene, through tinygltf.
#pragma once

#include <string>

#include "absl/status/statusor.h"
#include "core/scene/mesh_builder.h"
#include "core/scene/scene.h"
#include "core/scene/scene_bundle.h"

namespace pf {

// Loads and validates a scene. Errors are one line naming the file and the element:
// an unreadable or malformed file, a scene without a camera or a light, NaN or Inf in a
// transform or a vertex, an index out of range. Unsupported features are logged as warnings.
// `name` prefixes the errors (the file the user gave).
// `bundle` has passed CheckSceneBundle (LoadScene checks it). Meshes used by several nodes
// are read once; images are decoded (through OpenImageIO) only where a material uses them,
// within `limits`.
absl::StatusOr<Scene> LoadGltf(const SceneBundle& bundle, const std::string& name,
                               const SceneLimits& limits);

}  // namespace pf
