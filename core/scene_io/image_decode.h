// Decoding a scene's image files, held in memory, into linear RGB textures through
// OpenImageIO (PNG, JPEG, OpenEXR, TIFF, TGA, BMP, Radiance HDR).
#pragma once

#include <string>
#include <string_view>
#include <tuple>

#include "absl/status/statusor.h"
#include "core/scene/mesh_builder.h"
#include "core/scene/texture.h"

namespace pf {

// How an image's values map to linear reflectance.
enum class ImageEncoding {
    kAuto,  // 8- and 16-bit integer images are sRGB, floating point ones linear (pbrt-v4, glTF)
    kSrgb,
    kLinear,
    kGamma,  // value^gamma
};

// What a texture takes of an image's channels.
enum class ImageChannels {
    kColour,  // RGB (a grey image grey); alpha ignored
    // One value, in every channel of the texture: pbrt-v4's float textures' (one channel as it
    // is, three averaged, four: the alpha channel).
    kFloat,
    kAlpha,  // the alpha channel (of grey-alpha or RGBA images; 1 without one), linear
    // One channel in every channel of the texture (a grey image's grey): glTF's
    // metallicRoughnessTexture keeps roughness in green, metallic in blue, its clearcoat
    // textures the factor in red and roughness in green.
    kRed,
    kGreen,
    kBlue,
};

struct ImageDecodeOptions {
    ImageEncoding encoding = ImageEncoding::kAuto;
    double gamma = 2.2;
    ImageChannels channels = ImageChannels::kColour;
    bool invert = false;  // each value v read as max(0, 1 - v) (pbrt's "invert")
    double exponent = 1;  // then as v^exponent (a roughness texture mapped to GGX alpha)
    // How the texture is addressed beyond the image (Texture::wrap_u, wrap_v).
    uint32_t wrap_u = gpu::kWrapRepeat, wrap_v = gpu::kWrapRepeat;
    bool operator<(const ImageDecodeOptions& other) const {
        return std::tie(encoding, gamma, channels, invert, exponent, wrap_u, wrap_v) <
               std::tie(other.encoding, other.gamma, other.channels, other.invert, other.exponent,
                        other.wrap_u, other.wrap_v);
    }
};

// Decodes `bytes`, the contents of bundle file `name` (whose extension picks the format).
// Nothing is read from disk: formats OpenImageIO cannot read from memory are refused. An
// image over `limits.max_image_pixels` is refused before its pixels are decoded
// (RESOURCE_EXHAUSTED); errors name `name`. Grey images give grey RGB; `options.channels` says
// what of alpha is read.
absl::StatusOr<Texture> DecodeImage(std::string_view bytes, const std::string& name,
                                    const SceneLimits& limits,
                                    const ImageDecodeOptions& options = {});
// What of `options` applies to linear texels already decoded (invert, exponent, wrap modes):
// DecodeImage's last step, and all of it for images made in memory (pbrt's baked textures).
void ApplyValueOptions(const ImageDecodeOptions& options, Texture* texture);

}  // namespace pf
