// A scene bundle's files as glTF reading sees them: tinygltf's file callbacks over the bundle
// (only its files exist, nothing is written) and the same lookup for the decoders that run
// before tinygltf (meshopt).
#pragma once

#include <tiny_gltf.h>

#include <string>
#include <string_view>

#include "absl/status/statusor.h"
#include "core/scene/scene_bundle.h"

namespace pf {

// Callbacks reading `bundle`, which must outlive them.
tinygltf::FsCallbacks BundleFsCallbacks(const SceneBundle& bundle);

// The contents of bundle path `path`, or a NotFound error naming it.
absl::StatusOr<std::string_view> ReadBundleFile(const SceneBundle& bundle, const std::string& path);

}  // namespace pf
