// Warping uniform samples to the distributions photon mapping needs. Each function states its
// density so callers can divide by it; all directions are unit vectors.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/math/vec3.h"

namespace pf {

struct Point2 {
    float x = 0, y = 0;
};

// Shirley-Chiu concentric map of the unit square onto the unit disk; uniform density 1/pi.
inline Point2 SampleUniformDisk(float u1, float u2) {
    const float a = 2.0f * u1 - 1.0f, b = 2.0f * u2 - 1.0f;
    if (a == 0.0f && b == 0.0f) return {0.0f, 0.0f};
    float radius, phi;
    if (std::abs(a) > std::abs(b)) {
        radius = a;
        phi = (kPi / 4.0f) * (b / a);
    } else {
        radius = b;
        phi = (kPi / 2.0f) - (kPi / 4.0f) * (a / b);
    }
    return {radius * std::cos(phi), radius * std::sin(phi)};
}

// Cosine-weighted direction about +z (Malley's method); density cos(theta)/pi.
inline Vec3 SampleCosineHemisphere(float u1, float u2) {
    const Point2 d = SampleUniformDisk(u1, u2);
    const float z = std::sqrt(std::max(0.0f, 1.0f - d.x * d.x - d.y * d.y));
    return {d.x, d.y, z};
}

// Uniform direction on the unit sphere; density 1/(4 pi).
inline Vec3 SampleUniformSphere(float u1, float u2) {
    const float z = 1.0f - 2.0f * u1;
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = 2.0f * kPi * u2;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

// Uniform direction in the cone about +z with cos(half angle) = cos_max;
// density 1/(2 pi (1 - cos_max)).
inline Vec3 SampleUniformCone(float u1, float u2, float cos_max) {
    const float cos_theta = 1.0f - u1 * (1.0f - cos_max);
    const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
    const float phi = 2.0f * kPi * u2;
    return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}

// Uniform barycentrics (b1, b2) on a triangle (Heitz 2019, "A Low-Distortion Map Between
// Triangle and Square"); density 1/area.
inline Point2 SampleUniformTriangle(float u1, float u2) {
    float b0, b1;
    if (u1 < u2) {
        b0 = u1 / 2.0f;
        b1 = u2 - b0;
    } else {
        b1 = u2 / 2.0f;
        b0 = u1 - b1;
    }
    return {b0, b1};
}

}  // namespace pf
