// A point in the plane: texture coordinates, disk and barycentric samples.
#pragma once

namespace pf {

struct alignas(8) Point2 {  // aligned as std430 vec2 (gpu_prelude.h)
    float x = 0, y = 0;

    // Spelled out for the shared headers' GLSL-style vec2(x, y): clang before 16 lacks C++20's
    // parenthesised aggregate initialisation.
    constexpr Point2() = default;
    constexpr Point2(float x_in, float y_in) : x(x_in), y(y_in) {}
    friend constexpr Point2 operator-(const Point2& a, const Point2& b) {
        return {a.x - b.x, a.y - b.y};
    }
};

}  // namespace pf
