// Orthonormal frame around a unit normal, for sampling directions in local space.
#pragma once

#include <cmath>

#include "core/math/vec3.h"

namespace pf {

struct Frame {
    Vec3 s, t, n;

    // Builds a frame without branches on the sign of n.z (Duff et al. 2017, "Building an
    // Orthonormal Basis, Revisited", JCGT 6(1)).
    static Frame FromNormal(const Vec3& normal) {
        const float sign = std::copysign(1.0f, normal.z);
        const float a = -1.0f / (sign + normal.z);
        const float b = normal.x * normal.y * a;
        return {{1.0f + sign * normal.x * normal.x * a, sign * b, -sign * normal.x},
                {b, sign + normal.y * normal.y * a, -normal.y},
                normal};
    }
    Vec3 ToWorld(const Vec3& local) const { return s * local.x + t * local.y + n * local.z; }
    Vec3 ToLocal(const Vec3& world) const { return {Dot(world, s), Dot(world, t), Dot(world, n)}; }
};

}  // namespace pf
