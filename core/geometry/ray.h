// Rays, ray hits, and the scale-aware origin offset that keeps secondary rays from
// re-hitting the surface they leave.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/math/vec3.h"

namespace pf {

struct Ray {
    Vec3 origin;
    Vec3 direction;  // unit length
    float t_max = std::numeric_limits<float>::infinity();
};

// What a tracer reports for the closest hit: enough to rebuild the surface point.
struct RayHit {
    float t = 0;
    uint32_t triangle = 0;   // index into Scene::triangles
    float b1 = 0, b2 = 0;    // barycentrics of vertices 1 and 2
};

// Moves p off the surface along the geometric normal n, toward the side `n` faces, by a few
// units in the last place of each coordinate rather than by a fixed epsilon (Wachter & Binder
// 2019, "A Fast and Robust Method for Avoiding Self-Intersection", Ray Tracing Gems ch. 6).
// Coordinates near zero, where a few units in the last place are nothing against the hit's
// rounding error, move by a small fixed fraction of the scene instead: `scene_scale` is the
// scene's largest coordinate magnitude (Bounds::Magnitude), so a scene scaled by 1e-4 or
// 1e+4 is offset exactly as the same scene at unit scale (tests/integration/numerics_test.cpp).
inline Vec3 OffsetRayOrigin(const Vec3& p, const Vec3& n, float scene_scale) {
    const float origin = scene_scale * (1.0f / 32.0f);
    const float float_scale = scene_scale * (1.0f / 65536.0f);
    constexpr float kIntScale = 256.0f;
    Vec3 result;
    for (int axis = 0; axis < 3; ++axis) {
        const float coordinate = p[axis];
        const auto offset = static_cast<int32_t>(kIntScale * n[axis]);
        const auto bits = std::bit_cast<int32_t>(coordinate);
        const float moved = std::bit_cast<float>(bits + (coordinate < 0 ? -offset : offset));
        result[axis] = std::abs(coordinate) < origin ? coordinate + float_scale * n[axis] : moved;
    }
    return result;
}

}  // namespace pf
