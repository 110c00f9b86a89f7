// An orthonormal frame around a unit normal, for directions in the local space of a surface
// (+z along the normal): the one definition for the CPU and the Vulkan kernels.
#ifndef PF_CORE_SHARED_FRAME_H
#define PF_CORE_SHARED_FRAME_H

#include "core/shared/gpu_prelude.h"
#include "core/shared/path_sampling.h"

PF_GPU_BEGIN

struct Frame {
    vec3 s, t, n;
};

// Built without branches on the sign of n.z (OrthonormalBasis: Duff et al. 2017).
PF_GPU_FN Frame FrameFromNormal(vec3 normal) {
    Frame frame;
    frame.n = normal;
    OrthonormalBasis(normal, frame.s, frame.t);
    return frame;
}

PF_GPU_FN vec3 ToWorld(Frame frame, vec3 local) {
    return frame.s * local.x + frame.t * local.y + frame.n * local.z;
}

PF_GPU_FN vec3 ToLocal(Frame frame, vec3 world) {
    return vec3(dot(world, frame.s), dot(world, frame.t), dot(world, frame.n));
}

PF_GPU_END

#endif  // PF_CORE_SHARED_FRAME_H
