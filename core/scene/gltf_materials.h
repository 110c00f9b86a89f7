// What a glTF material becomes among the materials photon mapping distinguishes
// (core/scene/material.h), for the glTF loader.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "core/scene/image_decode.h"
#include "core/scene/material.h"

namespace pf {

// The value of number `key` of a JSON object, or `fallback` where it has none.
double NumberOr(const tinygltf::Value& object, const char* key, double fallback);
// An extension's object, or null where the map has none of that name.
const tinygltf::Value* Extension(const tinygltf::ExtensionMap& extensions, const char* name);

// Scene::textures' index of a glTF texture decoded as `options` say (errors name it).
using GltfTextureLookup =
    std::function<absl::StatusOr<int32_t>(int gltf_texture, const ImageDecodeOptions& options)>;

// The glTF textures AddGltfMaterial may read of `material` (base colour, emissive,
// metallic-roughness, normal and its extensions': what a bundle must carry); others (occlusion,
// ...) are not read.
std::vector<int> GltfTexturesRead(const tinygltf::Material& material);

// Appends the materials glTF material `source` becomes to `materials` and returns the index of
// the one its surfaces use; `where` ("scene.gltf: material 'wood' (#2)") begins every error
// and note. See gltf_materials.cpp for the mapping.
absl::StatusOr<uint32_t> AddGltfMaterial(const tinygltf::Material& source, const std::string& where,
                                         const GltfTextureLookup& texture,
                                         std::vector<Material>& materials);

}  // namespace pf
