// Loading pbrt-v4 scenes (https://pbrt.org/fileformat-v4): the subset photon-mapping scenes
// use, mapped onto photonfarm's materials and lights. What the format has and photonfarm does
// not is a warning naming file:line:column, or an error where ignoring it would make the
// picture wrong; docs/scenes.md lists the mapping.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "core/scene/mesh_builder.h"
#include "core/scene/scene.h"
#include "core/scene_io/scene_files.h"

namespace pf {

struct PbrtLoadOptions {
    SceneLimits limits;
    // Read every file the scene references (Include, Import, PLY meshes, images), but decode
    // none and build nothing: how a bundle is packed.
    bool references_only = false;
    // Where warnings also go (they are always logged); may be null.
    std::vector<std::string>* warnings = nullptr;
};

// Loads `main_file` (a bundle path) and what it includes from `files`. `display_root` is
// prefixed to bundle paths in messages (the folder the user named the scene in).
absl::StatusOr<Scene> LoadPbrt(SceneFiles& files, const std::string& main_file,
                               const std::string& display_root, const PbrtLoadOptions& options);

}  // namespace pf
