// KHR_materials_pbrSpecularGlossiness (archived, yet in many published models) read as the
// metallic-roughness material the Khronos converter makes of it (the extension's
// convert-between-workflows example, three.pbrUtilities.js ConvertToMetallicRoughness), value
// by value, and texel by texel where the material has textures.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <string>

#include "absl/status/statusor.h"
#include "core/scene/material.h"
#include "core/scene_io/gltf/gltf_materials.h"

namespace pf {

// A metallic-roughness value: base colour (linear), metallic and glTF's roughness, each in [0, 1].
struct MetallicRoughnessValue {
    Rgb base_color{1.0f};
    float metallic = 0, roughness = 1;
};

// The Khronos converter's mapping of linear `diffuse`, linear `specular` (F0) and
// `glossiness`: metallic solves a quadratic in the colours' perceived brightness
// (sqrt(0.299 r^2 + 0.587 g^2 + 0.114 b^2)) against a dielectric's F0 of 0.04, the base colour
// blends the colour the diffuse part implies with the one the specular part implies by
// metallic^2 (clamped to [0, 1]), roughness is 1 - glossiness.
MetallicRoughnessValue SpecularGlossinessToMetallicRoughness(const Rgb& diffuse,
                                                             const Rgb& specular, float glossiness);

// Decides, for each material with the extension, which of its two descriptions is read: the
// specular-glossiness one where the file requires the extension or the material gives no
// metallic-roughness values of its own, else its metallic-roughness fallback (the extension is
// dropped from it). Where the specular-glossiness one is read, its textures take the
// metallic-roughness slots (diffuseTexture the base colour's, specularGlossinessTexture the
// metallic-roughness one's) and diffuseFactor the base colour's, so that texture coordinates,
// their transforms and alpha treat them as the textures they become (the values themselves are
// ConvertSpecularGlossiness's).
void PrepareSpecularGlossiness(tinygltf::Model* model);

// What a material read as specular-glossiness becomes: factors where a value is the same over
// the whole surface, else textures baked texel by texel (indices into Scene::textures).
struct ConvertedSpecularGlossiness {
    MetallicRoughnessValue factors;  // 1 where a texture holds the value
    int32_t base_color_texture = kNoTexture;
    int32_t metallic_texture = kNoTexture;
    int32_t alpha_texture = kNoTexture;  // GGX alpha: roughness squared
};

// Converts the extension's object `extension` (its factors, diffuseTexture read as sRGB colour,
// specularGlossinessTexture's colour as sRGB specular and its alpha as linear glossiness).
// Textures are baked at the larger image's resolution, each sampled bilinearly at the baked
// texel's centre (both with the base colour's texture coordinates). Errors name `where`.
absl::StatusOr<ConvertedSpecularGlossiness> ConvertSpecularGlossiness(
    const tinygltf::Value& extension, const std::string& where, const GltfTextureAccess& textures);

}  // namespace pf
