// The GGX (Trowbridge-Reitz) microfacet distribution of the rough materials, isotropic, with
// Smith's height-correlated masking and shadowing, sampled through its visible normals
// (Heitz 2018, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4)). Directions
// are in the local frame of the shading normal, +z, on the side the light arrives from.
// Written in the vocabulary of gpu_prelude.h, for the CPU and the Vulkan kernels alike.
#ifndef PF_CORE_SHARED_MICROFACET_H
#define PF_CORE_SHARED_MICROFACET_H

#include "core/shared/gpu_prelude.h"
#include "core/shared/path_sampling.h"

PF_GPU_BEGIN

// The normal distribution D(m) for a microfacet normal with m.z = cos_m; alpha > 0.
PF_GPU_FN float GgxDistribution(float cos_m, float alpha) {
    const float a2 = alpha * alpha;
    const float t = cos_m * cos_m * (a2 - 1.0f) + 1.0f;
    return a2 / (3.14159265358979323846f * t * t);
}

// Smith's Lambda(v) for a direction with v.z = cos_v (Heitz 2014, eq. 72).
PF_GPU_FN float GgxLambda(float cos_v, float alpha) {
    const float c2 = max(cos_v * cos_v, 1e-12f);
    const float tan2 = max(0.0f, 1.0f - c2) / c2;
    return 0.5f * (sqrt(1.0f + alpha * alpha * tan2) - 1.0f);
}

// G2(wo, wi) / G1(wo): what a direction sampled from the visible normals of wo carries, in
// f cos / pdf, besides the Fresnel term. |cos| of both directions to the normal.
PF_GPU_FN float GgxMaskingRatio(float cos_o, float cos_i, float alpha) {
    const float lambda_o = GgxLambda(cos_o, alpha);
    return (1.0f + lambda_o) / (1.0f + lambda_o + GgxLambda(cos_i, alpha));
}

// The density in solid angle of a reflection wi sampled from wo's visible normals, with
// half vector h: G1(wo) D(h) / (4 cos_o).
PF_GPU_FN float GgxReflectionPdf(float cos_o, float cos_h, float alpha) {
    return GgxDistribution(cos_h, alpha) / ((1.0f + GgxLambda(cos_o, alpha)) * 4.0f * cos_o);
}

// f cos(wi) of a reflection, without its Fresnel term, for light sampling at rough metal:
// D(h) G2(wo, wi) / (4 cos_o), both cosines positive, h their half vector.
PF_GPU_FN float GgxReflectionCosine(float cos_o, float cos_i, float cos_h, float alpha) {
    return GgxDistribution(cos_h, alpha) /
           ((1.0f + GgxLambda(cos_o, alpha) + GgxLambda(cos_i, alpha)) * 4.0f * cos_o);
}

// A microfacet normal drawn with density G1(wo) max(0, wo.m) D(m) / wo.z, for wo.z > 0.
PF_GPU_FN vec3 SampleGgxVisibleNormal(vec3 wo, float alpha, float u1, float u2) {
    // The view stretched to the unit-roughness configuration, and a frame around it.
    const vec3 v = normalize(vec3(alpha * wo.x, alpha * wo.y, wo.z));
    const float length_sq = v.x * v.x + v.y * v.y;
    const float inverse = length_sq > 0.0f ? 1.0f / sqrt(length_sq) : 0.0f;
    const vec3 t1 =
        length_sq > 0.0f ? vec3(-v.y * inverse, v.x * inverse, 0.0f) : vec3(1.0f, 0.0f, 0.0f);
    const vec3 t2 = vec3(-v.z * t1.y, v.z * t1.x, v.x * t1.y - v.y * t1.x);  // cross(v, t1)
    // A point of the projected hemisphere: a disk whose far half is squashed by v.z.
    const float r = sqrt(u1);
    float sine, cosine;
    SinCosTurns(u2, sine, cosine);
    const float p1 = r * cosine;
    const float s = 0.5f * (1.0f + v.z);
    const float p2 = (1.0f - s) * sqrt(max(0.0f, 1.0f - p1 * p1)) + s * r * sine;
    const float pz = sqrt(max(0.0f, 1.0f - p1 * p1 - p2 * p2));
    const vec3 h = vec3(p1 * t1.x + p2 * t2.x + pz * v.x, p1 * t1.y + p2 * t2.y + pz * v.y,
                        p1 * t1.z + p2 * t2.z + pz * v.z);
    // Back to the roughness of the surface.
    return normalize(vec3(alpha * h.x, alpha * h.y, max(1e-6f, h.z)));
}

PF_GPU_END

#endif  // PF_CORE_SHARED_MICROFACET_H
