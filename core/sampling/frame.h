// Orthonormal frame around a unit normal, for sampling directions in local space.
#pragma once

#include <cmath>

#include "core/math/vec3.h"
#include "core/shared/path_sampling.h"

namespace pf {

struct Frame {
    Vec3 s, t, n;

    // Builds a frame without branches on the sign of n.z (Duff et al. 2017; the one
    // definition for the CPU and the Vulkan kernels is gpu::OrthonormalBasis).
    static Frame FromNormal(const Vec3& normal) {
        Frame frame{{}, {}, normal};
        gpu::OrthonormalBasis(normal, frame.s, frame.t);
        return frame;
    }
    Vec3 ToWorld(const Vec3& local) const { return s * local.x + t * local.y + n * local.z; }
    Vec3 ToLocal(const Vec3& world) const { return {Dot(world, s), Dot(world, t), Dot(world, n)}; }
};

}  // namespace pf
