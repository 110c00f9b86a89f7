// A scene bundle's files as glTF reading sees them: tinygltf's file callbacks over the bundle
// (only its files exist, nothing is written), the same lookup for the decoders that run
// before tinygltf (meshopt), and its image callback, which keeps images encoded.
#pragma once

#include <tiny_gltf.h>

#include <map>
#include <string>
#include <string_view>

#include "absl/status/statusor.h"
#include "core/scene/scene_bundle.h"

namespace pf {

// Callbacks reading `bundle`, which must outlive them.
tinygltf::FsCallbacks BundleFsCallbacks(const SceneBundle& bundle);

// The contents of bundle path `path`, or a NotFound error naming it.
absl::StatusOr<std::string_view> ReadBundleFile(const SceneBundle& bundle, const std::string& path);

// An image's encoded bytes, kept by tinygltf's image callback and decoded only if a material
// uses it; `name` carries the extension that tells OpenImageIO the format.
struct EncodedImage {
    std::string bytes, name;
};
using GltfImages = std::map<int, EncodedImage>;

// tinygltf's image callback (its user data a GltfImages): keeps the encoded bytes, decoded
// later only for images a material uses, through OpenImageIO.
bool KeepEncodedImage(tinygltf::Image* image, int index, std::string* error, std::string* warning,
                      int requested_width, int requested_height, const unsigned char* bytes,
                      int size, void* user);

}  // namespace pf
