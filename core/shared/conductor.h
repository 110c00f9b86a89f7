// How a metal's reflectance varies with the angle of incidence, one definition for the CPU
// (core/shared/scatter.h, coat.h's coated conductor) and the Vulkan kernels
// (through scatter.h): every mirror and rough conductor reflects tint-times-this at the cosine
// between the incident direction and the (micro)facet it is reflected by.
#ifndef PF_CORE_SHARED_CONDUCTOR_H
#define PF_CORE_SHARED_CONDUCTOR_H

#include "core/shared/gpu_prelude.h"

PF_GPU_BEGIN

// Conductor Fresnel kinds (Material::conductor).
PF_CONST(uint32_t)
kConductorTint = 0;  // the tint at every angle (photonfarm's and pbrt-v3's
                     // mirrors)
PF_CONST(uint32_t)
kConductorSchlick = 1;  // Schlick's F0 + (1 - F0)(1 - cos)^5 with F0 the tint
                        // (glTF's metal)
PF_CONST(uint32_t)
kConductorComplex = 2;  // the Fresnel reflectance of the complex index
                        // eta + i k per channel, times the tint (pbrt-v4)
PF_CONST(uint32_t)
kConductorReflectance = 3;  // as complex, of the index 1 + i 2 sqrt(r / (1 - r))
                            // for the tint r: reflectance r at normal incidence
                            // (pbrt-v4's "reflectance", per texel)

// A conductor's Fresnel term, as the functions below take it (ConductorOf builds one).
struct Conductor {
    uint32_t kind;  // kConductor*
    vec3 eta;       // kConductorComplex: the index's real part per channel, in vacuum
    vec3 k;         // ... and its imaginary part
};

// Unpolarised Fresnel reflectance of a conductor of complex index eta + i k relative to the
// medium the light arrives in, at the incident cosine cos_i: the exact expression (Born and
// Wolf), written without complex numbers as in Lagarde's "Memo on Fresnel equations" (2013).
PF_GPU_FN float FresnelComplex(float cos_i, float eta, float k) {
    cos_i = clamp(cos_i, 0.0f, 1.0f);
    const float cos2 = cos_i * cos_i, sin2 = 1.0f - cos2;
    const float eta2 = eta * eta, k2 = k * k;
    const float t0 = (eta2 - k2 - 1.0f) + cos2;  // eta^2 - k^2 - sin^2, exact where eta = 1, k = 0
    const float a2_plus_b2 = sqrt(t0 * t0 + 4.0f * eta2 * k2);
    const float a = sqrt(max(0.0f, 0.5f * (a2_plus_b2 + t0)));
    const float t1 = a2_plus_b2 + cos2, t2 = 2.0f * cos_i * a;
    const float rs = (t1 - t2) / max(t1 + t2, 1e-30f);
    const float t3 = cos2 * a2_plus_b2 + sin2 * sin2, t4 = t2 * sin2;
    const float rp = rs * (t3 - t4) / max(t3 + t4, 1e-30f);
    return clamp(0.5f * (rp + rs), 0.0f, 1.0f);
}

// What the conductor reflects of light arriving at cosine cos_i to the facet, the tint
// included, with the light arriving in a medium of index outside_ior (1 in air; a coat's
// index under a coat, which the complex index is divided by, as pbrt-v4 divides it).
PF_GPU_FN vec3 ConductorFresnel(Conductor conductor, float cos_i, vec3 tint, float outside_ior) {
    if (conductor.kind == kConductorTint) return tint;
    if (conductor.kind == kConductorSchlick) {
        const float m = 1.0f - clamp(cos_i, 0.0f, 1.0f);
        const float m2 = m * m;
        const float w = m2 * m2 * m;
        return tint + (vec3(1.0f, 1.0f, 1.0f) - tint) * w;
    }
    vec3 eta = conductor.eta, k = conductor.k, scale = tint;
    if (conductor.kind == kConductorReflectance) {
        eta = vec3(1.0f, 1.0f, 1.0f);
        const vec3 r = vec3(min(tint.x, 0.9999f), min(tint.y, 0.9999f), min(tint.z, 0.9999f));
        k = vec3(2.0f * sqrt(max(r.x, 0.0f) / (1.0f - r.x)),
                 2.0f * sqrt(max(r.y, 0.0f) / (1.0f - r.y)),
                 2.0f * sqrt(max(r.z, 0.0f) / (1.0f - r.z)));
        scale = vec3(1.0f, 1.0f, 1.0f);
    }
    const float relative = 1.0f / outside_ior;
    return vec3(FresnelComplex(cos_i, eta.x * relative, k.x * relative) * scale.x,
                FresnelComplex(cos_i, eta.y * relative, k.y * relative) * scale.y,
                FresnelComplex(cos_i, eta.z * relative, k.z * relative) * scale.z);
}

PF_GPU_END

#endif  // PF_CORE_SHARED_CONDUCTOR_H
