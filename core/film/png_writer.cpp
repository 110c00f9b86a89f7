// PNG output with OpenImageIO.
#include "core/film/png_writer.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "absl/strings/str_cat.h"

namespace pf {
namespace {

uint8_t EncodeSrgb(float linear) {
    if (!(linear > 0)) return 0;  // also maps NaN to black
    linear = std::min(linear, 1.0f);
    const float encoded =
        linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
    return static_cast<uint8_t>(std::lround(encoded * 255.0f));
}

}  // namespace

absl::Status WritePng(const std::string& path, const Image& image, float exposure) {
    const float scale = std::exp2(exposure);
    std::vector<uint8_t> bytes(image.pixels.size() * 3);
    for (size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) bytes[3 * i + c] = EncodeSrgb(image.pixels[i][c] * scale);
    auto output = OIIO::ImageOutput::create(path);
    if (!output)
        return absl::InvalidArgumentError(
            absl::StrCat(path, ": cannot write PNG: ", OIIO::geterror()));
    const OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
    if (!output->open(path, spec) || !output->write_image(OIIO::TypeDesc::UINT8, bytes.data()) ||
        !output->close())
        return absl::UnavailableError(
            absl::StrCat(path, ": cannot write PNG: ", output->geterror()));
    return absl::OkStatus();
}

}  // namespace pf
