// What a glTF material becomes among the materials photon mapping distinguishes
// (core/scene/material.h), for the glTF loader.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "core/scene/material.h"
#include "core/scene/texture.h"
#include "core/scene_io/image_decode.h"

namespace pf {

// The value of number `key` of a JSON object, or `fallback` where it has none.
double NumberOr(const tinygltf::Value& object, const char* key, double fallback);
// An extension's object, or null where the map has none of that name.
const tinygltf::Value* Extension(const tinygltf::ExtensionMap& extensions, const char* name);

// How AddGltfMaterial reaches a scene's textures (errors name the texture).
struct GltfTextureAccess {
    // Scene::textures' index of a glTF texture decoded as `options` say.
    std::function<absl::StatusOr<int32_t>(int gltf_texture, const ImageDecodeOptions& options)>
        index;
    // A glTF texture decoded as `options` say, for a material to bake textures of its own from.
    std::function<absl::StatusOr<Texture>(int gltf_texture, const ImageDecodeOptions& options)>
        decode;
    // Appends a texture a material made (baked) to Scene::textures; returns its index.
    std::function<int32_t(Texture texture)> add;
};

// The image photonfarm reads of a texture: its `source` (PNG or JPEG), else its
// EXT_texture_webp image; -1 where it has neither (a KTX2 image of KHR_texture_basisu alone, which
// nothing here decodes).
int GltfTextureImage(const tinygltf::Texture& texture);

// The glTF textures AddGltfMaterial may read of `material` (base colour, emissive,
// metallic-roughness, normal and its extensions', KHR_materials_pbrSpecularGlossiness's: what a
// bundle must carry); others (occlusion, ...) are not read.
std::vector<int> GltfTexturesRead(const tinygltf::Material& material);

// Appends the materials glTF material `source` becomes to `materials` and returns the index of
// the one its surfaces use; `where` ("scene.gltf: material 'wood' (#2)") begins every error
// and note. A material with KHR_materials_pbrSpecularGlossiness is read as that (its model has
// passed PrepareSpecularGlossiness, gltf_spec_gloss.h). See gltf_materials.cpp for the mapping.
absl::StatusOr<uint32_t> AddGltfMaterial(const tinygltf::Material& source, const std::string& where,
                                         const GltfTextureAccess& textures,
                                         std::vector<Material>& materials);

}  // namespace pf
