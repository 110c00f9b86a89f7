// Decoding a scene's image files, held in memory, into linear RGB textures through
// OpenImageIO (PNG, JPEG, OpenEXR, TIFF, TGA, BMP, Radiance HDR).
#pragma once

#include <string>
#include <string_view>

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

struct ImageDecodeOptions {
    ImageEncoding encoding = ImageEncoding::kAuto;
    double gamma = 2.2;
};

// Decodes `bytes`, the contents of bundle file `name` (whose extension picks the format).
// Nothing is read from disk: formats OpenImageIO cannot read from memory are refused. An
// image over `limits.max_image_pixels` is refused before its pixels are decoded
// (RESOURCE_EXHAUSTED); errors name `name`. Grey images give grey RGB; alpha is ignored.
absl::StatusOr<Texture> DecodeImage(std::string_view bytes, const std::string& name,
                                    const SceneLimits& limits,
                                    const ImageDecodeOptions& options = {});

}  // namespace pf
