// Coated surfaces: a dielectric interface over a diffuse or conductor base, in one of two kinds.
//  - Layered (pbrt-v4's coateddiffuse and coatedconductor): a layer of index `ior` (smooth, or
//    rough with GGX alpha `alpha`), its interior absorbing with optical thickness `thickness`
//    (pbrt-v4's LayeredBxDF with albedo 0: a crossing at cosine mu transmits
//    exp(-thickness / mu)). Light is followed through the layer as pbrt-v4's random walk
//    follows it, choosing each interface's branch with its Fresnel probability.
//  - Fresnel mix (glTF's dielectric BRDF, fresnel_mix(diffuse, specular)): a GGX specular lobe
//    weighted at each microfacet m by Schlick's Fresnel term F(w.m) of F0 from `ior`, scaled
//    by `weight` (glTF's specularFactor), over a diffuse base weighted by T(wo) T(wi) / (1 -
//    F_avg), T(w) = 1 - E_m[F(w.m)] what the layer does not reflect: glTF's (1 - F(v.h)) made
//    separable, so that photons and camera paths each carry their half, and normalised by the
//    cosine-weighted mean F_avg, so that a white base reflects all the light but what GGX's
//    masking loses (Kelemen and Szirmay-Kalos 2001 couple the two likewise). Nothing refracts
//    and nothing is turned back to the base.
//  - None (the layer below a sheen alone; index 1): light passes straight through to the base.
// Any of them may wear a sheen (core/shared/sheen.h, glTF's KHR_materials_sheen) over it: light
// arriving along w is reflected by the sheen with probability P(w), else meets the layer below;
// what leaves the base is weighed by (1 - P) / (1 - P_avg) on its way out, as the Fresnel mix's
// base is.
// Every pass (camera, photon, direct light, path tracer) sees the same surface through the
// functions below. Directions are in the local frame of the shading normal, +z on the side the
// light arrives from outside. One definition for the CPU and the Vulkan kernels.
#ifndef PF_CORE_SHARED_COAT_H
#define PF_CORE_SHARED_COAT_H

#include "core/shared/conductor.h"
#include "core/shared/features.h"
#include "core/shared/gpu_prelude.h"
#include "core/shared/microfacet.h"
#include "core/shared/path_sampling.h"
#include "core/shared/rng.h"
#include "core/shared/sheen.h"

PF_GPU_BEGIN

// Coat kinds (Material::coat_kind).
PF_CONST(uint32_t) kCoatLayered = 0;
PF_CONST(uint32_t) kCoatFresnelMix = 1;
PF_CONST(uint32_t) kCoatNone = 2;

// A coat, as the functions below take it (CoatOf builds one from a material on either side).
struct Coat {
    uint32_t kind;    // kCoat*
    float ior;        // the interface's index of refraction (Fresnel mix: its F0's)
    float alpha;      // its GGX alpha; 0: smooth
    float thickness;  // layered: the interior's optical thickness
    float weight;     // Fresnel mix: the specular lobe's scale, Fresnel's value at grazing
    uint32_t depth;   // layered conductor: the most bounces under the coat
    vec3 sheen;       // the sheen's colour over it (black: none)
    float sheen_roughness;
};

// The probability P(w) that the sheen reflects light arriving at cosine cos_z (0 without one).
PF_GPU_FN float SheenProbability(Coat coat, float cos_z) {
    const float largest = max(coat.sheen.x, max(coat.sheen.y, coat.sheen.z));
    if (!kHasSheen || !(largest > 0.0f)) return 0.0f;
    return min(1.0f, largest * SheenAlbedo(abs(cos_z), coat.sheen_roughness));
}

// The base's normalisation under the sheen, 1 / (1 - P_avg).
PF_GPU_FN float SheenInside(Coat coat) {
    const float largest = max(coat.sheen.x, max(coat.sheen.y, coat.sheen.z));
    if (!kHasSheen || !(largest > 0.0f)) return 1.0f;
    return 1.0f / (1.0f - min(largest * SheenAverageAlbedo(coat.sheen_roughness), 0.99f));
}

// Light arriving from outside along -wo, reflected by the sheen, chosen with probability p:
// wi cosine-distributed by (u1, u2), the weight colour pi f_sheen / p.
PF_GPU_FN vec3 ReflectOffSheen(Coat coat, vec3 wo, float p, float u1, float u2, PF_OUT(vec3) wi) {
    wi = SampleCosineHemisphere(u1, u2);
    return coat.sheen *
           (3.14159265358979323846f * SheenBrdf(wo, wi, SheenAlpha(coat.sheen_roughness)) / p);
}

// The visits to a coat's base (Coat::depth) of coats that name no limit: as many as matter
// (a lossless smooth coat over white keeps 0.6^64 of its light past them).
PF_CONST(int32_t) kMaxCoatReturns = 64;

// The layer's transmittance along a crossing with direction cosine cos_z.
PF_GPU_FN float CoatLayerTransmittance(float thickness, float cos_z) {
    return thickness > 0.0f ? exp(-thickness / max(abs(cos_z), 1e-6f)) : 1.0f;
}

// Light leaving along wo (wo.z > 0, the incident side +z) meets a dielectric interface with
// eta = n_incident / n_transmitted: sets wi to where it goes, reflected (wi.z > 0) or
// transmitted (wi.z < 0), the branch chosen with its Fresnel probability by u_branch and the
// microfacet by (u1, u2) on a rough interface (alpha > 0). Returns the weight carried: 1 on a
// smooth interface, the masking ratio G2 / G1 on a rough one, 0 where the sample is lost.
PF_GPU_FN float CrossCoatInterface(vec3 wo, float eta, float alpha, float u_branch, float u1,
                                   float u2, PF_OUT(vec3) wi) {
    if (alpha <= 0.0f) {
        const vec3 normal = vec3(0.0f, 0.0f, 1.0f);
        wi = vec3(-wo.x, -wo.y, wo.z);
        if (u_branch < FresnelDielectric(wo.z, eta)) return 1.0f;
        vec3 refracted;
        if (Refract(-wo, normal, eta, refracted)) wi = refracted;
        return 1.0f;
    }
    const vec3 m = SampleGgxVisibleNormal(wo, alpha, u1, u2);
    const float cos_om = dot(wo, m);
    wi = m * (2.0f * cos_om) - wo;
    vec3 refracted;
    if (u_branch >= FresnelDielectric(cos_om, eta) && Refract(-wo, m, eta, refracted)) {
        wi = refracted;
        return wi.z < 0.0f ? GgxMaskingRatio(wo.z, -wi.z, alpha) : 0.0f;
    }
    return wi.z > 0.0f ? GgxMaskingRatio(wo.z, wi.z, alpha) : 0.0f;
}

// The same with the incident side -z (light inside the layer going up meets the coat from
// below; wo.z < 0): mirrored through the interface's plane and back.
PF_GPU_FN float CrossCoatFromBelow(vec3 wo, float eta, float alpha, float u_branch, float u1,
                                   float u2, PF_OUT(vec3) wi) {
    vec3 mirrored;
    const float weight =
        CrossCoatInterface(vec3(wo.x, wo.y, -wo.z), eta, alpha, u_branch, u1, u2, mirrored);
    wi = vec3(mirrored.x, mirrored.y, -mirrored.z);
    return weight;
}

// The Fresnel mix's weight at cosine cos_theta: weight x Schlick's F of F0 from the index.
PF_GPU_FN float MixFresnel(Coat coat, float cos_theta) {
    const float r = (coat.ior - 1.0f) / (coat.ior + 1.0f);
    const float f0 = r * r;
    const float m = 1.0f - clamp(cos_theta, 0.0f, 1.0f);
    const float m2 = m * m;
    return coat.weight * (f0 + (1.0f - f0) * (m2 * m2 * m));
}

// The cosine-weighted mean over directions w of what the layer reflects, E_m[F(w.m)] over w's
// visible microfacets: weight (F0 + (1 - F0) b(alpha)), where b is the mean of (1 - w.m)^5 --
// 1/21 on a smooth layer (the integral of (1 - mu)^5 2 mu over [0, 1]), a cubic fit within
// 1e-3 of it on rough ones (tests/core/scene/fresnel_mix_test.cpp integrates it).
PF_GPU_FN float MixFresnelAverage(Coat coat) {
    const float r = (coat.ior - 1.0f) / (coat.ior + 1.0f);
    const float f0 = r * r;
    const float a = coat.alpha;
    const float b = 1.0f / 21.0f + a * (-0.080443f + a * (0.122424f - 0.054434f * a));
    return coat.weight * (f0 + (1.0f - f0) * b);
}

// What the radiance at the base is worth, times what reaches it: 1 / ior^2 under a layered
// coat (radiance inside is ior^2 times larger), the Fresnel mix's normalisation 1 / (1 -
// F_avg) under a Fresnel mix. Camera paths entering a coat carry this factor; a path leaving
// it divides it out again (the Fresnel mix's LeaveCoat applies its normalisation itself).
PF_GPU_FN float CoatInside(Coat coat) {
    if (coat.kind == kCoatFresnelMix) return SheenInside(coat) / (1.0f - MixFresnelAverage(coat));
    if (coat.kind == kCoatNone) return SheenInside(coat);
    return SheenInside(coat) / (coat.ior * coat.ior);
}

// A microfacet of the coat's interface seen from w: one of w's visible normals, drawn by
// (u1, u2), on a rough interface; the normal on a smooth one.
PF_GPU_FN vec3 CoatMicrofacet(Coat coat, vec3 w, float u1, float u2) {
    if (coat.alpha > 0.0f) return SampleGgxVisibleNormal(w, coat.alpha, u1, u2);
    return vec3(0.0f, 0.0f, 1.0f);
}

// The Fresnel mix's specular lobe reflecting wo off microfacet m: sets wi and returns the
// masking ratio (1 on a smooth layer), 0 where wi leaves the hemisphere.
PF_GPU_FN float ReflectOffMix(Coat coat, vec3 wo, vec3 m, PF_OUT(vec3) wi) {
    wi = m * (2.0f * dot(wo, m)) - wo;
    if (!(wi.z > 0.0f)) return 0.0f;
    return coat.alpha > 0.0f ? GgxMaskingRatio(wo.z, wi.z, coat.alpha) : 1.0f;
}

// EnterCoat below the sheen.
PF_GPU_FN float EnterLayer(Coat coat, vec3 wo, float u_branch, float u1, float u2,
                           PF_OUT(vec3) wi) {
    if (coat.kind == kCoatNone) {
        wi = vec3(wo.x, wo.y, -wo.z);
        return 1.0f;
    }
    if (coat.kind == kCoatFresnelMix) {
        // Reflected by a visible microfacet with its Fresnel probability, else to the base.
        const vec3 m = CoatMicrofacet(coat, wo, u1, u2);
        if (u_branch < MixFresnel(coat, dot(wo, m))) return ReflectOffMix(coat, wo, m, wi);
        wi = vec3(wo.x, wo.y, -wo.z);
        return 1.0f;
    }
    const float weight = CrossCoatInterface(wo, 1.0f / coat.ior, coat.alpha, u_branch, u1, u2, wi);
    return wi.z < 0.0f ? weight * CoatLayerTransmittance(coat.thickness, wi.z) : weight;
}

// What the coat's own reflection from wo to wi keeps under a sheen, past the 1 - P(wo) chosen
// on the way in: sqrt((1 - P(wi)) / (1 - P(wo))), so that the reflection is scaled by the
// geometric mean of 1 - P at both ends, reciprocal (glTF scales it by the smaller; on a smooth
// coat the two agree).
PF_GPU_FN float SheenOverReflection(Coat coat, float cos_o, float cos_i) {
    const float p_o = SheenProbability(coat, cos_o);
    if (!(p_o > 0.0f && p_o < 1.0f)) return 1.0f;  // no sheen; or one that reflects everything
    return sqrt((1.0f - SheenProbability(coat, cos_i)) / (1.0f - p_o));
}

// Light arriving from outside along -wo: reflected by the sheen or the coat (wi.z > 0; a
// sheen's weight is coloured), or into it and down to the base (wi.z < 0; grey, including a
// layered coat's transmittance). u_branch chooses the branch, (u1, u2) the microfacet of a rough
// interface or the sheen's direction.
PF_GPU_FN vec3 EnterCoat(Coat coat, vec3 wo, float u_branch, float u1, float u2, PF_OUT(vec3) wi) {
    const float p = SheenProbability(coat, wo.z);
    if (u_branch < p) return ReflectOffSheen(coat, wo, p, u1, u2, wi);
    float weight = EnterLayer(coat, wo, (u_branch - p) / (1.0f - p), u1, u2, wi);
    if (wi.z > 0.0f) weight *= SheenOverReflection(coat, wo.z, wi.z);
    return vec3(weight, weight, weight);
}

// Light leaving the base upward along `up` (up.z > 0) meets the coat from inside: escapes (wi.z
// > 0, outside), or a layered coat reflects it back down to the base (wi.z < 0; the weight
// includes both crossings' transmittance). A Fresnel mix lets it out along `up`, weighted by
// (1 - F(up.m)) / (1 - F_avg), m one of up's visible microfacets. A sheen weighs what escapes
// by (1 - P(wi)) / (1 - P_avg).
PF_GPU_FN float LeaveLayer(Coat coat, vec3 up, float u_branch, float u1, float u2,
                           PF_OUT(vec3) wi) {
    if (coat.kind == kCoatNone) {
        wi = up;
        return 1.0f;
    }
    if (coat.kind == kCoatFresnelMix) {
        wi = up;
        return (1.0f - MixFresnel(coat, dot(up, CoatMicrofacet(coat, up, u1, u2)))) /
               (1.0f - MixFresnelAverage(coat));
    }
    const float weight = CoatLayerTransmittance(coat.thickness, up.z) *
                         CrossCoatFromBelow(-up, coat.ior, coat.alpha, u_branch, u1, u2, wi);
    return wi.z < 0.0f ? weight * CoatLayerTransmittance(coat.thickness, wi.z) : weight;
}

// ... and what escapes passes the sheen, weighed by (1 - P(wi)) / (1 - P_avg).
PF_GPU_FN float LeaveCoat(Coat coat, vec3 up, float u_branch, float u1, float u2, PF_OUT(vec3) wi) {
    const float weight = LeaveLayer(coat, up, u_branch, u1, u2, wi);
    if (!(wi.z > 0.0f)) return weight;
    return weight * (1.0f - SheenProbability(coat, wi.z)) * SheenInside(coat);
}

// The fraction of light arriving from outside along -w (w.z > 0) that passes the layer below
// the sheen: exact for a smooth coat; for a rough one an unbiased estimate from the microfacet
// (u1, u2), as EnterLayer would draw it, the Fresnel branch taken by its expectation.
PF_GPU_FN float LayerTransmittance(Coat coat, vec3 w, float u1, float u2) {
    if (coat.kind == kCoatNone) return 1.0f;
    if (coat.kind == kCoatFresnelMix)
        return 1.0f - MixFresnel(coat, dot(w, CoatMicrofacet(coat, w, u1, u2)));
    const float eta = 1.0f / coat.ior;
    vec3 m = vec3(0.0f, 0.0f, 1.0f);
    if (coat.alpha > 0.0f) m = SampleGgxVisibleNormal(w, coat.alpha, u1, u2);
    vec3 refracted;
    if (!Refract(-w, m, eta, refracted) || !(refracted.z < 0.0f)) return 0.0f;
    const float transmitted = 1.0f - FresnelDielectric(dot(w, m), eta);
    const float masking = coat.alpha > 0.0f ? GgxMaskingRatio(w.z, -refracted.z, coat.alpha) : 1.0f;
    return transmitted * masking * CoatLayerTransmittance(coat.thickness, refracted.z);
}

// ... and the fraction that reaches the base, what the sheen lets through too.
PF_GPU_FN float CoatTransmittance(Coat coat, vec3 w, float u1, float u2) {
    if (!(w.z > 0.0f)) return 0.0f;
    return (1.0f - SheenProbability(coat, w.z)) * LayerTransmittance(coat, w, u1, u2);
}

// SplitAtCoat below the sheen.
PF_GPU_FN float SplitAtLayer(Coat coat, vec3 wo, float u1, float u2, PF_OUT(vec3) wi,
                             PF_OUT(float) reflected) {
    reflected = 0.0f;
    if (coat.kind == kCoatNone) return 1.0f;
    if (coat.kind == kCoatFresnelMix) {
        const vec3 m = CoatMicrofacet(coat, wo, u1, u2);
        const float fresnel = MixFresnel(coat, dot(wo, m));
        reflected = fresnel * ReflectOffMix(coat, wo, m, wi);
        return 1.0f - fresnel;
    }
    const float eta = 1.0f / coat.ior;
    vec3 m = vec3(0.0f, 0.0f, 1.0f);
    if (coat.alpha > 0.0f) m = SampleGgxVisibleNormal(wo, coat.alpha, u1, u2);
    const float cos_om = dot(wo, m);
    const float fresnel = FresnelDielectric(cos_om, eta);
    wi = m * (2.0f * cos_om) - wo;
    if (wi.z > 0.0f)
        reflected = coat.alpha > 0.0f ? fresnel * GgxMaskingRatio(wo.z, wi.z, coat.alpha) : fresnel;
    vec3 refracted;
    if (!Refract(-wo, m, eta, refracted) || !(refracted.z < 0.0f)) return 0.0f;
    const float masking =
        coat.alpha > 0.0f ? GgxMaskingRatio(wo.z, -refracted.z, coat.alpha) : 1.0f;
    return (1.0f - fresnel) * masking * CoatLayerTransmittance(coat.thickness, refracted.z);
}

// Both of EnterCoat's branches at once, for paths that split rather than choose (the camera
// pass): from one microfacet (u1, u2) on a rough coat, a reflection (wi, weight `reflected`,
// black where it leaves the hemisphere) and, returned, the weight carried to the base, each
// times its probability: their sum is EnterCoat's expectation. Under a sheen, u_branch chooses
// which of the two reflections, the sheen's or the coat's, with the sheen's probability.
PF_GPU_FN float SplitAtCoat(Coat coat, vec3 wo, float u_branch, float u1, float u2, PF_OUT(vec3) wi,
                            PF_OUT(vec3) reflected) {
    float layer_reflected;
    const float entered = SplitAtLayer(coat, wo, u1, u2, wi, layer_reflected);
    const float p = SheenProbability(coat, wo.z);
    if (layer_reflected > 0.0f) layer_reflected *= SheenOverReflection(coat, wo.z, wi.z);
    reflected = vec3(layer_reflected, layer_reflected, layer_reflected);
    if (u_branch < p) reflected = ReflectOffSheen(coat, wo, p, u1, u2, wi);
    return (1.0f - p) * entered;
}

// Light arriving from outside along -wo (wo.z > 0) at a layered coat over a conductor of
// Fresnel term `conductor` and tint `tint` (GGX alpha `base_alpha`, 0 for a mirror; its complex
// index taken relative to the coat's, as pbrt-v4 takes it), followed through the
// layer as pbrt-v4's random walk follows it: reflected by the coat, or in, off the base, and up to
// the coat again, which lets it out or turns it back, at most coat.depth times before it is taken
// as absorbed. Sets wi (wi.z > 0 where the weight is not black) and returns the weight carried.
PF_GPU_FN vec3 ScatterCoatedConductor(Coat coat, Conductor conductor, vec3 wo, vec3 tint,
                                      float base_alpha, PF_INOUT(Pcg32) rng, PF_OUT(vec3) wi) {
    float u_branch = Pcg32NextFloat(rng), u1 = Pcg32NextFloat(rng), u2 = Pcg32NextFloat(rng);
    vec3 weight = EnterCoat(coat, wo, u_branch, u1, u2, wi);
    for (uint32_t bounce = 0; bounce < coat.depth && wi.z < 0.0f; ++bounce) {
        // Off the base: wi heads down to it; its reflection heads up.
        const vec3 at_base = vec3(-wi.x, -wi.y, -wi.z);
        vec3 up = vec3(-at_base.x, -at_base.y, at_base.z);
        float cos_base = at_base.z;  // to the facet the base reflects it by
        if (base_alpha > 0.0f) {
            u1 = Pcg32NextFloat(rng);
            u2 = Pcg32NextFloat(rng);
            const vec3 m = SampleGgxVisibleNormal(at_base, base_alpha, u1, u2);
            cos_base = dot(at_base, m);
            up = m * (2.0f * cos_base) - at_base;
            if (!(up.z > 0.0f)) return vec3(0.0f, 0.0f, 0.0f);
            weight = weight * GgxMaskingRatio(at_base.z, up.z, base_alpha);
        }
        weight = weight * ConductorFresnel(conductor, cos_base, tint, coat.ior);
        // Russian roulette once the walk is long and carries little, as pbrt-v4's.
        const float largest = max(weight.x, max(weight.y, weight.z));
        if (bounce > 2 && largest < 0.25f) {
            const float survive = max(largest, 0.05f);
            if (!(Pcg32NextFloat(rng) < survive)) return vec3(0.0f, 0.0f, 0.0f);
            weight = weight * (1.0f / survive);
        }
        u_branch = Pcg32NextFloat(rng);
        u1 = Pcg32NextFloat(rng);
        u2 = Pcg32NextFloat(rng);
        weight = weight * LeaveCoat(coat, up, u_branch, u1, u2, wi);
    }
    return wi.z > 0.0f ? weight : vec3(0.0f, 0.0f, 0.0f);
}

PF_GPU_END

#endif  // PF_CORE_SHARED_COAT_H
