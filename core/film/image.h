// A float linear-RGB image, row-major with row 0 at the top.
#pragma once

#include <cstdint>
#include <vector>

#include "core/math/vec3.h"

namespace pf {

struct Image {
    int width = 0, height = 0;
    std::vector<Rgb> pixels;

    Image() = default;
    Image(int w, int h) : width(w), height(h), pixels(static_cast<size_t>(w) * h, Rgb(0.0f)) {}
    Rgb& At(int x, int y) { return pixels[static_cast<size_t>(y) * width + x]; }
    const Rgb& At(int x, int y) const { return pixels[static_cast<size_t>(y) * width + x]; }
};

}  // namespace pf
