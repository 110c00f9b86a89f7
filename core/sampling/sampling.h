// Warping uniform samples to the distributions photon mapping needs. Each function states its
// density so callers can divide by it; all directions are unit vectors.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/math/fast_trig.h"
#include "core/math/vec3.h"

namespace pf {

struct Point2 {
    float x = 0, y = 0;
};

// Polar map of the unit square onto the unit disk; uniform density 1/pi. Chosen over
// Shirley and Chiu's concentric map, whose lower distortion matters only for stratified
// samples: its choice of wedge is a branch the predictor loses half the time, and this is the
// innermost loop of the photon pass.
inline Point2 SampleUniformDisk(float u1, float u2) {
    const float radius = std::sqrt(u1);
    float sine, cosine;
    SinCosTurns(u2, &sine, &cosine);
    return {radius * cosine, radius * sine};
}

// Cosine-weighted direction about +z (Malley's method: the disk lifted to the hemisphere);
// density cos(theta)/pi. The disk point's squared radius is u1, so z comes from u1 directly,
// in parallel with the disk point rather than after it.
inline Vec3 SampleCosineHemisphere(float u1, float u2) {
    const Point2 d = SampleUniformDisk(u1, u2);
    const float z = std::sqrt(std::max(0.0f, 1.0f - u1));
    return {d.x, d.y, z};
}

// Uniform direction on the unit sphere; density 1/(4 pi).
inline Vec3 SampleUniformSphere(float u1, float u2) {
    const float z = 1.0f - 2.0f * u1;
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    float sine, cosine;
    SinCosTurns(u2, &sine, &cosine);
    return {r * cosine, r * sine, z};
}

// Uniform direction in the cone about +z with cos(half angle) = cos_max;
// density 1/(2 pi (1 - cos_max)).
inline Vec3 SampleUniformCone(float u1, float u2, float cos_max) {
    const float cos_theta = 1.0f - u1 * (1.0f - cos_max);
    const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
    float sine, cosine;
    SinCosTurns(u2, &sine, &cosine);
    return {sin_theta * cosine, sin_theta * sine, cos_theta};
}

// Uniform barycentrics (b1, b2) on a triangle by the square-root map (Shirley 1990); density
// 1/area. Branch-free, unlike Heitz's lower-distortion map, for the reason given above.
inline Point2 SampleUniformTriangle(float u1, float u2) {
    const float root = std::sqrt(u1);
    return {u2 * root, 1.0f - root};
}

}  // namespace pf
