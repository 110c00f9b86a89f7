// Surface materials: what the photon mappers distinguish. Diffuse surfaces store hit points
// and photons; the others scatter specularly or glossily and are followed by every pass.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

#include "core/math/vec3.h"
#include "core/shared/gpu_types.h"
#include "core/shared/scatter.h"

namespace pf {

enum class MaterialType : uint32_t {
    kDiffuse,          // Lambertian, reflectance base_color (x texture)
    kMirror,           // perfect specular reflection, reflectance base_color
    kDielectric,       // solid glass: Fresnel reflection and refraction with index ior
    kThinDielectric,   // thin glass sheet: Fresnel reflection, straight-through transmission
    kRoughConductor,   // rough metal: GGX microfacet reflection with roughness alpha, tinted by
                       // base_color
    kRoughDielectric,  // rough solid glass: GGX microfacet reflection and refraction with index ior
    kMix,  // one of two materials at each point, the second with probability mix_amount (pbrt's
           // "mix"; Scene::Surface resolves it, core/shared/alpha.h's MixHash)
};

// Roughness below this is taken as this (core/shared/scatter.h).
using gpu::kMinRoughness;

inline constexpr int32_t kNoTexture = -1;

struct Material {
    MaterialType type = MaterialType::kDiffuse;
    Rgb base_color{0.8f};  // reflectance (diffuse, mirror) or transmission tint (glass)
    int32_t base_color_texture = kNoTexture;  // index into Scene::textures
    float ior = 1.5f;                         // index of refraction inside the dielectric
    float roughness = 0.0f;  // GGX alpha of the rough materials, in [kMinRoughness, 1]
    // Where set, the GGX alphas (roughness and coat_roughness) are theirs times this texture's
    // first channel at the point (glTF's metallicRoughnessTexture, pbrt's roughness textures:
    // the loaders map its values to alpha; Scene::ShadingMaterial).
    int32_t roughness_texture = kNoTexture;
    Rgb emission{0.0f};  // emitted radiance, W/(m^2 sr), from the front face
    // Emission is emission x this texture (index into Scene::textures) where it has one: pbrt's
    // image area lights, glTF's emissiveTexture.
    int32_t emission_texture = kNoTexture;
    // Emission from both faces (pbrt's "twosided" area lights). Not a bool: materials are
    // written byte for byte into prepared scenes, and must have no padding.
    uint32_t two_sided = 0;
    // A dielectric coat over the surface (core/shared/coat.h) on a diffuse, mirror or rough
    // conductor base: its kind (gpu::kCoatLayered: pbrt-v4's coateddiffuse and
    // coatedconductor, glTF's KHR_materials_clearcoat; gpu::kCoatFresnelMix, over a diffuse
    // base only: glTF's dielectric BRDF; gpu::kCoatNone, index 1: nothing but a sheen), index
    // of refraction (0: no coat), GGX alpha (0: smooth), the optical thickness of a layered
    // coat's absorbing interior, and a Fresnel mix's weight (glTF's specularFactor).
    uint32_t coat_kind = 0;
    float coat_ior = 0.0f;
    float coat_roughness = 0.0f;
    float coat_thickness = 0.0f;
    float coat_weight = 1.0f;
    // The most visits light pays a coat's base, each followed by its chance to leave through
    // the coat, before it is taken as absorbed: pbrt-v4's maxdepth counts crossings of the
    // layer, two a visit, so its default 10 is 5 here (pbrt_materials.cpp); glTF's coats,
    // which name none, as many as matter (gpu::kMaxCoatReturns).
    uint32_t coat_depth = 64;
    // pbrt-v4's nsamples: the walks averaged in each estimate of a coated conductor's response
    // to a punctual light (core/shared/glossy_lights.h's CoatedConductorResponse).
    uint32_t coat_samples = 1;
    // A sheen over the coat (core/shared/sheen.h, glTF's KHR_materials_sheen): its colour
    // (black: none) and roughness, times the sheen texture's colour and the sheen roughness
    // texture's first channel at the point where they are set (Scene::ShadingMaterial).
    Rgb sheen_color{0.0f};
    float sheen_roughness = 0.0f;
    int32_t sheen_texture = kNoTexture;
    int32_t sheen_roughness_texture = kNoTexture;
    // How a mirror's or rough conductor's reflectance varies with the angle of incidence
    // (core/shared/conductor.h): its kind (gpu::kConductor*; 0: the tint at every angle) and,
    // for gpu::kConductorComplex, the complex index eta + i k per channel, in vacuum.
    uint32_t conductor = 0;
    Rgb conductor_eta{1.0f};
    Rgb conductor_k{0.0f};
    // The absorption coefficients, per unit of world length and channel, of the media on the
    // two sides of the surface: `absorption` behind it (inside a solid dielectric: glTF's
    // KHR_materials_volume attenuation, pbrt's MediumInterface inside), `outside_absorption` in
    // front (pbrt's MediumInterface outside: a liquid around the glass that holds it). Light
    // crossing a length d of one keeps exp(-absorption d) (Beer-Lambert): a path segment takes
    // the medium of the side of the surface it ends at (SegmentTransmittance in
    // core/shared/scatter.h).
    Rgb absorption{0.0f};
    Rgb outside_absorption{0.0f};
    // Diffuse transmission (pbrt-v4's diffusetransmission; core/shared/translucent.h): a
    // diffuse surface reflecting base_color and letting this through to its other side, both
    // Lambertian, times transmittance_texture's colour at the point where it has one (clamped
    // to 1 there, as pbrt-v4 clamps). Black: an opaque surface. Never under a coat.
    Rgb transmittance{0.0f};
    int32_t transmittance_texture = kNoTexture;
    // Cut-outs (core/shared/alpha.h): the surface is there where alpha x the alpha texture's
    // first channel (an index into Scene::textures) is at least alpha_cutoff, or, with no
    // cutoff (0), for that fraction of the rays that meet it.
    float alpha = 1.0f;
    float alpha_cutoff = 0.0f;
    int32_t alpha_texture = kNoTexture;
    // gpu::kSurface* (core/shared/gpu_types.h): back faces that let every ray through (a glTF
    // mesh that is single-sided and open), alpha times the vertex colours' alpha, emission
    // times the vertex colours (Scene::colors).
    uint32_t surface_flags = 0;
    // kMix: the two materials (indices into Scene::materials, both below this one's) and the
    // probability of the second, times the first channel of mix_texture at the point where it
    // has one (glTF's metallic, pbrt's amount textures).
    uint32_t mix_first = 0, mix_second = 0;
    float mix_amount = 0.5f;
    int32_t mix_texture = kNoTexture;
    // The shading normal's detail (core/shared/shading_normal.h): a tangent-space normal map
    // (glTF's normalTexture, its x and y times normal_scale; pbrt's normalmap), read through the
    // vertex tangents (Scene::tangents), and a bump map (pbrt's displacement): the surface moved
    // along its normal by bump_scale x the texture's first channel, in world units.
    int32_t normal_texture = kNoTexture;
    float normal_scale = 1.0f;
    int32_t bump_texture = kNoTexture;
    float bump_scale = 1.0f;

    // Scatters into one direction (a mirror, smooth glass): a delta distribution.
    bool IsSpecular() const {
        return type == MaterialType::kMirror || type == MaterialType::kDielectric ||
               type == MaterialType::kThinDielectric;
    }
    bool IsRough() const {
        return type == MaterialType::kRoughConductor || type == MaterialType::kRoughDielectric;
    }
    bool HasCoat() const { return coat_ior > 0.0f; }
    bool HasSheen() const { return HasCoat() && !IsBlack(sheen_color); }
    // Whether a texture changes how a point shades beyond its base colour: its GGX alphas, its
    // sheen, its transmittance (Scene::ShadingMaterial).
    bool HasShadingTextures() const {
        return roughness_texture != kNoTexture || sheen_texture != kNoTexture ||
               sheen_roughness_texture != kNoTexture || transmittance_texture != kNoTexture;
    }
    // Whether the volume inside absorbs.
    bool HasVolume() const { return !IsBlack(absorption) || !IsBlack(outside_absorption); }
    // Whether some rays pass through the surface: where alpha says, or at its back faces.
    bool HasCutOuts() const {
        return alpha_texture != kNoTexture || !(alpha >= 1.0f) ||
               (surface_flags & (gpu::kSurfaceSingleSided | gpu::kSurfaceVertexAlpha)) != 0;
    }
    bool SingleSided() const { return (surface_flags & gpu::kSurfaceSingleSided) != 0; }
    bool IsEmissive() const { return !IsBlack(emission); }
    // Whether light crosses the diffuse surface to its other side.
    bool IsTranslucent() const { return !IsBlack(transmittance); }
    // Whether a texture changes its shading normal; a normal map needs vertex tangents.
    bool HasShadingDetail() const {
        return normal_texture != kNoTexture || bump_texture != kNoTexture;
    }
    // Every texture it reads: indices into Scene::textures, kNoTexture where it has none.
    std::array<int32_t, 10> Textures() const {
        return {base_color_texture,   emission_texture, alpha_texture,
                roughness_texture,    mix_texture,      normal_texture,
                bump_texture,         sheen_texture,    sheen_roughness_texture,
                transmittance_texture};
    }
    // Whether shading reads the surface's texture coordinates.
    bool ReadsUv() const {
        const std::array<int32_t, 10> textures = Textures();
        return std::any_of(textures.begin(), textures.end(),
                           [](int32_t texture) { return texture != kNoTexture; });
    }
    // Whether a surface of this material seen from its front (or back) emits.
    bool EmitsToward(bool front_facing) const {
        return (front_facing || two_sided != 0) && IsEmissive();
    }
};

// The material kinds as the shared light transport numbers them (core/shared/gpu_types.h).
static_assert(uint32_t(MaterialType::kDiffuse) == gpu::kMaterialDiffuse &&
              uint32_t(MaterialType::kMirror) == gpu::kMaterialMirror &&
              uint32_t(MaterialType::kDielectric) == gpu::kMaterialDielectric &&
              uint32_t(MaterialType::kThinDielectric) == gpu::kMaterialThinDielectric &&
              uint32_t(MaterialType::kRoughConductor) == gpu::kMaterialRoughConductor &&
              uint32_t(MaterialType::kRoughDielectric) == gpu::kMaterialRoughDielectric &&
              uint32_t(MaterialType::kMix) == gpu::kMaterialMix);

// The material's coat and conductor Fresnel term, as core/shared/coat.h and conductor.h take
// them.
inline gpu::Coat CoatOf(const Material& material) {
    return {material.coat_kind,      material.coat_ior,       material.coat_roughness,
            material.coat_thickness, material.coat_weight,    material.coat_depth,
            material.sheen_color,    material.sheen_roughness};
}
inline gpu::Conductor ConductorOf(const Material& material) {
    return {material.conductor, material.conductor_eta, material.conductor_k};
}

// The material as the shared light transport scatters by it (core/shared/scatter.h; the
// Vulkan kernels build theirs from GpuMaterial in bsdf.glsl). `material` is the one shading
// the point (Scene::ShadingMaterial: textures applied, a mix resolved).
inline gpu::Bsdf BsdfOf(const Material& material) {
    gpu::Bsdf bsdf;
    bsdf.type = uint32_t(material.type);
    bsdf.ior = material.ior;
    bsdf.roughness = material.roughness;
    bsdf.coated = material.HasCoat();
    bsdf.coat = CoatOf(material);
    bsdf.conductor = ConductorOf(material);
    bsdf.coat_samples = material.coat_samples;
    bsdf.transmittance = material.transmittance;
    return bsdf;
}

}  // namespace pf
