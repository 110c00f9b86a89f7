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
// `camera` chooses among the scene's camera nodes: empty for the first in the node hierarchy
// (depth first), a number for that one in the same order, else the node's or the camera's
// name. A scene without a camera is framed as glTF viewers frame it: a 45-degree view from +z
// at the bounds' centre, far enough back that the bounding sphere fills the height (a warning
// says so).
absl::StatusOr<Scene> LoadGltf(const SceneBundle& bundle, const std::string& name,
                               const SceneLimits& limits, const std::string& camera = "");

}  // namespace pf
