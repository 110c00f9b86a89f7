// glTF materials (the core specification's metallic-roughness model and the KHR_materials_*
// extensions read here) mapped to the materials photon mapping distinguishes:
//  - transmission > 0 with KHR_materials_volume: solid glass (refracts, index from
//    KHR_materials_ior, default 1.5), rough glass where roughness > 0; transmission alone: a
//    thin sheet that does not refract;
//  - otherwise glTF's BRDF, mix(dielectric, metal, metallic):
//    the dielectric a Lambertian base under a Fresnel mix (core/shared/coat.h: GGX specular of
//    F0 from the index, KHR_materials_specular's factor and colour applied), the metal a mirror
//    or GGX conductor of Schlick's Fresnel with F0 the base colour; metallic between 0 and 1, or
//    from the metallicRoughnessTexture's blue channel, is a mix choosing the metal with that
//    probability at each point (Material::kMix); roughness squared is the GGX alpha of both, times
//    the texture's green channel squared where it has one (Material::roughness_texture);
//  - KHR_materials_clearcoat: a layered coat of index 1.5 over either (the dielectric's own
//    specular layer, under a coat of about its index, is dropped), mixed with the uncoated
//    surface where clearcoatFactor (times clearcoatTexture's red channel) is below 1; its
//    roughness times clearcoatRoughnessTexture's green channel over the dielectric.
// Emission is emissiveFactor x emissiveTexture x KHR_materials_emissive_strength, radiance in
// W/(m^2 sr), from the front face, and the back one too where the material is doubleSided.
// alphaMode MASK and BLEND cut the surface out where alpha says; normalTexture tilts the
// shading normal (Material::normal_texture).
// KHR_materials_unlit: an emitter of radiance the base colour (factor x texture x vertex
// colour) over a black BSDF: the surface shows its colour and reflects nothing.
// KHR_materials_pbrSpecularGlossiness: the metallic-roughness material the Khronos converter
// makes of it (gltf_spec_gloss.h).
#include "core/scene_io/gltf/gltf_materials.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "core/scene_io/gltf/gltf_spec_gloss.h"
#include "core/shared/coat.h"
#include "core/shared/conductor.h"

namespace pf {

double NumberOr(const tinygltf::Value& object, const char* key, double fallback) {
    if (!object.IsObject() || !object.Has(key) || !object.Get(key).IsNumber()) return fallback;
    return object.Get(key).GetNumberAsDouble();
}

const tinygltf::Value* Extension(const tinygltf::ExtensionMap& extensions, const char* name) {
    const auto it = extensions.find(name);
    return it == extensions.end() ? nullptr : &it->second;
}

namespace {

// The index of a texture named by `key` ({"index": n}) in an extension's object; -1 without.
int ExtensionTexture(const tinygltf::Value& extension, const char* key) {
    if (!extension.Has(key) || !extension.Get(key).IsObject()) return -1;
    return static_cast<int>(NumberOr(extension.Get(key), "index", -1));
}

// The index with Schlick normal-incidence reflectance f0 (in [0, 1)).
float IorOfF0(double f0) {
    const double r = std::sqrt(std::clamp(f0, 0.0, 0.99));
    return static_cast<float>((1 + r) / (1 - r));
}

class GltfMaterialBuilder {
public:
    // `spec_gloss`: the values of a material read as specular-glossiness, which stand for its
    // metallic-roughness ones (null for others).
    GltfMaterialBuilder(const tinygltf::Material& source, const std::string& where,
                        const GltfTextureAccess& textures, std::vector<Material>& materials,
                        const ConvertedSpecularGlossiness* spec_gloss = nullptr)
        : source_(source),
          where_(where),
          textures_(textures),
          materials_(materials),
          spec_gloss_(spec_gloss) {}

    absl::StatusOr<uint32_t> Build();

private:
    absl::Status Error(const std::string& what) const {
        return absl::InvalidArgumentError(absl::StrCat(where_, ": ", what));
    }
    // The base colour, its texture, emission and the faces it is drawn on.
    absl::Status ReadCommon(Material& material);
    // The cut-outs of alphaMode, set on the material its surfaces use.
    absl::Status ReadAlpha(Material& material);
    // The metallic-roughness model's materials; returns the one surfaces use.
    absl::StatusOr<uint32_t> MetallicRoughness(const Material& common);
    // KHR_materials_unlit's emitter; returns it.
    absl::StatusOr<uint32_t> Unlit(const Material& common);
    // KHR_materials_sheen, kept in sheen_ until Sheened puts it over each surface.
    absl::Status ReadSheen();
    // `material` with the sheen over it: over its coat, or, uncoated, over no coat at all
    // (gpu::kCoatNone, index 1).
    Material Sheened(Material material) const {
        if (IsBlack(sheen_.sheen_color)) return material;
        if (!material.HasCoat()) {
            material.coat_kind = gpu::kCoatNone;
            material.coat_ior = 1.0f;
            material.coat_roughness = material.coat_thickness = 0.0f;
        }
        material.sheen_color = sheen_.sheen_color;
        material.sheen_roughness = sheen_.sheen_roughness;
        material.sheen_texture = sheen_.sheen_texture;
        material.sheen_roughness_texture = sheen_.sheen_roughness_texture;
        return material;
    }
    // The index of a new material; of a new mix of `first` and `second`, emitting as `common`.
    uint32_t Add(const Material& material) {
        materials_.push_back(material);
        return static_cast<uint32_t>(materials_.size() - 1);
    }
    uint32_t Mix(const Material& common, uint32_t first, uint32_t second, float amount,
                 int32_t texture) {
        Material mix = common;
        mix.type = MaterialType::kMix;
        mix.mix_first = first, mix.mix_second = second;
        mix.mix_amount = amount, mix.mix_texture = texture;
        return Add(mix);
    }
    // glTF texture `index` as one linear channel of it in every channel (to `exponent`).
    absl::StatusOr<int32_t> ChannelTexture(int index, ImageChannels channel,
                                           double exponent = 1) const {
        ImageDecodeOptions options;
        options.encoding = ImageEncoding::kLinear;
        options.channels = channel;
        options.exponent = exponent;
        return textures_.index(index, options);
    }
    void NoteTextureLeftOut(const tinygltf::Value& extension, const char* name,
                            std::initializer_list<const char*> keys, const char* instead) const {
        for (const char* key : keys)
            if (ExtensionTexture(extension, key) >= 0)
                spdlog::warn("{}: {}'s {} is left out ({})", where_, name, key, instead);
    }

    const tinygltf::Material& source_;
    const std::string& where_;
    const GltfTextureAccess& textures_;
    std::vector<Material>& materials_;
    const ConvertedSpecularGlossiness* spec_gloss_;
    Material sheen_;  // its sheen fields only
};

absl::Status GltfMaterialBuilder::ReadCommon(Material& material) {
    const auto& pbr = source_.pbrMetallicRoughness;
    if (pbr.baseColorFactor.size() == 4)
        material.base_color =
            Rgb(Vec3d(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2]));
    if (!IsFinite(material.base_color) || MaxComponent(material.base_color) > 1.0f ||
        MinComponent(material.base_color) < 0)
        return Error("baseColorFactor must lie in [0, 1]");
    ImageDecodeOptions colour;  // glTF's colour textures are sRGB-encoded
    colour.encoding = ImageEncoding::kSrgb;
    if (spec_gloss_ != nullptr) {  // converted, baked where it varies
        material.base_color = spec_gloss_->factors.base_color;
        material.base_color_texture = spec_gloss_->base_color_texture;
    } else if (pbr.baseColorTexture.index >= 0) {
        const absl::StatusOr<int32_t> texture = textures_.index(pbr.baseColorTexture.index, colour);
        if (!texture.ok()) return texture.status();
        material.base_color_texture = *texture;
    }
    double strength = 1.0;
    if (const tinygltf::Value* e = Extension(source_.extensions, "KHR_materials_emissive_strength"))
        strength = NumberOr(*e, "emissiveStrength", 1.0);
    if (source_.emissiveFactor.size() == 3)
        material.emission = Rgb(
            Vec3d(source_.emissiveFactor[0], source_.emissiveFactor[1], source_.emissiveFactor[2]) *
            strength);
    if (!IsFinite(material.emission) || MinComponent(material.emission) < 0)
        return Error("emission must be finite and non-negative");
    if (material.IsEmissive() && source_.emissiveTexture.index >= 0) {
        const absl::StatusOr<int32_t> texture =
            textures_.index(source_.emissiveTexture.index, colour);
        if (!texture.ok()) return texture.status();
        material.emission_texture = *texture;
    }
    // The normal texture: linear, each channel 0..1 for -1..1, x and y times its scale.
    if (source_.normalTexture.index >= 0) {
        ImageDecodeOptions linear;
        linear.encoding = ImageEncoding::kLinear;
        const absl::StatusOr<int32_t> texture =
            textures_.index(source_.normalTexture.index, linear);
        if (!texture.ok()) return texture.status();
        material.normal_texture = *texture;
        material.normal_scale = static_cast<float>(source_.normalTexture.scale);
        if (!std::isfinite(material.normal_scale))
            return Error("normalTexture's scale must be finite");
    }
    // A double-sided material is drawn, so emits, on both faces.
    material.two_sided = source_.doubleSided ? 1 : 0;
    return absl::OkStatus();
}

absl::Status GltfMaterialBuilder::ReadAlpha(Material& material) {
    // MASK keeps the surface where alpha (baseColorFactor's fourth value times the base colour
    // texture's alpha) is at least alphaCutoff; BLEND as coverage, a ray meeting it with
    // probability alpha (core/shared/alpha.h); OPAQUE ignores alpha.
    if (source_.alphaMode != "MASK" && source_.alphaMode != "BLEND") return absl::OkStatus();
    const auto& pbr = source_.pbrMetallicRoughness;
    const double alpha = pbr.baseColorFactor.size() == 4 ? pbr.baseColorFactor[3] : 1.0;
    if (!(alpha >= 0 && alpha <= 1)) return Error("baseColorFactor's alpha must lie in [0, 1]");
    material.alpha = static_cast<float>(alpha);
    if (pbr.baseColorTexture.index >= 0) {
        ImageDecodeOptions options;
        options.channels = ImageChannels::kAlpha;  // alpha is linear
        const absl::StatusOr<int32_t> texture =
            textures_.index(pbr.baseColorTexture.index, options);
        if (!texture.ok()) return texture.status();
        material.alpha_texture = *texture;
    }
    if (source_.alphaMode == "MASK") {
        if (!(source_.alphaCutoff >= 0 && source_.alphaCutoff <= 1))
            return Error("alphaCutoff must lie in [0, 1]");
        material.alpha_cutoff = static_cast<float>(source_.alphaCutoff);
        if (material.alpha_cutoff <= 0)  // every point passes: opaque
            material.alpha = 1, material.alpha_texture = kNoTexture;
    }
    return absl::OkStatus();
}

absl::Status GltfMaterialBuilder::ReadSheen() {
    const tinygltf::Value* e = Extension(source_.extensions, "KHR_materials_sheen");
    if (e == nullptr) return absl::OkStatus();
    Vec3d colour(0.0);
    if (e->Has("sheenColorFactor")) {
        const tinygltf::Value& given = e->Get("sheenColorFactor");
        colour = Vec3d(-1.0);  // refused unless three numbers
        if (given.IsArray() && given.ArrayLen() == 3)
            for (int c = 0; c < 3; ++c)
                if (given.Get(c).IsNumber()) colour[c] = given.Get(c).GetNumberAsDouble();
    }
    const double roughness = NumberOr(*e, "sheenRoughnessFactor", 0.0);
    if (!(MinComponent(colour) >= 0 && MaxComponent(colour) <= 1 && roughness >= 0 &&
          roughness <= 1))
        return Error(
            "KHR_materials_sheen: sheenColorFactor must be three numbers in [0, 1] and "
            "sheenRoughnessFactor lie in [0, 1]");
    sheen_.sheen_color = Rgb(colour);
    sheen_.sheen_roughness = static_cast<float>(roughness);
    if (IsBlack(sheen_.sheen_color)) return absl::OkStatus();  // the layer is off
    if (const int index = ExtensionTexture(*e, "sheenColorTexture"); index >= 0) {
        ImageDecodeOptions colour_texture;  // sRGB-encoded, as the base colour's
        colour_texture.encoding = ImageEncoding::kSrgb;
        const absl::StatusOr<int32_t> texture = textures_.index(index, colour_texture);
        if (!texture.ok()) return texture.status();
        sheen_.sheen_texture = *texture;
    }
    if (const int index = ExtensionTexture(*e, "sheenRoughnessTexture");
        index >= 0 && roughness > 0) {
        const absl::StatusOr<int32_t> texture = ChannelTexture(index, ImageChannels::kAlpha);
        if (!texture.ok()) return texture.status();
        sheen_.sheen_roughness_texture = *texture;
    }
    return absl::OkStatus();
}

absl::StatusOr<uint32_t> GltfMaterialBuilder::MetallicRoughness(const Material& common) {
    const auto& pbr = source_.pbrMetallicRoughness;
    // A specular-glossiness material's converted values, its baked textures (its own stand in
    // the metallic-roughness slots only for their coordinates: PrepareSpecularGlossiness).
    const double metallic_factor = spec_gloss_ ? spec_gloss_->factors.metallic : pbr.metallicFactor;
    const double roughness_factor =
        spec_gloss_ ? spec_gloss_->factors.roughness : pbr.roughnessFactor;
    if (!(metallic_factor >= 0 && metallic_factor <= 1 && roughness_factor >= 0 &&
          roughness_factor <= 1))
        return Error("metallicFactor and roughnessFactor must lie in [0, 1]");
    // GGX alpha: glTF's roughness squared, the texture's green channel read squared to match.
    const float alpha = static_cast<float>(roughness_factor * roughness_factor);
    const bool smooth = alpha < kMinRoughness;
    const int maps = spec_gloss_ ? -1 : pbr.metallicRoughnessTexture.index;
    int32_t roughness_texture = spec_gloss_ ? spec_gloss_->alpha_texture : kNoTexture;
    int32_t metallic_texture = spec_gloss_ ? spec_gloss_->metallic_texture : kNoTexture;
    if (maps >= 0 && !smooth) {
        const absl::StatusOr<int32_t> texture = ChannelTexture(maps, ImageChannels::kGreen, 2);
        if (!texture.ok()) return texture.status();
        roughness_texture = *texture;
    }
    if (maps >= 0 && metallic_factor > 0) {
        const absl::StatusOr<int32_t> texture = ChannelTexture(maps, ImageChannels::kBlue);
        if (!texture.ok()) return texture.status();
        metallic_texture = *texture;
    }
    const bool dielectric = metallic_factor < 1 || metallic_texture != kNoTexture;
    const bool metal = metallic_factor > 0;

    Material base = common;  // each part emits as the surface does
    base.roughness_texture = roughness_texture;
    Material plastic = base;  // glTF's dielectric BRDF
    plastic.coat_kind = gpu::kCoatFresnelMix;
    plastic.coat_roughness = smooth ? 0.0f : std::max(alpha, kMinRoughness);
    double f0_scale = 1.0;
    int32_t specular_texture = kNoTexture;
    if (const tinygltf::Value* e = Extension(source_.extensions, "KHR_materials_ior"))
        plastic.coat_ior = static_cast<float>(NumberOr(*e, "ior", 1.5));
    else
        plastic.coat_ior = 1.5f;
    if (!(plastic.coat_ior >= 1.0f && std::isfinite(plastic.coat_ior)))
        return Error("KHR_materials_ior's ior must be at least 1");
    if (const tinygltf::Value* e = Extension(source_.extensions, "KHR_materials_specular")) {
        plastic.coat_weight = static_cast<float>(NumberOr(*e, "specularFactor", 1.0));
        if (e->Has("specularColorFactor") && e->Get("specularColorFactor").IsArray() &&
            e->Get("specularColorFactor").ArrayLen() == 3) {
            const tinygltf::Value& colour = e->Get("specularColorFactor");
            f0_scale = (colour.Get(0).GetNumberAsDouble() + colour.Get(1).GetNumberAsDouble() +
                        colour.Get(2).GetNumberAsDouble()) /
                       3;
        }
        if (!(plastic.coat_weight >= 0 && plastic.coat_weight <= 1 && f0_scale >= 0 &&
              std::isfinite(f0_scale)))
            return Error(
                "KHR_materials_specular: specularFactor must lie in [0, 1], "
                "specularColorFactor be finite and non-negative");
        NoteTextureLeftOut(*e, "KHR_materials_specular", {"specularColorTexture"},
                           "its factor alone is used");
        // specularTexture's alpha scales the layer's weight texel by texel: a mix of the
        // surface with its layer and without, the texel the amount.
        if (const int index = ExtensionTexture(*e, "specularTexture");
            index >= 0 && plastic.coat_weight > 0) {
            const absl::StatusOr<int32_t> texture = ChannelTexture(index, ImageChannels::kAlpha);
            if (!texture.ok()) return texture.status();
            specular_texture = *texture;
        }
    }
    if (f0_scale != 1.0) {  // F0 = min(F0(ior) x the colour's mean, 1), as an index
        const double r = (plastic.coat_ior - 1.0) / (plastic.coat_ior + 1.0);
        plastic.coat_ior = IorOfF0(std::min(r * r * f0_scale, 1.0));
    }
    plastic.coat_ior = std::min(plastic.coat_ior, IorOfF0(0.99));  // F0 below 1
    if (plastic.coat_weight <= 0) plastic = base;                  // no specular layer: Lambertian
    Material conductor = base;
    conductor.type = smooth ? MaterialType::kMirror : MaterialType::kRoughConductor;
    conductor.roughness = smooth ? 0.0f : std::max(alpha, kMinRoughness);
    conductor.conductor = gpu::kConductorSchlick;  // glTF's conductor_fresnel, F0 the base colour
    if (smooth) conductor.roughness_texture = kNoTexture;

    // KHR_materials_clearcoat: the same surfaces under a layered coat of index 1.5.
    float clearcoat = 0;
    int32_t clearcoat_texture = kNoTexture;
    Material clear_plastic = base, clear_conductor = conductor;
    if (const tinygltf::Value* e = Extension(source_.extensions, "KHR_materials_clearcoat")) {
        clearcoat = static_cast<float>(NumberOr(*e, "clearcoatFactor", 0.0));
        const double roughness = NumberOr(*e, "clearcoatRoughnessFactor", 0.0);
        if (!(clearcoat >= 0 && clearcoat <= 1 && roughness >= 0 && roughness <= 1))
            return Error(
                "KHR_materials_clearcoat: clearcoatFactor and clearcoatRoughnessFactor must lie "
                "in [0, 1]");
        for (Material* coated : {&clear_plastic, &clear_conductor}) {
            coated->coat_kind = gpu::kCoatLayered;
            coated->coat_ior = 1.5f;
            coated->coat_roughness =
                roughness * roughness < kMinRoughness ? 0.0f : float(roughness * roughness);
        }
        NoteTextureLeftOut(*e, "KHR_materials_clearcoat", {"clearcoatNormalTexture"},
                           "the coat takes the surface's shading normal");
        // clearcoatTexture's red channel scales the factor texel by texel (the mix's amount).
        if (const int index = ExtensionTexture(*e, "clearcoatTexture");
            index >= 0 && clearcoat > 0) {
            const absl::StatusOr<int32_t> texture = ChannelTexture(index, ImageChannels::kRed);
            if (!texture.ok()) return texture.status();
            clearcoat_texture = *texture;
        }
        // A roughness texture scales a material's every alpha (Scene::ShadingMaterial): the
        // coated diffuse base needs none of its own, so it takes clearcoatRoughnessTexture's
        // (green, squared as the factor is); the coated metal shares the metal's with its coat.
        clear_plastic.roughness_texture = kNoTexture;
        const int rough = ExtensionTexture(*e, "clearcoatRoughnessTexture");
        if (rough >= 0 && clear_plastic.coat_roughness > 0 && clearcoat > 0) {
            const absl::StatusOr<int32_t> texture = ChannelTexture(rough, ImageChannels::kGreen, 2);
            if (!texture.ok()) return texture.status();
            clear_plastic.roughness_texture = *texture;
            if (metal)
                spdlog::warn(
                    "{}: clearcoatRoughnessTexture is left out over the metal (a material has one "
                    "roughness texture: the metal's)",
                    where_);
        }
        if (clear_conductor.roughness_texture != kNoTexture && clear_conductor.coat_roughness > 0 &&
            clearcoat > 0)
            spdlog::warn(
                "{}: the metallic-roughness texture scales the clearcoat's roughness over the "
                "metal too",
                where_);
    }
    if (clearcoat > 0 && !IsBlack(sheen_.sheen_color))
        spdlog::warn("{}: the sheen lies over the clearcoat (glTF puts it under)", where_);
    // The surface (under its sheen, if any), its specular layer weighed texel by texel where
    // specularTexture says.
    const auto add_plain = [&](const Material& plain) {
        if (&plain != &plastic || specular_texture == kNoTexture || !plastic.HasCoat())
            return Add(Sheened(plain));
        const uint32_t lambertian = Add(Sheened(base));
        return Mix(base, lambertian, Add(Sheened(plastic)), 1.0f, specular_texture);
    };
    // A surface and its clearcoated self, mixed by clearcoatFactor.
    const auto with_clearcoat = [&](const Material& plain, const Material& coated) {
        if (clearcoat <= 0) return add_plain(plain);
        if (clearcoat >= 1 && clearcoat_texture == kNoTexture) return Add(Sheened(coated));
        const uint32_t first = add_plain(plain);
        return Mix(base, first, Add(Sheened(coated)), clearcoat, clearcoat_texture);
    };
    uint32_t dielectric_index = 0, metal_index = 0;
    if (dielectric) dielectric_index = with_clearcoat(plastic, clear_plastic);
    if (metal) metal_index = with_clearcoat(conductor, clear_conductor);
    if (!metal) return dielectric_index;
    if (!dielectric) return metal_index;
    return Mix(base, dielectric_index, metal_index, static_cast<float>(metallic_factor),
               metallic_texture);
}

absl::StatusOr<uint32_t> GltfMaterialBuilder::Unlit(const Material& common) {
    // The base colour (factor x texture; x vertex colour, Scene::Emission) is what the camera
    // sees, emitted toward it as radiance; the surface reflects nothing. Photon mapping has no
    // surface seen without being lit: an emitter lights the scene as any other does, which is
    // what an unlit sky dome or a model with its lighting baked in wants.
    Material unlit = common;
    unlit.emission = common.base_color;
    unlit.emission_texture = common.base_color_texture;
    unlit.base_color = Rgb(0.0f);
    unlit.base_color_texture = kNoTexture;
    unlit.normal_texture = kNoTexture;
    unlit.surface_flags |= gpu::kSurfaceVertexEmission;
    if (absl::Status status = ReadAlpha(unlit); !status.ok()) return status;
    return Add(unlit);
}

absl::StatusOr<uint32_t> GltfMaterialBuilder::Build() {
    Material common;
    if (absl::Status status = ReadCommon(common); !status.ok()) return status;
    if (Extension(source_.extensions, "KHR_materials_unlit") != nullptr) return Unlit(common);
    double transmission = 0.0;
    if (const tinygltf::Value* e = Extension(source_.extensions, "KHR_materials_transmission"))
        transmission = NumberOr(*e, "transmissionFactor", 0.0);
    if (transmission > 0) {
        Material glass = common;
        if (const tinygltf::Value* e = Extension(source_.extensions, "KHR_materials_ior"))
            glass.ior = static_cast<float>(NumberOr(*e, "ior", 1.5));
        if (!(glass.ior >= 1.0f && std::isfinite(glass.ior)))
            return Error("KHR_materials_ior's ior must be at least 1");
        const tinygltf::Value* volume = Extension(source_.extensions, "KHR_materials_volume");
        glass.type = volume != nullptr && NumberOr(*volume, "thicknessFactor", 0.0) > 0
                         ? MaterialType::kDielectric
                         : MaterialType::kThinDielectric;
        if (glass.type == MaterialType::kDielectric) {
            // KHR_materials_volume's attenuation: light crossing a length d inside keeps
            // attenuationColor^(d / attenuationDistance), Beer-Lambert with absorption
            // -ln(attenuationColor) / attenuationDistance (world units, as the extension's).
            const double distance =
                NumberOr(*volume, "attenuationDistance", std::numeric_limits<double>::infinity());
            Vec3d colour(1.0);
            if (volume->Has("attenuationColor")) {
                const tinygltf::Value& given = volume->Get("attenuationColor");
                colour = Vec3d(-1.0);  // refused unless three numbers
                if (given.IsArray() && given.ArrayLen() == 3)
                    for (int c = 0; c < 3; ++c)
                        if (given.Get(c).IsNumber()) colour[c] = given.Get(c).GetNumberAsDouble();
            }
            if (!(distance > 0) || !(MinComponent(colour) >= 0 && MaxComponent(colour) <= 1))
                return Error(
                    "KHR_materials_volume: attenuationDistance must be above 0 and "
                    "attenuationColor three numbers in [0, 1]");
            if (std::isfinite(distance))
                for (int c = 0; c < 3; ++c)
                    glass.absorption[c] = static_cast<float>(
                        std::min(-std::log(std::max(colour[c], 1e-6)) / distance, 1e30));
        }
        if (transmission < 1)
            spdlog::warn("{}: transmissionFactor {} taken as 1 (no diffuse-transmission mix)",
                         where_, transmission);
        const double roughness = source_.pbrMetallicRoughness.roughnessFactor;
        if (glass.type == MaterialType::kDielectric && roughness > 0.0) {
            glass.type = MaterialType::kRoughDielectric;
            glass.roughness =
                static_cast<float>(std::clamp(roughness * roughness, double(kMinRoughness), 1.0));
        }
        if (absl::Status status = ReadAlpha(glass); !status.ok()) return status;
        if (Extension(source_.extensions, "KHR_materials_sheen") != nullptr)
            spdlog::warn("{}: KHR_materials_sheen is left out over a transmissive surface", where_);
        return Add(glass);
    }
    std::vector<std::string> left_out;
    for (const auto& [name, value] : source_.extensions)
        if (name.starts_with("KHR_materials_") && name != "KHR_materials_emissive_strength" &&
            name != "KHR_materials_ior" && name != "KHR_materials_specular" &&
            name != "KHR_materials_clearcoat" && name != "KHR_materials_transmission" &&
            name != "KHR_materials_volume" && name != "KHR_materials_sheen" &&
            name != "KHR_materials_pbrSpecularGlossiness")
            left_out.push_back(name);
    if (!left_out.empty()) spdlog::warn("{}: {} left out", where_, absl::StrJoin(left_out, ", "));
    if (absl::Status status = ReadSheen(); !status.ok()) return status;
    const absl::StatusOr<uint32_t> index = MetallicRoughness(common);
    if (!index.ok()) return index.status();
    // Cut-outs belong to the material the triangles name (Scene::Alpha).
    if (absl::Status status = ReadAlpha(materials_[*index]); !status.ok()) return status;
    return *index;
}

}  // namespace

int GltfTextureImage(const tinygltf::Texture& texture) {
    if (texture.source >= 0) return texture.source;
    if (const tinygltf::Value* webp = Extension(texture.extensions, "EXT_texture_webp"))
        return static_cast<int>(NumberOr(*webp, "source", -1));
    return -1;
}

std::vector<int> GltfTexturesRead(const tinygltf::Material& material) {
    std::vector<int> read;
    for (const int texture :
         {material.pbrMetallicRoughness.baseColorTexture.index, material.emissiveTexture.index,
          material.pbrMetallicRoughness.metallicRoughnessTexture.index,
          material.normalTexture.index})
        if (texture >= 0) read.push_back(texture);
    if (const tinygltf::Value* e = Extension(material.extensions, "KHR_materials_clearcoat"))
        for (const char* key : {"clearcoatTexture", "clearcoatRoughnessTexture"})
            if (const int texture = ExtensionTexture(*e, key); texture >= 0)
                read.push_back(texture);
    if (const tinygltf::Value* e = Extension(material.extensions, "KHR_materials_specular"))
        if (const int texture = ExtensionTexture(*e, "specularTexture"); texture >= 0)
            read.push_back(texture);
    if (const tinygltf::Value* e = Extension(material.extensions, "KHR_materials_sheen"))
        for (const char* key : {"sheenColorTexture", "sheenRoughnessTexture"})
            if (const int texture = ExtensionTexture(*e, key); texture >= 0)
                read.push_back(texture);
    if (const tinygltf::Value* e =
            Extension(material.extensions, "KHR_materials_pbrSpecularGlossiness"))
        for (const char* key : {"diffuseTexture", "specularGlossinessTexture"})
            if (const int texture = ExtensionTexture(*e, key); texture >= 0)
                read.push_back(texture);
    return read;
}

absl::StatusOr<uint32_t> AddGltfMaterial(const tinygltf::Material& source, const std::string& where,
                                         const GltfTextureAccess& textures,
                                         std::vector<Material>& materials) {
    const tinygltf::Value* spec_gloss =
        Extension(source.extensions, "KHR_materials_pbrSpecularGlossiness");
    if (spec_gloss == nullptr || Extension(source.extensions, "KHR_materials_unlit") != nullptr)
        return GltfMaterialBuilder(source, where, textures, materials).Build();
    const absl::StatusOr<ConvertedSpecularGlossiness> converted =
        ConvertSpecularGlossiness(*spec_gloss, where, textures);
    if (!converted.ok()) return converted.status();
    return GltfMaterialBuilder(source, where, textures, materials, &*converted).Build();
}

}  // namespace pf
