// Loading a scene from any format photonfarm reads, chosen by the main file's extension:
// glTF 2.0 (.gltf, .glb) and pbrt-v4 (.pbrt). Every load reads from a bundle, so nothing
// outside the scene's folder is ever read.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "core/scene/mesh_builder.h"
#include "core/scene/scene.h"
#include "core/scene/scene_bundle.h"

namespace pf {

struct SceneLoadOptions {
    SceneLimits limits;
    std::vector<std::string>* warnings = nullptr;  // also logged; pbrt scenes only, may be null
    // Give a scene with textures its TextureFilter (what the camera pass reads); workers, which
    // trace photons only, leave it out.
    bool texture_filter = true;
};

// Loads the bundle's main file. `name` names the scene in errors (the path the user gave).
absl::StatusOr<Scene> LoadScene(const SceneBundle& bundle, const std::string& name,
                                const SceneLoadOptions& options = {});
// Packs the scene at `path` into a bundle and loads that.
absl::StatusOr<Scene> LoadScene(const std::string& path, const SceneLoadOptions& options = {});

// Reads the scene at `scene_path` and every file it references (glTF buffers and images;
// pbrt Include/Import files, PLY meshes and image textures), found relative to the scene's
// folder. A reference that leaves the folder (absolute, '..' past the root, a URL) is
// refused naming the file and the reference.
absl::StatusOr<SceneBundle> PackSceneBundle(const std::string& scene_path);

// Whether `path` names a format photonfarm reads (by extension): .gltf, .glb, .pbrt.
bool IsSceneFile(const std::string& path);

}  // namespace pf
