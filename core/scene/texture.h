// An RGB image texture in linear floating point with its MIP pyramid, sampled bilinearly
// (photons: a point on the surface) or trilinearly over a footprint (camera hit points: the
// pixel's cone where it meets the surface), with wrapping.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/math/vec3.h"

namespace pf {

// One level of an image: row-major, row 0 at the top (glTF's v = 0), linear RGB.
struct TextureLevel {
    int width = 0, height = 0;
    std::vector<Rgb> texels;

    Rgb Texel(int x, int y) const {
        x = ((x % width) + width) % width;
        y = ((y % height) + height) % height;
        return texels[static_cast<size_t>(y) * width + x];
    }
    // Bilinear lookup at glTF texture coordinates (u right, v down), repeat wrapping.
    Rgb Sample(float u, float v) const {
        const float x = u * width - 0.5f, y = v * height - 0.5f;
        const float fx = std::floor(x), fy = std::floor(y);
        const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
        const float wx = x - fx, wy = y - fy;
        return (Texel(x0, y0) * (1 - wx) + Texel(x0 + 1, y0) * wx) * (1 - wy) +
               (Texel(x0, y0 + 1) * (1 - wx) + Texel(x0 + 1, y0 + 1) * wx) * wy;
    }
};

// Level 0 is the image itself (what the photon pass and the Vulkan backend read); `mips`
// holds the halved levels below it, made by OpenImageIO's resampling filter when the image is
// decoded (core/scene/image_decode.cpp), down to 1x1.
struct Texture : TextureLevel {
    std::vector<TextureLevel> mips;

    // Trilinear lookup for a footprint `footprint` texture-coordinate units across: the two
    // levels whose texels are nearest that size, blended.
    Rgb SampleFiltered(float u, float v, float footprint) const {
        const float texels_across = footprint * static_cast<float>(std::max(width, height));
        if (mips.empty() || !(texels_across > 1.0f)) return Sample(u, v);
        const float level = std::min(std::log2(texels_across), static_cast<float>(mips.size()));
        const int lower = static_cast<int>(level);
        const float blend = level - static_cast<float>(lower);
        auto at = [&](int l) { return l == 0 ? Sample(u, v) : mips[l - 1].Sample(u, v); };
        const Rgb fine = at(lower);
        return blend > 0 && lower < static_cast<int>(mips.size()) ? fine * (1 - blend) + at(lower + 1) * blend : fine;
    }
};

// The sRGB electro-optical transfer function: an 8-bit-encoded sRGB value to linear.
inline float SrgbToLinear(float encoded) {
    return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

}  // namespace pf
