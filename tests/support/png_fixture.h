// Small PNG images for the loaders' tests.
#pragma once

#include <OpenImageIO/imageio.h>

#include <array>
#include <filesystem>
#include <string>

#include "core/scene/scene_files.h"
#include "tests/support/test_env.h"

namespace pf::testing {

// The bytes of a 2x1 8-bit PNG of `pixels`, `channels` a texel (written through OpenImageIO
// to a temporary file, read back and removed); empty where that failed. OpenImageIO takes the
// colour of an RGBA texel as premultiplied by its alpha and divides it out, unless `as_given`.
inline std::string TwoTexelPngOf(const unsigned char* pixels, int channels, const std::string& name,
                                 bool as_given = false) {
    const std::filesystem::path path = TempPath(name);
    auto out = OIIO::ImageOutput::create(path.string());
    OIIO::ImageSpec spec(2, 1, channels, OIIO::TypeDesc::UINT8);
    if (as_given) spec.attribute("oiio:UnassociatedAlpha", 1);
    if (!out || !out->open(path.string(), spec) || !out->write_image(OIIO::TypeDesc::UINT8, pixels))
        return {};
    out->close();
    const absl::StatusOr<std::string> bytes = ReadWholeFile(path);
    std::filesystem::remove(path);
    return bytes.ok() ? *bytes : std::string();
}

// RGB texels.
inline std::string TwoTexelPng(const std::array<unsigned char, 6>& pixels,
                               const std::string& name) {
    return TwoTexelPngOf(pixels.data(), 3, name);
}

// RGBA texels.
inline std::string TwoTexelRgbaPng(const std::array<unsigned char, 8>& pixels,
                                   const std::string& name, bool as_given = false) {
    return TwoTexelPngOf(pixels.data(), 4, name, as_given);
}

}  // namespace pf::testing
