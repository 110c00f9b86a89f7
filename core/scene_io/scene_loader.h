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
    // An environment in place of the scene's own; its file is read from the bundle.
    EnvironmentSettings environment;
    // Which of a glTF scene's cameras renders (LoadGltf's `camera`); empty: the first.
    std::string camera;
};

// Loads the bundle's main file. `name` names the scene in errors (the path the user gave).
// A scene with no light at all (after options.environment) is refused, naming the way out.
absl::StatusOr<Scene> LoadScene(const SceneBundle& bundle, const std::string& name,
                                const SceneLoadOptions& options = {});
// Packs the scene at `path` into a bundle and loads that.
absl::StatusOr<Scene> LoadScene(const std::string& path, const SceneLoadOptions& options = {});

// Reads the scene at `scene_path` and every file it references (glTF buffers and images;
// pbrt Include/Import files, PLY meshes, spectra and image textures), found relative to the
// scene's folder. The bundle's root is that folder, or `scene_root` where given (a folder
// holding the scene: then references may reach its sibling folders). A reference that leaves
// the root (absolute, '..' past it, a URL) is refused naming the file and the reference.
// `render_settings`, when given, receives what the scene asks of its render (a pbrt
// Integrator and Sampler).
absl::StatusOr<SceneBundle> PackSceneBundle(const std::string& scene_path,
                                            SceneRenderSettings* render_settings = nullptr,
                                            const std::string& scene_root = "");

// The environment `settings` ask for, its image decoded from `bundle`: a latitude-longitude
// map (any format DecodeImage reads), or a colour. Errors name the file or the setting.
absl::StatusOr<Environment> MakeEnvironment(const EnvironmentSettings& settings,
                                            const SceneBundle& bundle, const SceneLimits& limits);

// Adds the image at path `environment->file` (on this machine) to `bundle`, under a name of
// its own at the bundle's root, and points `environment->file` at it; nothing without a file.
absl::Status BundleEnvironment(EnvironmentSettings* environment, SceneBundle* bundle);

// Whether `path` names a format photonfarm reads (by extension): .gltf, .glb, .pbrt.
bool IsSceneFile(const std::string& path);

}  // namespace pf
