// Small PNG images for the loaders' tests, encoded in memory without OpenImageIO (so the test
// binaries do not load it at start-up; reading them goes through DecodeImage, which does).
#pragma once

#include <stb_image_write.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace pf::testing {

// The bytes of a `width` x `height` 8-bit PNG of `pixels` (`channels` values a texel, 1 to 4:
// grey, grey-alpha, RGB, RGBA; top row first), through stb_image_write; empty where that failed.
inline std::string PngOf(int width, int height, int channels, const unsigned char* pixels) {
    std::string png;
    const auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data), size);
    };
    if (!stbi_write_png_to_func(append, &png, width, height, channels, pixels, width * channels))
        return {};
    return png;
}

// The same as a 16-bit PNG (`samples` as stored, big-endian in the file). stb_image_write writes
// 8-bit PNG only: the chunks are framed here (PNG 1.2: IHDR, one IDAT of unfiltered rows
// deflated by zlib, IEND, each with its CRC-32), which is all an uninterlaced PNG needs.
inline std::string SixteenBitPngOf(int width, int height, int channels, const uint16_t* samples) {
    const char colour_types[] = {0, 0, 4, 2, 6};  // by channels: grey, grey-alpha, RGB, RGBA
    std::string rows;
    for (int y = 0; y < height; ++y) {
        rows.push_back('\0');  // filter type 0: none
        for (int i = 0; i < width * channels; ++i) {
            const uint16_t sample = samples[size_t(y) * width * channels + i];
            rows.push_back(static_cast<char>(sample >> 8));
            rows.push_back(static_cast<char>(sample & 0xff));
        }
    }
    uLongf deflated_size = compressBound(rows.size());
    std::string deflated(deflated_size, '\0');
    if (compress(reinterpret_cast<Bytef*>(deflated.data()), &deflated_size,
                 reinterpret_cast<const Bytef*>(rows.data()), rows.size()) != Z_OK)
        return {};
    deflated.resize(deflated_size);
    const auto big_endian = [](uint32_t value) {
        return std::string{static_cast<char>(value >> 24), static_cast<char>(value >> 16),
                           static_cast<char>(value >> 8), static_cast<char>(value)};
    };
    std::string png = "\x89PNG\r\n\x1a\n";
    const auto chunk = [&](const std::string& type, const std::string& data) {
        const std::string typed = type + data;
        const uLong crc = crc32(0, reinterpret_cast<const Bytef*>(typed.data()), typed.size());
        png += big_endian(data.size()) + typed + big_endian(crc);
    };
    // Bit depth 16, the colour type, deflate, adaptive filtering, no interlace.
    chunk("IHDR", big_endian(width) + big_endian(height) +
                      std::string{16, colour_types[channels], 0, 0, 0});
    chunk("IDAT", deflated);
    chunk("IEND", "");
    return png;
}

// The bytes of a 2x1 8-bit PNG of `pixels`, `channels` a texel (`name`, the file a test would
// give it, is not needed: nothing is written to disk). Unless `as_given`, an RGBA texel's
// colour is taken as premultiplied by its alpha and stored divided by it (c * 255 / alpha,
// truncated, at most 255), as the OpenImageIO writer that made these fixtures before did;
// the tests' texels are the ones stored that way.
inline std::string TwoTexelPngOf(const unsigned char* pixels, int channels,
                                 const std::string& /*name*/, bool as_given = false) {
    std::vector<unsigned char> stored(pixels, pixels + 2 * channels);
    if (channels == 4 && !as_given)
        for (int texel = 0; texel < 2; ++texel) {
            const unsigned alpha = stored[texel * 4 + 3];
            if (alpha == 0) continue;
            for (int c = 0; c < 3; ++c)
                stored[texel * 4 + c] = static_cast<unsigned char>(
                    std::min(255u, unsigned{stored[texel * 4 + c]} * 255u / alpha));
        }
    return PngOf(2, 1, channels, stored.data());
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
