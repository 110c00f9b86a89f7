// Surface materials: what the photon mapper distinguishes. Diffuse surfaces store hit points
// and photons; the others scatter specularly and are followed by both passes.
#pragma once

#include <cstdint>

#include "core/math/vec3.h"

namespace pf {

enum class MaterialType : uint32_t {
    kDiffuse,         // Lambertian, reflectance base_color (x texture)
    kMirror,          // perfect specular reflection, reflectance base_color
    kDielectric,      // solid glass: Fresnel reflection and refraction with index ior
    kThinDielectric,  // thin glass sheet: Fresnel reflection, straight-through transmission
};

inline constexpr int32_t kNoTexture = -1;

struct Material {
    MaterialType type = MaterialType::kDiffuse;
    Rgb base_color{0.8f};          // reflectance (diffuse, mirror) or transmission tint (glass)
    int32_t base_color_texture = kNoTexture;  // index into Scene::textures
    float ior = 1.5f;              // index of refraction inside the dielectric
    Rgb emission{0.0f};            // emitted radiance, W/(m^2 sr), from the front face only

    bool IsSpecular() const { return type != MaterialType::kDiffuse; }
    bool IsEmissive() const { return !IsBlack(emission); }
};

}  // namespace pf
