// Curves (pbrt-v4's "curve" shape: hair, fur, grass): a cubic Bezier segment swept by a band
// whose width varies linearly along it. One definition, for the CPU passes and the Vulkan
// kernels, of what a hit on one is (CurveSurfaceAt) and of the Vulkan backend's ray test
// (IntersectCurve: the recursive subdivision pbrt-v4's Curve::RecursiveIntersect makes, Pharr,
// Jakob and Humphreys, "Physically Based Rendering", 4th ed., section 6.7.3, walked without a
// stack). The CPU traces curves with Embree's curve primitives (embree/embree_tracer.cpp).
//
// A segment's u runs from 0 to 1 along it, its v from 0 to 1 across it, pbrt-v4's: v grows
// toward cross(direction, tangent) for flat and cylinder curves, toward cross(normal, tangent)
// for ribbons. Flat and cylinder curves are bands facing the ray that meets them; a cylinder
// shades with the normal of a round tube at the hit's offset across; a ribbon is a band whose
// normal turns from one end's to the other's.
#ifndef PF_CORE_SHARED_CURVE_H
#define PF_CORE_SHARED_CURVE_H

#include "core/shared/gpu_prelude.h"
#include "core/shared/path_sampling.h"
#include "core/shared/shading_normal.h"

PF_GPU_BEGIN

// A hit's primitive (RayHit::triangle) and a GPU BVH leaf slot's (GpuTriangle::p0.w) is a
// curve where this bit is set: the rest is its index.
PF_CONST(uint32_t) kCurveBit = 0x80000000u;
// Curve types, as core/scene/scene.h numbers them.
PF_CONST(uint32_t) kCurveFlat = 0;
PF_CONST(uint32_t) kCurveCylinder = 1;
PF_CONST(uint32_t) kCurveRibbon = 2;
// pbrt-v4's deepest subdivision of a segment (2^10 pieces).
PF_CONST(int) kMaxCurveDepth = 10;

// The cubic Bezier curve of control points p0..p3 at u, and its derivative.
PF_GPU_FN vec3 BezierPoint(vec3 p0, vec3 p1, vec3 p2, vec3 p3, float u) {
    const float s = 1.0f - u;
    return p0 * (s * s * s) + p1 * (3.0f * s * s * u) + p2 * (3.0f * s * u * u) + p3 * (u * u * u);
}
PF_GPU_FN vec3 BezierDerivative(vec3 p0, vec3 p1, vec3 p2, vec3 p3, float u) {
    const float s = 1.0f - u;
    return (p1 - p0) * (3.0f * s * s) + (p2 - p1) * (6.0f * s * u) + (p3 - p2) * (3.0f * u * u);
}

// The blossom of the curve at (a, b, c): the control points of its piece over [u0, u1] are the
// blossoms at (u0, u0, u0), (u0, u0, u1), (u0, u1, u1) and (u1, u1, u1).
PF_GPU_FN vec3 BezierBlossom(vec3 p0, vec3 p1, vec3 p2, vec3 p3, float a, float b, float c) {
    const vec3 q0 = p0 + (p1 - p0) * a, q1 = p1 + (p2 - p1) * a, q2 = p2 + (p3 - p2) * a;
    const vec3 r0 = q0 + (q1 - q0) * b, r1 = q1 + (q2 - q1) * b;
    return r0 + (r1 - r0) * c;
}

// A ribbon's normal at u: the unit end normals n0 and n1 spherically interpolated.
PF_GPU_FN vec3 RibbonNormal(vec3 n0, vec3 n1, float u) {
    const float angle = acos(clamp(dot(n0, n1), -1.0f, 1.0f));
    if (!(angle > 1e-5f)) return n0;
    const float inverse_sin = 1.0f / sin(angle);
    return n0 * (sin((1.0f - u) * angle) * inverse_sin) + n1 * (sin(u * angle) * inverse_sin);
}

// The unit tangent at u; where the derivative vanishes (a cusp), the chord's direction, and
// where that does too, any direction across `direction`.
PF_GPU_FN vec3 CurveTangent(vec3 p0, vec3 p1, vec3 p2, vec3 p3, float u, vec3 direction) {
    vec3 tangent = BezierDerivative(p0, p1, p2, p3, u);
    if (!(dot(tangent, tangent) > 0.0f)) tangent = p3 - p0;
    if (!(dot(tangent, tangent) > 0.0f)) {
        vec3 s, t;
        OrthonormalBasis(direction, s, t);
        return s;
    }
    return normalize(tangent);
}

// The surface a ray of unit `direction` meets at (u, v) on a segment (control points p0..p3,
// widths w0, w1 at its ends, type kCurve*, a ribbon's unit end normals n0, n1): `geometric`, the
// unit normal whose side is the front (flat and cylinder curves: the ray's side; ribbons: their
// normals'), `shading`, on the same side, and `position`, the hit's point across the band moved
// one width toward the ray's side, so that rays leaving it toward that side clear the curve (as
// pbrt-v4's error bounds of one width move them).
PF_GPU_FN void CurveSurfaceAt(vec3 p0, vec3 p1, vec3 p2, vec3 p3, float w0, float w1, uint32_t type,
                              vec3 n0, vec3 n1, float u, float v, vec3 direction,
                              PF_OUT(vec3) position, PF_OUT(vec3) geometric, PF_OUT(vec3) shading) {
    const vec3 tangent = CurveTangent(p0, p1, p2, p3, u, direction);
    const vec3 centre = BezierPoint(p0, p1, p2, p3, u);
    const float width = w0 + (w1 - w0) * u;
    if (type == kCurveRibbon) {
        const vec3 normal = PerpendicularTo(tangent, RibbonNormal(n0, n1, u));
        const vec3 across = cross(normal, tangent);
        const vec3 toward_ray = dot(direction, normal) < 0.0f ? normal : normal * -1.0f;
        position = centre + across * ((v - 0.5f) * width) + toward_ray * width;
        geometric = normal;
        shading = normal;
        return;
    }
    const vec3 facing = PerpendicularTo(tangent, direction * -1.0f);
    const vec3 across = cross(tangent, facing);  // normalize(cross(direction, tangent))
    position = centre + across * ((v - 0.5f) * width) + facing * width;
    geometric = facing;
    shading = facing;
    if (type == kCurveCylinder) {
        // A round tube seen across its width: the normal where the ray's offset from its axis
        // is s of its radius. (pbrt-v4 turns the normal by 90 degrees x s instead, and toward
        // the far side: its cylinders are lit as if from the mirrored direction; docs/scenes.md.)
        const float s = clamp(2.0f * v - 1.0f, -1.0f, 1.0f);
        shading = normalize(facing * sqrt(max(0.0f, 1.0f - s * s)) + across * s);
    }
}

// v at `point` on a segment (as CurveSurfaceAt takes it) for a ray of unit `direction` that met
// it at u: the point's offset across the band from its centre, over its width, from 1/2.
PF_GPU_FN float CurveAcross(vec3 p0, vec3 p1, vec3 p2, vec3 p3, float w0, float w1, uint32_t type,
                            vec3 n0, vec3 n1, float u, vec3 point, vec3 direction) {
    const vec3 tangent = CurveTangent(p0, p1, p2, p3, u, direction);
    vec3 across;
    if (type == kCurveRibbon)
        across = cross(PerpendicularTo(tangent, RibbonNormal(n0, n1, u)), tangent);
    else
        across = cross(tangent, PerpendicularTo(tangent, direction * -1.0f));
    const float width = w0 + (w1 - w0) * u;
    if (!(width > 0.0f)) return 0.5f;
    return clamp(0.5f + dot(point - BezierPoint(p0, p1, p2, p3, u), across) / width, 0.0f, 1.0f);
}

// How many times pbrt-v4 halves a segment before testing its pieces as lines: enough that a
// piece lies within 1/20 of the wider end's width of its chord (Curve::IntersectRay's maxDepth,
// from the control polygon's second differences L0, in any frame).
PF_GPU_FN int CurveDepth(vec3 p0, vec3 p1, vec3 p2, vec3 p3, float w0, float w1) {
    const vec3 d0 = p0 - p1 * 2.0f + p2, d1 = p1 - p2 * 2.0f + p3;
    const float l0 =
        max(max(max(abs(d0.x), abs(d0.y)), max(abs(d0.z), abs(d1.x))), max(abs(d1.y), abs(d1.z)));
    const float eps = max(w0, w1) * 0.05f;
    if (!(l0 > 0.0f) || !(eps > 0.0f)) return 0;
    // log4 of the ratio: log2 rounded to the nearest integer, halved (pbrt-v4's Log2Int / 2).
    const float ratio = 1.41421356237f * 6.0f * l0 / (8.0f * eps);
    if (!(ratio >= 1.0f)) return 0;
    const int depth = int(floor(log2(ratio) + 0.5f)) / 2;
    return depth < kMaxCurveDepth ? depth : kMaxCurveDepth;
}

// Whether the box of points a..d, grown by `margin`, meets the ray's segment from its origin to
// depth `t_max` along +z (in the ray's frame).
PF_GPU_FN bool CurvePieceMeetsRay(vec3 a, vec3 b, vec3 c, vec3 d, float margin, float t_max) {
    const float x0 = min(min(a.x, b.x), min(c.x, d.x)) - margin;
    const float x1 = max(max(a.x, b.x), max(c.x, d.x)) + margin;
    const float y0 = min(min(a.y, b.y), min(c.y, d.y)) - margin;
    const float y1 = max(max(a.y, b.y), max(c.y, d.y)) + margin;
    const float z0 = min(min(a.z, b.z), min(c.z, d.z)) - margin;
    const float z1 = max(max(a.z, b.z), max(c.z, d.z)) + margin;
    return x0 <= 0.0f && x1 >= 0.0f && y0 <= 0.0f && y1 >= 0.0f && z1 >= 0.0f && z0 <= t_max;
}

// The closest hit of the ray (origin, unit direction) on a segment (as CurveSurfaceAt takes it)
// with 0 < t < t_max: pbrt-v4's test. In the ray's frame (the ray along +z), the segment is
// halved CurveDepth times, pieces whose boxes miss the ray dropped; each piece left is tested as
// the line between its ends: the ray must pass between the perpendiculars of its end tangents,
// within half the width (a ribbon's foreshortened by |cos| of its normal to the ray) of the
// curve near the line's nearest point (refined to the piece's own nearest, which pbrt-v4 does
// not do), whose depth is t. The halvings are walked as a binary tree
// without a stack, each piece's control points the blossoms of the segment's.
PF_GPU_FN bool IntersectCurve(vec3 origin, vec3 direction, float t_max, vec3 p0, vec3 p1, vec3 p2,
                              vec3 p3, float w0, float w1, uint32_t type, vec3 n0, vec3 n1,
                              PF_OUT(float) t, PF_OUT(float) u, PF_OUT(float) v) {
    t = 0.0f;
    u = 0.0f;
    v = 0.0f;
    vec3 ex, ey;
    OrthonormalBasis(direction, ex, ey);  // ex x ey = direction
    const vec3 a0 = p0 - origin, a1 = p1 - origin, a2 = p2 - origin, a3 = p3 - origin;
    const vec3 c0 = vec3(dot(a0, ex), dot(a0, ey), dot(a0, direction));
    const vec3 c1 = vec3(dot(a1, ex), dot(a1, ey), dot(a1, direction));
    const vec3 c2 = vec3(dot(a2, ex), dot(a2, ey), dot(a2, direction));
    const vec3 c3 = vec3(dot(a3, ex), dot(a3, ey), dot(a3, direction));
    const int depth = CurveDepth(c0, c1, c2, c3, w0, w1);
    bool found = false;
    int level = 0;
    uint32_t index = 0;
    while (true) {
        const float scale = 1.0f / float(1u << uint32_t(level));
        const float u0 = float(index) * scale, u1 = float(index + 1u) * scale;
        const vec3 q0 = BezierBlossom(c0, c1, c2, c3, u0, u0, u0);
        const vec3 q1 = BezierBlossom(c0, c1, c2, c3, u0, u0, u1);
        const vec3 q2 = BezierBlossom(c0, c1, c2, c3, u0, u1, u1);
        const vec3 q3 = BezierBlossom(c0, c1, c2, c3, u1, u1, u1);
        const float half_width = 0.5f * max(w0 + (w1 - w0) * u0, w0 + (w1 - w0) * u1);
        const bool meets = CurvePieceMeetsRay(q0, q1, q2, q3, half_width, t_max);
        if (meets && level < depth) {  // its halves next, the first first
            ++level;
            index *= 2u;
            continue;
        }
        if (meets) {
            // The ray must lie past the perpendicular of each end's tangent, inward.
            const bool inside = (q1.x - q0.x) * -q0.x + (q1.y - q0.y) * -q0.y >= 0.0f &&
                                (q2.x - q3.x) * -q3.x + (q2.y - q3.y) * -q3.y >= 0.0f;
            const float chord_x = q3.x - q0.x, chord_y = q3.y - q0.y;
            const float chord_sq = chord_x * chord_x + chord_y * chord_y;
            if (inside && chord_sq > 0.0f) {
                // The nearest point of the chord, then (beyond pbrt-v4) two Newton steps
                // toward the piece's own nearest point to the ray, whose distance and v the
                // chord's parameter would misplace along a bent piece.
                float w = clamp((-q0.x * chord_x - q0.y * chord_y) / chord_sq, 0.0f, 1.0f);
                for (int step = 0; step < 2; ++step) {
                    const vec3 b = BezierPoint(q0, q1, q2, q3, w);
                    const vec3 db = BezierDerivative(q0, q1, q2, q3, w);
                    const vec3 ddb = (q2 - q1 * 2.0f + q0) * (6.0f * (1.0f - w)) +
                                     (q3 - q2 * 2.0f + q1) * (6.0f * w);
                    const float slope = db.x * db.x + db.y * db.y + b.x * ddb.x + b.y * ddb.y;
                    if (slope > 0.0f) w = clamp(w - (b.x * db.x + b.y * db.y) / slope, 0.0f, 1.0f);
                }
                const float hit_u = clamp(u0 + (u1 - u0) * w, u0, u1);
                float hit_width = w0 + (w1 - w0) * hit_u;
                // A ribbon narrows as it turns from the ray; its v runs toward
                // cross(normal, tangent), away from cross(direction, tangent) seen from its front.
                const float facing =
                    type == kCurveRibbon ? dot(RibbonNormal(n0, n1, hit_u), direction) : 1.0f;
                hit_width *= abs(facing);
                const float along = w;
                const vec3 pc = BezierPoint(q0, q1, q2, q3, along);
                const float distance_sq = pc.x * pc.x + pc.y * pc.y;
                if (hit_width > 0.0f && distance_sq <= 0.25f * hit_width * hit_width &&
                    pc.z > 0.0f && pc.z < t_max) {
                    const vec3 dpc = BezierDerivative(q0, q1, q2, q3, along);
                    // The side of the curve the ray passes: v above 1/2 toward
                    // cross(+z, tangent).
                    const float side = dpc.x * -pc.y + pc.x * dpc.y;
                    const float offset = sqrt(distance_sq) / hit_width;
                    t = pc.z;
                    u = hit_u;
                    v = (side > 0.0f) == (facing > 0.0f) ? 0.5f + offset : 0.5f - offset;
                    t_max = pc.z;
                    found = true;
                }
            }
        }
        // The next piece: up while this is a second half, then the second half beside it.
        while ((index & 1u) == 1u && level > 0) {
            index >>= 1u;
            --level;
        }
        if (level == 0) break;
        ++index;
    }
    return found;
}

PF_GPU_END

#endif  // PF_CORE_SHARED_CURVE_H
