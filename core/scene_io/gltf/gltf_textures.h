// A glTF model's textures decoded into a Scene's (through OpenImageIO, image_decode.h), each
// image once per way it is read, with the sampler's wrap modes; and the refusal of a texture
// whose only image nothing here decodes (KHR_texture_basisu's KTX2).
#pragma once

#include <tiny_gltf.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"
#include "core/scene/scene.h"
#include "core/scene_io/gltf/gltf_bundle_files.h"
#include "core/scene_io/gltf/gltf_materials.h"
#include "core/scene_io/image_decode.h"

namespace pf {

class GltfTextureReader {
public:
    // `path` begins every error; all must outlive the reader, which adds to `scene`.
    GltfTextureReader(const std::string& path, const tinygltf::Model& model,
                      const GltfImages& images, const SceneLimits& limits, Scene* scene)
        : path_(path), model_(model), images_(images), limits_(limits), scene_(scene) {}

    // Scene::textures' index of glTF texture `texture` decoded with `options` (its sampler's
    // wrap modes applied); kNoTexture for an alpha channel that is 1 everywhere (it cuts
    // nothing out). Errors name `element` and the texture: one that does not exist, a KTX2
    // image alone (KHR_texture_basisu: the way out named), an image missing or undecodable.
    // All but an alpha channel are decoded by DecodePending: their Scene::textures entries
    // are null until then (and an undecodable image's error comes from it).
    absl::StatusOr<int32_t> Index(int texture, const std::string& element,
                                  const ImageDecodeOptions& options);
    // Decodes the textures Index has left, all at once on TBB's threads (a model's dozen
    // 2048^2 PNGs); the first error in the order they were asked for.
    absl::Status DecodePending();
    // The same texture decoded, for a material to bake from; not added to the scene.
    absl::StatusOr<Texture> Decode(int texture, const std::string& element,
                                   const ImageDecodeOptions& options);
    // The three above as AddGltfMaterial reaches them, for the material `element`.
    GltfTextureAccess Access(const std::string& element);

private:
    // The image of `texture` and the options with its sampler's wrap modes.
    absl::StatusOr<std::pair<int, ImageDecodeOptions>> Source(int texture,
                                                              const std::string& element,
                                                              ImageDecodeOptions options) const;

    const std::string& path_;
    const tinygltf::Model& model_;
    const GltfImages& images_;
    const SceneLimits& limits_;
    Scene* scene_;
    // (glTF image, how it is decoded) -> Scene::textures
    std::map<std::pair<int, ImageDecodeOptions>, int32_t> indices_;
    struct Pending {
        int32_t index;  // into Scene::textures
        int texture;
        std::string element;
        ImageDecodeOptions options;
    };
    std::vector<Pending> pending_;
};

}  // namespace pf
