// Small PNG images for the loaders' tests.
#pragma once

#include <OpenImageIO/imageio.h>

#include <array>
#include <filesystem>
#include <string>

#include "core/scene/scene_files.h"
#include "tests/support/test_env.h"

namespace pf::testing {

// The bytes of a 2x1 8-bit RGB PNG of `pixels` (written through OpenImageIO to a temporary
// file, read back and removed); empty where that failed.
inline std::string TwoTexelPng(const std::array<unsigned char, 6>& pixels,
                               const std::string& name) {
    const std::filesystem::path path = TempPath(name);
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out || !out->open(path.string(), OIIO::ImageSpec(2, 1, 3, OIIO::TypeDesc::UINT8)) ||
        !out->write_image(OIIO::TypeDesc::UINT8, pixels.data()))
        return {};
    out->close();
    const absl::StatusOr<std::string> bytes = ReadWholeFile(path);
    std::filesystem::remove(path);
    return bytes.ok() ? *bytes : std::string();
}

}  // namespace pf::testing
