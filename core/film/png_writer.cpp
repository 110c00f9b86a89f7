// PNG output with stb_image_write.
#include "core/film/png_writer.h"

#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "absl/strings/str_cat.h"
#include "core/util/file_io.h"

namespace pf {
namespace {

uint8_t EncodeSrgb(float linear) {
    if (!(linear > 0)) return 0;  // also maps NaN to black
    linear = std::min(linear, 1.0f);
    const float encoded =
        linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
    return static_cast<uint8_t>(std::lround(encoded * 255.0f));
}

void AppendBytes(void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                               static_cast<size_t>(size));
}

}  // namespace

absl::StatusOr<std::string> EncodePng(const Image& image, float exposure) {
    if (image.width <= 0 || image.height <= 0 ||
        image.pixels.size() != static_cast<size_t>(image.width) * image.height)
        return absl::InvalidArgumentError("cannot encode an empty image as PNG");
    const float scale = std::exp2(exposure);
    std::vector<uint8_t> bytes(image.pixels.size() * 3);
    for (size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) bytes[3 * i + c] = EncodeSrgb(image.pixels[i][c] * scale);
    std::string png;
    if (stbi_write_png_to_func(AppendBytes, &png, image.width, image.height, 3, bytes.data(),
                               image.width * 3) == 0)
        return absl::InternalError("stb_image_write could not encode the PNG");
    return png;
}

absl::Status WritePng(const std::string& path, const Image& image, float exposure) {
    absl::StatusOr<std::string> png = EncodePng(image, exposure);
    if (!png.ok())
        return absl::InvalidArgumentError(absl::StrCat(path, ": ", png.status().message()));
    return WriteFileAtomically(path, *png);
}

}  // namespace pf
