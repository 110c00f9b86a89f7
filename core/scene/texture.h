// An RGB image texture in linear floating point, sampled bilinearly at a point (what photons
// meet; the Vulkan kernels read the same texels the same way), and the interface of filtered
// lookups over a footprint (camera hit points), which OpenImageIO's TextureSystem answers.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/math/vec3.h"
#include "core/shared/texture_wrap.h"

namespace pf {

// Row-major, row 0 at the top (glTF's v = 0), linear RGB. Or a procedural texture (pbrt-v4's
// noise, checkerboard, dots, scale and mix of them): no texels but a program, evaluated at
// each point (core/shared/procedural_texture.h; Scene::TextureValue).
struct Texture {
    int width = 0, height = 0;
    std::vector<Rgb> texels;
    // How each axis is addressed beyond the image (gpu::kWrap*, core/shared/texture_wrap.h).
    uint32_t wrap_u = gpu::kWrapRepeat, wrap_v = gpu::kWrapRepeat;
    // A procedural texture's words; empty for an image. Its images are other textures.
    std::vector<gpu::vec4> program;

    bool IsProcedural() const { return !program.empty(); }

    Rgb Texel(int x, int y) const {
        gpu::WrapTexels(x, y, width, height, wrap_u, wrap_v);
        if (x < 0 || y < 0) return Rgb(0.0f);
        return texels[static_cast<size_t>(y) * width + x];
    }
    // Bilinear lookup at glTF texture coordinates (u right, v down), wrapped as it says.
    Rgb Sample(float u, float v) const {
        const float x = u * width - 0.5f, y = v * height - 0.5f;
        const float fx = std::floor(x), fy = std::floor(y);
        const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
        const float wx = x - fx, wy = y - fy;
        return (Texel(x0, y0) * (1 - wx) + Texel(x0 + 1, y0) * wx) * (1 - wy) +
               (Texel(x0, y0 + 1) * (1 - wx) + Texel(x0 + 1, y0 + 1) * wx) * wy;
    }
};

// Filtered lookups of a scene's textures: the average over a footprint `footprint`
// texture-coordinate units across around (u, v), from MIP levels (a camera sample's cone where
// it meets the surface). The scene loaders give every scene with textures one
// (core/scene/texture_filter.h: MIP levels, trilinear). Safe to call from many threads.
class TextureFilter {
public:
    virtual ~TextureFilter() = default;
    virtual Rgb Sample(uint32_t texture, float u, float v, float footprint) const = 0;
};

// The sRGB electro-optical transfer function: an 8-bit-encoded sRGB value to linear.
inline float SrgbToLinear(float encoded) {
    return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

}  // namespace pf
