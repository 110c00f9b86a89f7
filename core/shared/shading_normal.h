// The shading normal's detail and what photons owe it. Normal maps (glTF's normalTexture, pbrt's
// normalmap): a texel is a normal in the tangent frame of the interpolated normal, the vertex
// tangent (MikkTSpace's, core/scene/tangents.h) and the bitangent sign x cross(normal, tangent).
// Bump maps (pbrt's displacement): the normal of the surface moved along the normal by a
// displacement texture, as pbrt-v4's BumpMap makes it for a triangle. Photons: Veach's adjoint
// for shading normals (thesis, 1997, section 5.3), so that photon density estimates the same
// radiance as a path tracer shading with the same normals. One definition for the CPU passes
// and the Vulkan kernels.
#ifndef PF_CORE_SHARED_SHADING_NORMAL_H
#define PF_CORE_SHARED_SHADING_NORMAL_H

#include "core/shared/gpu_prelude.h"
#include "core/shared/path_sampling.h"

PF_GPU_BEGIN

// A unit vector perpendicular to unit `n`: `direction` without its part along n, or where
// that is (nearly) nothing, any perpendicular.
PF_GPU_FN vec3 PerpendicularTo(vec3 n, vec3 direction) {
    const vec3 t = direction - n * dot(n, direction);
    if (dot(t, t) > 1e-12f * dot(direction, direction) && dot(t, t) > 0.0f) return normalize(t);
    vec3 s, u;
    OrthonormalBasis(n, s, u);
    return s;
}

// The unit normal a normal map's linear texel (each channel in [0, 1], 0.5 meaning 0) gives at
// a point of unit shading normal `n`, vertex tangent `tangent` and bitangent sign `sign`; x and
// y scaled by `scale` (glTF's normalTexture.scale). A texel pointing below the surface's tangent
// plane is lifted into it.
PF_GPU_FN vec3 NormalFromMap(vec3 n, vec3 tangent, float sign, vec3 texel, float scale) {
    const vec3 t = PerpendicularTo(n, tangent);
    const vec3 b = cross(n, t) * (sign < 0.0f ? -1.0f : 1.0f);
    const float x = (2.0f * texel.x - 1.0f) * scale, y = (2.0f * texel.y - 1.0f) * scale;
    const float z = max(2.0f * texel.z - 1.0f, 1e-3f);
    return normalize(t * x + b * y + n * z);
}

// The unit normal of a surface of unit normal `n` and dP/du `dpdu` displaced along n by d(u, v),
// whose derivatives are `d_u` and `d_v` (glTF's v, pointing down the image): pbrt-v4's BumpMap
// with its shading frame ss = dpdu made perpendicular to n, ts = cross(n, ss) (pbrt's v points
// up the image: its dP/dv), and the displacement's own curvature term (d dn/du) left out.
PF_GPU_FN vec3 NormalFromBump(vec3 n, vec3 dpdu, float d_u, float d_v) {
    const vec3 ss = dpdu - n * dot(n, dpdu);  // none where dpdu is: the normal is kept
    const vec3 ts = cross(n, ss);
    const vec3 bumped = cross(ss + n * d_u, ts - n * d_v);
    return dot(bumped, bumped) > 0.0f ? normalize(bumped) : n;
}

// A procedural displacement (evaluated at points, core/shared/procedural_texture.h) is
// differenced as pbrt-v4's BumpMap does without ray differentials: steps of 0.0005 in u and v,
// the point moved along NormalFromBump's frame, ss (axis 0) and ts (axis 1), by the step.
PF_CONST(float) kBumpStep = 0.0005f;
PF_GPU_FN vec3 BumpFrameAxis(vec3 n, vec3 dpdu, int32_t axis) {
    const vec3 ss = dpdu - n * dot(n, dpdu);
    return axis == 0 ? ss : cross(n, ss);
}

// dP/du of a triangle with edges e1 = p1 - p0, e2 = p2 - p0 and texture-coordinate edges duv1,
// duv2; zero where its texture coordinates span no area.
PF_GPU_FN vec3 TriangleDpDu(vec3 e1, vec3 e2, vec2 duv1, vec2 duv2) {
    const float determinant = duv1.x * duv2.y - duv2.x * duv1.y;
    if (!(abs(determinant) > 1e-20f)) return vec3(0.0f, 0.0f, 0.0f);
    return (e1 * duv2.y - e2 * duv1.y) * (1.0f / determinant);
}

// The side of a normal map's bitangent on a triangle (edges e1, e2, texture-coordinate edges
// duv1, duv2) of geometric normal `n`: +1 where it is cross(n, tangent), -1 where the texture
// is mirrored there. The bitangent points up the image (against glTF's v), as MikkTSpace's
// does for a model made with v up; each triangle's own, MikkTSpace's per-face orientation.
PF_GPU_FN float BitangentSign(vec3 n, vec3 e1, vec3 e2, vec2 duv1, vec2 duv2) {
    const float determinant = duv1.x * duv2.y - duv2.x * duv1.y;
    return determinant * dot(n, cross(e1, e2)) > 0.0f ? -1.0f : 1.0f;
}

// Veach's adjoint BSDF for shading normals: a photon meeting a surface of shading normal
// `shading` and geometric normal `geometric` along `arriving` (its direction of travel) and
// leaving along `leaving`, sampled by the shading normal, carries the BSDF's weight times
//     |arriving . shading| / |arriving . geometric|  (ShadingArrival: where it lands, too)
//   x |leaving . geometric| / |leaving . shading|    (ShadingDeparture),
// both 1 where the two normals are one. Light from below the shading normal's plane is none
// to what the surface reflects (the path tracer samples it above): arriving from there, 0; as
// where a denominator is 0.
PF_GPU_FN float ShadingArrival(vec3 arriving, vec3 shading, vec3 geometric) {
    const float along = dot(arriving, shading), across = dot(arriving, geometric);
    return along * across > 0.0f ? along / across : 0.0f;
}
PF_GPU_FN float ShadingDeparture(vec3 leaving, vec3 shading, vec3 geometric) {
    const float along = abs(dot(leaving, shading));
    return along > 0.0f ? abs(dot(leaving, geometric)) / along : 0.0f;
}

PF_GPU_END

#endif  // PF_CORE_SHARED_SHADING_NORMAL_H
