// Stochastic choices a surface makes by a hash rather than a path's random numbers. Alpha
// cut-outs: where a surface is absent (pbrt's "alpha", glTF's alphaMode MASK and BLEND).
// A ray meets a point of alpha a there or passes through it: with a cutoff c > 0 (glTF's
// MASK), where a >= c; without one, with probability a, decided by a hash of the ray and the
// triangle (pbrt-v4's stochastic alpha test, glTF's BLEND as coverage), so the same ray always
// decides the same way and nothing draws from a path's random numbers. A single-sided surface
// (glTF's doubleSided false on an open mesh) is absent seen from behind. One definition for
// the CPU tracer's Embree filter and the Vulkan traversal.
#ifndef PF_CORE_SHARED_ALPHA_H
#define PF_CORE_SHARED_ALPHA_H

#include "core/shared/gpu_prelude.h"
#include "core/shared/gpu_types.h"
#include "core/shared/rng.h"

PF_GPU_BEGIN

// Uniform in [0, 1) from the ray (its origin's and direction's bits) and the triangle.
PF_GPU_FN float AlphaHash(vec3 origin, vec3 direction, uint32_t triangle) {
    uint64_t h = Mix64(uint64_t(floatBitsToUint(origin.x)) << 32 | floatBitsToUint(origin.y));
    h = Mix64(h ^ (uint64_t(floatBitsToUint(origin.z)) << 32 | floatBitsToUint(direction.x)));
    h = Mix64(h ^ (uint64_t(floatBitsToUint(direction.y)) << 32 | floatBitsToUint(direction.z)));
    h = Mix64(h ^ uint64_t(triangle));
    return float(uint32_t(h >> 40)) * 5.9604644775390625e-8f;
}

// Whether the ray meets a point of alpha `alpha` under cutoff `cutoff` (0: stochastic),
// `hash` AlphaHash's number for it.
PF_GPU_FN bool AlphaMeets(float alpha, float cutoff, float hash) {
    return cutoff > 0.0f ? alpha >= cutoff : hash < alpha;
}

// Whether a ray passes a surface of gpu::kSurface* `flags` by its back face: where it is
// single-sided and the ray's direction goes the way of the triangle's front normal
// (`direction_dot_normal`, of any scale, in one space), as every ray that meets it from behind.
PF_GPU_FN bool PassesBackFace(uint32_t flags, float direction_dot_normal) {
    return (flags & kSurfaceSingleSided) != 0u && direction_dot_normal > 0.0f;
}

// A mix material's choice at a surface point (pbrt-v4's MixMaterial picks by a hash of the
// point too): uniform in [0, 1) from the point's bits and its triangle, the same for every
// ray that meets it there.
PF_GPU_FN float MixHash(vec3 position, uint32_t triangle) {
    return AlphaHash(position, vec3(0.0f, 0.0f, 0.0f), triangle ^ 0x6d697875u);
}

PF_GPU_END

#endif  // PF_CORE_SHARED_ALPHA_H
