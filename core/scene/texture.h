// An RGB image texture in linear floating point, sampled bilinearly with wrapping.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/math/vec3.h"

namespace pf {

struct Texture {
    int width = 0, height = 0;
    std::vector<Rgb> texels;  // row-major, row 0 at the top (glTF's v = 0), linear RGB

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

// The sRGB electro-optical transfer function: an 8-bit-encoded sRGB value to linear.
inline float SrgbToLinear(float encoded) {
    return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

}  // namespace pf
