// KHR_materials_pbrSpecularGlossiness converted to metallic-roughness, as the Khronos
// converter converts it, and its textures baked texel by texel.
#include "core/scene_io/gltf/gltf_spec_gloss.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "absl/strings/str_cat.h"

namespace pf {
namespace {

constexpr char kExtension[] = "KHR_materials_pbrSpecularGlossiness";
// The converter's reflectance of a dielectric at normal incidence, and its guard against
// dividing by zero.
constexpr double kDielectricF0 = 0.04;
constexpr double kEpsilon = 1e-6;

double PerceivedBrightness(const Rgb& c) {
    return std::sqrt(0.299 * c.x * c.x + 0.587 * c.y * c.y + 0.114 * c.z * c.z);
}

// A textureInfo object of the extension as the core specification's TextureInfo.
tinygltf::TextureInfo TextureInfoOf(const tinygltf::Value& extension, const char* key) {
    tinygltf::TextureInfo info;
    if (!extension.Has(key) || !extension.Get(key).IsObject()) return info;
    const tinygltf::Value& object = extension.Get(key);
    info.index = static_cast<int>(NumberOr(object, "index", -1));
    info.texCoord = static_cast<int>(NumberOr(object, "texCoord", 0));
    if (object.Has("extensions") && object.Get("extensions").IsObject())
        for (const std::string& name : object.Get("extensions").Keys())
            info.extensions[name] = object.Get("extensions").Get(name);
    return info;
}

// Number array `key` of `count` values in [0, 1], or `fallback` where absent; nullopt where
// given but not that.
std::optional<std::vector<double>> UnitNumbers(const tinygltf::Value& object, const char* key,
                                               size_t count, double fallback) {
    if (!object.Has(key)) return std::vector<double>(count, fallback);
    const tinygltf::Value& given = object.Get(key);
    if (!given.IsArray() || given.ArrayLen() != count) return std::nullopt;
    std::vector<double> values;
    for (size_t i = 0; i < count; ++i) {
        const tinygltf::Value& value = given.Get(static_cast<int>(i));
        if (!value.IsNumber()) return std::nullopt;
        values.push_back(value.GetNumberAsDouble());
        if (!(values.back() >= 0 && values.back() <= 1)) return std::nullopt;
    }
    return values;
}

// The value every texel holds, where they all hold the same.
std::optional<Rgb> Uniform(const std::vector<Rgb>& texels) {
    if (texels.empty()) return std::nullopt;
    for (const Rgb& texel : texels)
        if (!(texel == texels.front())) return std::nullopt;
    return texels.front();
}

}  // namespace

MetallicRoughnessValue SpecularGlossinessToMetallicRoughness(const Rgb& diffuse,
                                                             const Rgb& specular,
                                                             float glossiness) {
    const double one_minus_specular = 1.0 - MaxComponent(specular);
    const double specular_brightness = PerceivedBrightness(specular);
    double metallic = 0;
    if (specular_brightness >= kDielectricF0) {
        // a m^2 + b m + c = 0, the metallic whose F0 and diffuse albedo give the colours'
        // brightness; its larger root.
        const double a = kDielectricF0;
        const double b = PerceivedBrightness(diffuse) * one_minus_specular / (1 - kDielectricF0) +
                         specular_brightness - 2 * kDielectricF0;
        const double c = kDielectricF0 - specular_brightness;
        const double discriminant = std::max(b * b - 4 * a * c, 0.0);
        metallic = std::clamp((-b + std::sqrt(discriminant)) / (2 * a), 0.0, 1.0);
    }
    MetallicRoughnessValue value;
    const double blend = metallic * metallic;
    for (int c = 0; c < 3; ++c) {
        const double from_diffuse = diffuse[c] * (one_minus_specular / (1 - kDielectricF0) /
                                                  std::max(1 - metallic, kEpsilon));
        const double from_specular =
            (specular[c] - kDielectricF0 * (1 - metallic)) / std::max(metallic, kEpsilon);
        value.base_color[c] = static_cast<float>(
            std::clamp(from_diffuse + (from_specular - from_diffuse) * blend, 0.0, 1.0));
    }
    value.metallic = static_cast<float>(metallic);
    value.roughness = 1.0f - glossiness;
    return value;
}

void PrepareSpecularGlossiness(tinygltf::Model* model) {
    const bool required =
        std::find(model->extensionsRequired.begin(), model->extensionsRequired.end(), kExtension) !=
        model->extensionsRequired.end();
    for (tinygltf::Material& material : model->materials) {
        const auto extension = material.extensions.find(kExtension);
        if (extension == material.extensions.end()) continue;
        // tinygltf keeps pbrMetallicRoughness's members in `values`: none, no such material.
        if (!required && !material.values.empty()) {
            material.extensions.erase(extension);
            continue;
        }
        const tinygltf::Value& e = extension->second;
        tinygltf::PbrMetallicRoughness& pbr = material.pbrMetallicRoughness;
        pbr = tinygltf::PbrMetallicRoughness();
        const std::optional<std::vector<double>> diffuse = UnitNumbers(e, "diffuseFactor", 4, 1.0);
        if (diffuse) pbr.baseColorFactor = *diffuse;  // its alpha is the base colour's
        pbr.baseColorTexture = TextureInfoOf(e, "diffuseTexture");
        pbr.metallicRoughnessTexture = TextureInfoOf(e, "specularGlossinessTexture");
    }
}

absl::StatusOr<ConvertedSpecularGlossiness> ConvertSpecularGlossiness(
    const tinygltf::Value& extension, const std::string& where, const GltfTextureAccess& textures) {
    const std::optional<std::vector<double>> diffuse_factor =
        UnitNumbers(extension, "diffuseFactor", 4, 1.0);
    const std::optional<std::vector<double>> specular_factor =
        UnitNumbers(extension, "specularFactor", 3, 1.0);
    const double glossiness_factor = NumberOr(extension, "glossinessFactor", 1.0);
    if (!diffuse_factor || !specular_factor || !(glossiness_factor >= 0 && glossiness_factor <= 1))
        return absl::InvalidArgumentError(
            absl::StrCat(where, ": ", kExtension,
                         ": diffuseFactor must be four numbers and specularFactor three in [0, 1], "
                         "glossinessFactor lie in [0, 1]"));
    const Rgb diffuse(Vec3d((*diffuse_factor)[0], (*diffuse_factor)[1], (*diffuse_factor)[2]));
    const Rgb specular(Vec3d((*specular_factor)[0], (*specular_factor)[1], (*specular_factor)[2]));
    const auto glossiness = static_cast<float>(glossiness_factor);
    ConvertedSpecularGlossiness out;
    const int diffuse_index = TextureInfoOf(extension, "diffuseTexture").index;
    const int specular_index = TextureInfoOf(extension, "specularGlossinessTexture").index;
    if (diffuse_index < 0 && specular_index < 0) {
        out.factors = SpecularGlossinessToMetallicRoughness(diffuse, specular, glossiness);
        return out;
    }
    // The images, linear: diffuse and specular colours from sRGB, glossiness as it is.
    ImageDecodeOptions srgb;
    srgb.encoding = ImageEncoding::kSrgb;
    ImageDecodeOptions alpha;
    alpha.channels = ImageChannels::kAlpha;
    std::optional<Texture> diffuse_texels, specular_texels, glossiness_texels;
    if (diffuse_index >= 0) {
        absl::StatusOr<Texture> decoded = textures.decode(diffuse_index, srgb);
        if (!decoded.ok()) return decoded.status();
        diffuse_texels = std::move(*decoded);
    }
    if (specular_index >= 0) {
        absl::StatusOr<Texture> decoded = textures.decode(specular_index, srgb);
        if (!decoded.ok()) return decoded.status();
        specular_texels = std::move(*decoded);
        decoded = textures.decode(specular_index, alpha);
        if (!decoded.ok()) return decoded.status();
        glossiness_texels = std::move(*decoded);
    }
    // Baked at the larger image's size, addressed beyond it as the base colour's image is.
    const Texture& reference =
        !diffuse_texels ? *specular_texels
        : specular_texels && specular_texels->texels.size() > diffuse_texels->texels.size()
            ? *specular_texels
            : *diffuse_texels;
    Texture base_color, metallic, roughness_alpha;
    float roughness = 1;  // the first texel's (all texels' where the alpha is uniform)
    for (Texture* baked : {&base_color, &metallic, &roughness_alpha}) {
        baked->width = reference.width, baked->height = reference.height;
        baked->wrap_u = diffuse_texels ? diffuse_texels->wrap_u : reference.wrap_u;
        baked->wrap_v = diffuse_texels ? diffuse_texels->wrap_v : reference.wrap_v;
        baked->texels.reserve(reference.texels.size());
    }
    for (int y = 0; y < reference.height; ++y)
        for (int x = 0; x < reference.width; ++x) {
            const float u = (x + 0.5f) / float(reference.width);
            const float v = (y + 0.5f) / float(reference.height);
            const Rgb d = diffuse_texels ? diffuse * diffuse_texels->Sample(u, v) : diffuse;
            const Rgb s = specular_texels ? specular * specular_texels->Sample(u, v) : specular;
            const float g =
                glossiness_texels ? glossiness * glossiness_texels->Sample(u, v).x : glossiness;
            const MetallicRoughnessValue value = SpecularGlossinessToMetallicRoughness(d, s, g);
            if (base_color.texels.empty()) roughness = value.roughness;
            base_color.texels.push_back(value.base_color);
            metallic.texels.push_back(Rgb(value.metallic));
            roughness_alpha.texels.push_back(Rgb(value.roughness * value.roughness));
        }
    // A value the same everywhere is a factor; the others textures of their own.
    if (const std::optional<Rgb> same = Uniform(base_color.texels))
        out.factors.base_color = *same;
    else
        out.base_color_texture = textures.add(std::move(base_color));
    if (const std::optional<Rgb> same = Uniform(metallic.texels)) {
        out.factors.metallic = same->x;
    } else {
        out.factors.metallic = 1;
        out.metallic_texture = textures.add(std::move(metallic));
    }
    if (Uniform(roughness_alpha.texels)) {
        out.factors.roughness = roughness;
    } else {
        out.factors.roughness = 1;
        out.alpha_texture = textures.add(std::move(roughness_alpha));
    }
    return out;
}

}  // namespace pf
