// The sampling and scattering maths of photon and light paths, one definition for the CPU
// (core/sampling/fast_trig.h, core/sampling/sampling.h, core/sampling/frame.h,
// core/shared/scatter.h and core/geometry/ray.h call it) and the Vulkan kernels: the same numbers
// in, nearly the same paths out. Written in the vocabulary of gpu_prelude.h.
#ifndef PF_CORE_SHARED_PATH_SAMPLING_H
#define PF_CORE_SHARED_PATH_SAMPLING_H

#include "core/shared/gpu_prelude.h"

PF_GPU_BEGIN

// sin(2 pi u) and cos(2 pi u) for u in [0, 1), without a libm call: the photon loop samples a
// direction at every bounce, and libm's sincosf (about 15 ns here) was its largest single
// cost after the ray cast. Absolute error below 4e-7. Reduce to the nearest quarter turn:
// u = k/4 + r with |r| <= 1/8, so the polynomials only need |angle| <= pi/4, where their
// truncation error is below 3.2e-7 (sine) and 2.5e-8 (cosine); truncation rounds here since
// 4u + 1/2 >= 0.
PF_GPU_FN void SinCosTurns(float u, PF_OUT(float) sine, PF_OUT(float) cosine) {
    const int32_t k = int32_t(4.0f * u + 0.5f);
    const float angle = 6.28318530717958647692f * (u - 0.25f * float(k));
    const float a2 = angle * angle;
    const float s =
        angle * (1.0f + a2 * (-1.0f / 6.0f + a2 * (1.0f / 120.0f + a2 * (-1.0f / 5040.0f))));
    const float c =
        1.0f + a2 * (-0.5f + a2 * (1.0f / 24.0f + a2 * (-1.0f / 720.0f + a2 * (1.0f / 40320.0f))));
    // Rotate by k quarter turns: k odd swaps sine and cosine; the signs follow the quadrant.
    const bool swap = (k & 1) != 0;
    const float sin_base = swap ? c : s, cos_base = swap ? s : c;
    const uint32_t sin_sign = uint32_t(k & 2) << 30;        // k = 2, 3: negate sine
    const uint32_t cos_sign = uint32_t((k + 1) & 2) << 30;  // k = 1, 2: negate cosine
    sine = uintBitsToFloat(floatBitsToUint(sin_base) ^ sin_sign);
    cosine = uintBitsToFloat(floatBitsToUint(cos_base) ^ cos_sign);
}

// Polar map of the unit square onto the unit disk; uniform density 1/pi. Chosen over
// Shirley and Chiu's concentric map, whose lower distortion matters only for stratified
// samples: its choice of wedge is a branch the predictor loses half the time, and this is the
// innermost loop of the photon pass.
PF_GPU_FN vec2 SampleUniformDisk(float u1, float u2) {
    const float radius = sqrt(u1);
    float sine, cosine;
    SinCosTurns(u2, sine, cosine);
    return vec2(radius * cosine, radius * sine);
}

// Cosine-weighted direction about +z (Malley's method: the disk lifted to the hemisphere);
// density cos(theta)/pi. The disk point's squared radius is u1, so z comes from u1 directly,
// in parallel with the disk point rather than after it.
PF_GPU_FN vec3 SampleCosineHemisphere(float u1, float u2) {
    const vec2 d = SampleUniformDisk(u1, u2);
    return vec3(d.x, d.y, sqrt(max(0.0f, 1.0f - u1)));
}

// Uniform direction on the unit sphere; density 1/(4 pi).
PF_GPU_FN vec3 SampleUniformSphere(float u1, float u2) {
    const float z = 1.0f - 2.0f * u1;
    const float r = sqrt(max(0.0f, 1.0f - z * z));
    float sine, cosine;
    SinCosTurns(u2, sine, cosine);
    return vec3(r * cosine, r * sine, z);
}

// Uniform direction in the cone about +z with cos(half angle) = cos_max;
// density 1/(2 pi (1 - cos_max)).
PF_GPU_FN vec3 SampleUniformCone(float u1, float u2, float cos_max) {
    const float cos_theta = 1.0f - u1 * (1.0f - cos_max);
    const float sin_theta = sqrt(max(0.0f, 1.0f - cos_theta * cos_theta));
    float sine, cosine;
    SinCosTurns(u2, sine, cosine);
    return vec3(sin_theta * cosine, sin_theta * sine, cos_theta);
}

// Uniform barycentrics (b1, b2) on a triangle by the square-root map (Shirley 1990); density
// 1/area. Branch-free, unlike Heitz's lower-distortion map, for the reason given above.
PF_GPU_FN vec2 SampleUniformTriangle(float u1, float u2) {
    const float root = sqrt(u1);
    return vec2(u2 * root, 1.0f - root);
}

// Veach's power heuristic with beta = 2 (Veach 1997, section 9.2.4): the weight of a sample
// drawn with density `chosen` where another strategy would have drawn it with density `other`.
// KHR_lights_punctual's recommended window for a light of `range` at `distance`:
// clamp(1 - (d / range)^4, 0, 1); 1 without a range (0).
PF_GPU_FN float RangeWindow(float distance, float range) {
    if (range <= 0.0f) return 1.0f;
    const float r = distance / range, r2 = r * r;
    return max(0.0f, 1.0f - r2 * r2);
}

PF_GPU_FN float PowerHeuristic(float chosen, float other) {
    const float a = chosen * chosen, b = other * other;
    return a + b > 0.0f ? a / (a + b) : 0.0f;
}

// Tangents s, t completing the unit normal n to an orthonormal frame, without branches on
// the sign of n.z (Duff et al. 2017, "Building an Orthonormal Basis, Revisited", JCGT 6(1)).
PF_GPU_FN void OrthonormalBasis(vec3 n, PF_OUT(vec3) s, PF_OUT(vec3) t) {
    const float sign =
        uintBitsToFloat((floatBitsToUint(n.z) & 0x80000000u) | 0x3f800000u);  // copysign(1, z)
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    s = vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    t = vec3(b, sign + n.y * n.y * a, -n.y);
}

// Unpolarised Fresnel reflectance of a dielectric interface. cos_incident in [0, 1] on the
// incident side; eta = n_incident / n_transmitted. Total internal reflection gives 1.
PF_GPU_FN float FresnelDielectric(float cos_incident, float eta) {
    cos_incident = clamp(cos_incident, 0.0f, 1.0f);
    const float sin_t_sq = eta * eta * (1.0f - cos_incident * cos_incident);
    if (sin_t_sq >= 1.0f) return 1.0f;
    const float cos_t = sqrt(1.0f - sin_t_sq);
    const float r_parallel = (cos_incident - eta * cos_t) / (cos_incident + eta * cos_t);
    const float r_perpendicular = (eta * cos_incident - cos_t) / (eta * cos_incident + cos_t);
    return 0.5f * (r_parallel * r_parallel + r_perpendicular * r_perpendicular);
}

// Beer-Lambert: the fraction of light that crosses `distance` of a volume whose absorption
// coefficient is sigma_a in each channel.
PF_GPU_FN vec3 BeerLambert(vec3 sigma_a, float distance) {
    return vec3(exp(-sigma_a.x * distance), exp(-sigma_a.y * distance), exp(-sigma_a.z * distance));
}

// Refracts direction d through the interface with normal n facing the incident side
// (dot(d, n) < 0); eta = n_incident / n_transmitted. False under total internal reflection.
PF_GPU_FN bool Refract(vec3 d, vec3 n, float eta, PF_OUT(vec3) refracted) {
    const float cos_i = -dot(d, n);
    const float sin_t_sq = eta * eta * max(0.0f, 1.0f - cos_i * cos_i);
    if (sin_t_sq >= 1.0f) return false;
    const float cos_t = sqrt(1.0f - sin_t_sq);
    refracted = normalize(d * eta + n * (eta * cos_i - cos_t));
    return true;
}

// What a path carries, which decides what a refraction does to it (pbrt-v4's TransportMode):
// camera paths (every integrator's, the path tracer's, final gathering) carry radiance, photons
// carry flux. Radiance over the square of the index, L / eta^2, is what stays unchanged along
// a ray through interfaces (Veach 1997, section 5.2: the solid angle of a pencil of rays shrinks
// by (eta_i / eta_t)^2 as it enters a denser medium), so radiance arriving from the transmitted
// side is scaled by (eta_i / eta_t)^2 on the incident side; flux crossing an interface is not
// scaled. Paths that go in and out of one medium cancel the factor: it shows where a path ends
// on the other side (a floor seen through water, an emitter inside glass, a camera inside a
// medium).
PF_CONST(uint32_t) kCarriesRadiance = 0;
PF_CONST(uint32_t) kCarriesFlux = 1;

// The factor a refraction with eta = n_incident / n_transmitted applies to what the path
// carries, the incident side being the side the path arrives from.
PF_GPU_FN float RefractionScale(uint32_t carries, float eta) {
    return carries == kCarriesRadiance ? eta * eta : 1.0f;
}

// One coordinate of a ray origin moved off a surface along its geometric normal, toward the
// side the normal faces, by a few units in the last place rather than by a fixed epsilon
// (Wachter & Binder 2019, "A Fast and Robust Method for Avoiding Self-Intersection", Ray
// Tracing Gems ch. 6). Coordinates near zero, where a few units in the last place are nothing
// against the hit's rounding error, move by a small fixed fraction of the scene instead:
// `scene_scale` is the scene's largest coordinate magnitude (Bounds::Magnitude), so a scene
// scaled by 1e-4 or 1e+4 is offset exactly as the same scene at unit scale.
PF_GPU_FN float OffsetCoordinate(float coordinate, float normal, float scene_scale) {
    const int32_t offset = int32_t(256.0f * normal);
    const float moved =
        intBitsToFloat(floatBitsToInt(coordinate) + (coordinate < 0.0f ? -offset : offset));
    return abs(coordinate) < scene_scale * (1.0f / 32.0f)
               ? coordinate + scene_scale * (1.0f / 65536.0f) * normal
               : moved;
}

PF_GPU_END

#endif  // PF_CORE_SHARED_PATH_SAMPLING_H
