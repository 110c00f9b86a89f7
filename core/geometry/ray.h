// Rays, ray hits, and the scale-aware origin offset that keeps secondary rays from
// re-hitting the surface they leave.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/math/vec3.h"
#include "core/shared/path_sampling.h"

namespace pf {

struct Ray {
    Vec3 origin;
    Vec3 direction;  // unit length
    float t_max = std::numeric_limits<float>::infinity();
};

// What a tracer reports for the closest hit: enough to rebuild the surface point.
struct RayHit {
    float t = 0;
    // Index into Scene::triangles; with kCurveBit set (gpu::kCurveBit, core/shared/curve.h),
    // the rest is an index into Scene::curves (IsCurve, CurveIndex).
    static constexpr uint32_t kCurveBit = 0x80000000u;
    uint32_t triangle = 0;
    float b1 = 0, b2 = 0;  // barycentrics of vertices 1 and 2; of a curve, b1 is u along it
    uint32_t instance =
        ~0u;  // index into Scene::instances, or ~0u (Instance::kNone) for a world triangle
    // A curve's: the ray that met it (world space, direction unit), from which Scene::Surface
    // finds where across the curve it passed and which way the curve faces it.
    Vec3 origin, direction;

    bool IsCurve() const { return (triangle & kCurveBit) != 0; }
    uint32_t CurveIndex() const { return triangle & ~kCurveBit; }
};

// Moves p off the surface along the geometric normal n, toward the side `n` faces, by a few
// units in the last place of each coordinate, or near zero by a small fraction of
// `scene_scale`, the scene's largest coordinate magnitude (Bounds::Magnitude): see
// gpu::OffsetCoordinate, the one definition for the CPU and the Vulkan kernels. A scene
// scaled by 1e-4 or 1e+4 is offset exactly as at unit scale (tests/integration/numerics_test.cpp).
inline Vec3 OffsetRayOrigin(const Vec3& p, const Vec3& n, float scene_scale) {
    return {gpu::OffsetCoordinate(p.x, n.x, scene_scale),
            gpu::OffsetCoordinate(p.y, n.y, scene_scale),
            gpu::OffsetCoordinate(p.z, n.z, scene_scale)};
}

}  // namespace pf
