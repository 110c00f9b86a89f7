// A hit point's gather region, one definition for the CPU (core/ppm/hash_grid.h) and the Vulkan
// kernel (photon_trace.comp). A hit point's sphere of radius R takes in photons across a room's
// concave edge (on the next wall, whose light is not its own), across a thin wall (the ground
// on its other side), and holds less than pi R^2 of its surface at a convex edge (a block's
// rim): edges show as bright and dark lines that only shrinking radii remove. So a hit point
// gathers only the photons that landed on its own surface (SameSurface) within where that
// surface reaches about it: per octant of its tangent plane, a reach in 255ths of R
// (core/camera/surface_extent.h probes it), eight bytes a hit point. The estimate divides by
// the area of that region (SurfaceExtent::AreaFraction), so it stays a density over the
// surface the photons could land on.
#ifndef PF_CORE_SHARED_SURFACE_EDGES_H
#define PF_CORE_SHARED_SURFACE_EDGES_H

#include "core/shared/gpu_prelude.h"
#include "core/shared/path_sampling.h"

PF_GPU_BEGIN

// The octants of a hit point's tangent plane (OrthonormalBasis of its normal: s, t), counted
// from s toward t, each with a byte of reach: sector j's in bits 8j to 8j + 7.
PF_CONST(uint32_t) kEdgeSectors = 8u;
// A sector's full reach: its surface goes on to R or beyond.
PF_CONST(uint32_t) kEdgeReachFull = 255u;
// Every sector's reach full: the surface fills the disc (no test needed).
PF_CONST(uint64_t) kUnboundedEdges = 0xfffffffffffffffful;

// Whether a photon that landed on a surface of unit normal `landed` (turned toward the side it
// arrived from) is on the surface of a hit point of normal `normal` (any length): normals within
// 60 degrees, a surface's facets and bump-mapped normals included, a room's next wall not.
PF_GPU_FN bool SameSurface(vec3 normal, vec3 landed) {
    const float cosine = dot(normal, landed);
    return cosine > 0.0f && 4.0f * cosine * cosine >= dot(normal, normal);
}

// The octant of the tangent-plane offset (x, y).
PF_GPU_FN uint32_t EdgeSector(float x, float y) {
    // The offset turned by quarter turns into the first quadrant, (a, b): then which half.
    uint32_t quadrant = 0u;
    float a = x, b = y;
    if (y >= 0.0f) {
        if (x < 0.0f) quadrant = 1u, a = y, b = -x;
    } else if (x < 0.0f) {
        quadrant = 2u, a = -x, b = -y;
    } else {
        quadrant = 3u, a = -y, b = x;
    }
    return 2u * quadrant + (b > a ? 1u : 0u);
}

// Whether a hit point of normal `normal` (any length) and `edges`, whose sphere of squared
// radius `radius_sq` holds a photon at `offset` from it that landed on a surface of normal
// `landed`, gathers it: anywhere in the sphere where its surface fills the disc (a probe found
// no edge within R, so no other surface lies there either), else only on its own surface
// (SameSurface) within its reach in the photon's octant.
PF_GPU_FN bool WithinSurfaceEdges(uint64_t edges, vec3 normal, vec3 landed, vec3 offset,
                                  float radius_sq) {
    if (edges == kUnboundedEdges) return true;
    if (!SameSurface(normal, landed)) return false;
    vec3 s, t;
    OrthonormalBasis(normalize(normal), s, t);
    const float x = dot(offset, s), y = dot(offset, t);
    const float reach = float(uint32_t(edges >> (8u * EdgeSector(x, y))) & 255u) * (1.0f / 255.0f);
    return x * x + y * y <= reach * reach * radius_sq;
}

PF_GPU_END

#endif  // PF_CORE_SHARED_SURFACE_EDGES_H
