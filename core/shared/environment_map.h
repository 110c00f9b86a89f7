// Environment maps between images and directions, one definition for the CPU
// (core/scene/environment.cpp) and the Vulkan kernels (shaders/environment.glsl): pbrt-v4's
// equal-area octahedral square (Clarberg, "Fast equal-area mapping of the (hemi)sphere using
// SIMD", 2008, as pbrt-v4's ImageInfiniteLight uses it: z up) and the latitude-longitude map
// (y up, the image's centre toward -z), which texel a direction falls in, each texel row's
// solid angle, and a direction uniform in solid angle within a texel. Written in the
// vocabulary of gpu_prelude.h. Also a projection light's image, which pbrt-v4 maps onto
// directions by a perspective divide (ProjectionTexel, ProjectionPlanePoint), and the portal
// an environment may shine in through (PortalExit).
#ifndef PF_CORE_SHARED_ENVIRONMENT_MAP_H
#define PF_CORE_SHARED_ENVIRONMENT_MAP_H

#include "core/shared/gpu_prelude.h"

PF_GPU_BEGIN

// The mappings, numbered as core/scene/environment.h's EnvironmentMapping.
PF_CONST(uint32_t) kMappingUniform = 0;
PF_CONST(uint32_t) kMappingEqualArea = 1;
PF_CONST(uint32_t) kMappingLatLong = 2;

// |magnitude| with the sign bit of `sign` (C's copysign, which GLSL lacks).
PF_GPU_FN float CopySign(float magnitude, float sign) {
    return uintBitsToFloat((floatBitsToUint(magnitude) & 0x7fffffffu) |
                           (floatBitsToUint(sign) & 0x80000000u));
}

PF_GPU_FN vec3 EqualAreaSquareToSphere(vec2 p) {
    const float u = 2.0f * p.x - 1.0f, v = 2.0f * p.y - 1.0f;
    const float up = abs(u), vp = abs(v);
    const float signed_distance = 1.0f - (up + vp);
    const float r = 1.0f - abs(signed_distance);
    const float phi = (r == 0.0f ? 1.0f : (vp - up) / r + 1.0f) * (3.14159265358979323846f / 4.0f);
    const float z = CopySign(1.0f - r * r, signed_distance);
    const float sin_theta = r * sqrt(max(0.0f, 2.0f - r * r));
    return vec3(CopySign(cos(phi), u) * sin_theta, CopySign(sin(phi), v) * sin_theta, z);
}

PF_GPU_FN vec2 EqualAreaSphereToSquare(vec3 d) {
    const float x = abs(d.x), y = abs(d.y), z = abs(d.z);
    const float r = sqrt(max(0.0f, 1.0f - z));
    const float a = max(x, y);
    const float b = a == 0.0f ? 0.0f : min(x, y) / a;
    float phi = atan(b) * (2.0f / 3.14159265358979323846f);
    if (x < y) phi = 1.0f - phi;
    float v = phi * r;
    float u = r - v;
    if (d.z < 0.0f) {  // the lower hemisphere folds out over the square's corners
        const float swapped = u;
        u = 1.0f - v;
        v = 1.0f - swapped;
    }
    u = CopySign(u, d.x);
    v = CopySign(v, d.y);
    return vec2(0.5f * (u + 1.0f), 0.5f * (v + 1.0f));
}

// u = 1/2 + atan2(x, -z) / 2 pi, v = acos(y) / pi.
PF_GPU_FN vec3 LatLongToSphere(vec2 p) {
    const float phi = 6.28318530717958647692f * (p.x - 0.5f);
    const float theta = 3.14159265358979323846f * p.y;
    const float sin_theta = sin(theta);
    return vec3(sin_theta * sin(phi), cos(theta), -sin_theta * cos(phi));
}

PF_GPU_FN vec2 LatLongFromSphere(vec3 d) {
    return vec2(0.5f + atan(d.x, -d.z) * (1.0f / 6.28318530717958647692f),
                acos(clamp(d.y, -1.0f, 1.0f)) * (1.0f / 3.14159265358979323846f));
}

// The texel (y * width + x) a unit direction in the map's frame falls in.
PF_GPU_FN uint32_t EnvironmentTexel(uint32_t mapping, int32_t width, int32_t height, vec3 d) {
    const vec2 uv =
        mapping == kMappingEqualArea ? EqualAreaSphereToSquare(d) : LatLongFromSphere(d);
    const int32_t x = int32_t(clamp(uv.x * float(width), 0.0f, float(width - 1)));
    const int32_t y = int32_t(clamp(uv.y * float(height), 0.0f, float(height - 1)));
    return uint32_t(y) * uint32_t(width) + uint32_t(x);
}

// The solid angle of one texel of row y (sr): all alike on the equal-area square; in a
// latitude-longitude map the band between the row's polar angles over the row's texels.
PF_GPU_FN float EnvironmentTexelSolidAngle(uint32_t mapping, int32_t width, int32_t height,
                                           int32_t y) {
    if (mapping == kMappingEqualArea) return 12.566370614359172954f / float(width * height);
    const float theta0 = 3.14159265358979323846f * float(y) / float(height);
    const float theta1 = 3.14159265358979323846f * float(y + 1) / float(height);
    return 6.28318530717958647692f / float(width) * (cos(theta0) - cos(theta1));
}

// The direction at fractions (fx, fy) in [0, 1)^2 of texel (x, y), uniform in solid angle over
// the texel for uniform fractions: the equal-area square is so already; a latitude-longitude
// texel is uniform in longitude and in the cosine of the polar angle.
PF_GPU_FN vec3 EnvironmentDirectionInTexel(uint32_t mapping, int32_t width, int32_t height,
                                           uint32_t x, uint32_t y, float fx, float fy) {
    if (mapping == kMappingEqualArea)
        return EqualAreaSquareToSphere(
            vec2((float(x) + fx) / float(width), (float(y) + fy) / float(height)));
    const float cos0 = cos(3.14159265358979323846f * float(y) / float(height));
    const float cos1 = cos(3.14159265358979323846f * float(y + 1u) / float(height));
    const float cos_theta = cos0 + fy * (cos1 - cos0);
    const float sin_theta = sqrt(max(0.0f, 1.0f - cos_theta * cos_theta));
    const float phi = 6.28318530717958647692f * ((float(x) + fx) / float(width) - 0.5f);
    return vec3(sin_theta * sin(phi), cos_theta, -sin_theta * cos(phi));
}

// A projection light's image spans +-extent on the plane z = 1 of the light's frame, its
// first row toward -y. The point of that plane at image position (x, y), in texels from the
// image's first corner.
PF_GPU_FN vec3 ProjectionPlanePoint(vec2 extent, int32_t width, int32_t height, float x, float y) {
    return vec3((x / float(width) * 2.0f - 1.0f) * extent.x,
                (y / float(height) * 2.0f - 1.0f) * extent.y, 1.0f);
}

// The texel (y * width + x) that light-frame direction d falls in, or -1 outside the image's
// frustum or before pbrt-v4's near plane z = 1e-3 (ProjectionLight::I).
PF_GPU_FN int32_t ProjectionTexel(vec2 extent, int32_t width, int32_t height, vec3 d) {
    if (!(d.z >= 1e-3f)) return -1;
    const float px = d.x / d.z, py = d.y / d.z;
    if (!(abs(px) <= extent.x && abs(py) <= extent.y)) return -1;
    const int32_t x =
        int32_t(clamp((px + extent.x) / (2.0f * extent.x) * float(width), 0.0f, float(width - 1)));
    const int32_t y = int32_t(
        clamp((py + extent.y) / (2.0f * extent.y) * float(height), 0.0f, float(height - 1)));
    return y * width + x;
}

// Where a ray from `origin` toward unit `toward` leaves through a portal (a rectangle from
// `corner` along perpendicular edges u and v, its unit `normal` toward the environment): true
// with the distance t where it crosses it toward the outside (EnvironmentPortal::Exit).
PF_GPU_FN bool PortalExit(vec3 corner, vec3 u, vec3 v, vec3 normal, vec3 origin, vec3 toward,
                          PF_OUT(float) t) {
    const float facing = dot(toward, normal);
    if (!(facing > 0.0f)) return false;
    t = dot(corner - origin, normal) / facing;
    if (!(t >= 0.0f && t <= 3.4e38f)) return false;
    const vec3 q = origin + toward * t - corner;
    const float a = dot(q, u) / dot(u, u), b = dot(q, v) / dot(v, v);
    return a >= 0.0f && a <= 1.0f && b >= 0.0f && b <= 1.0f;
}

PF_GPU_END

#endif  // PF_CORE_SHARED_ENVIRONMENT_MAP_H
