// What glossy surfaces reflect of a punctual light (point, spot and distant lights, goniometric
// and projection ones: deltas that no sampled direction finds) toward a camera path:
// f(wo, wi) |cos wi| of the parts of a surface's BSDF that are not themselves deltas, taken
// where light sampling picked a punctual light (next-event estimation at a glossy vertex).
// Area lights and the environment are found by the surfaces' own sampling, so these add only
// what that sampling can never reach: nothing is counted twice.
// Each function is what the sampling of core/shared/coat.h, microfacet.h and scatter.h draws,
// evaluated: integrated over wi it gives the sampled albedo
// (tests/core/scene/glossy_lights_test.cpp). Local frame of the shading normal on the viewer's side
// (+z), wo toward the viewer. One definition for the CPU and the Vulkan kernels.
#ifndef PF_CORE_SHARED_GLOSSY_LIGHTS_H
#define PF_CORE_SHARED_GLOSSY_LIGHTS_H

#include "core/shared/coat.h"
#include "core/shared/conductor.h"
#include "core/shared/gpu_prelude.h"
#include "core/shared/microfacet.h"
#include "core/shared/path_sampling.h"
#include "core/shared/rng.h"
#include "core/shared/sheen.h"

PF_GPU_BEGIN

// GGX reflection f |cos wi| without its Fresnel term, and the cosine of wo to the half vector:
// D(h) G2 / (4 cos_o); 0 unless both directions lie above the surface.
PF_GPU_FN float GgxReflection(vec3 wo, vec3 wi, float alpha, PF_OUT(float) cos_oh) {
    cos_oh = 0.0f;
    if (!(wo.z > 0.0f && wi.z > 0.0f)) return 0.0f;
    const vec3 h = normalize(vec3(wo.x + wi.x, wo.y + wi.y, wo.z + wi.z));
    cos_oh = dot(wo, h);
    return GgxReflectionCosine(wo.z, wi.z, h.z, alpha);
}

// A coat's own reflection, f |cos wi| (core/shared/coat.h's EnterCoat, evaluated): the sheen's
// lobe, and the layer's glossy reflection -- a rough layered coat's Fresnel reflection, a rough
// Fresnel mix's specular lobe -- times what the sheen lets pass both ways. A smooth interface
// reflects a delta: nothing here. Coloured by the sheen.
PF_GPU_FN vec3 CoatReflection(Coat coat, vec3 wo, vec3 wi) {
    if (!(wo.z > 0.0f && wi.z > 0.0f)) return vec3(0.0f, 0.0f, 0.0f);
    const float sheen_o = SheenProbability(coat, wo.z);
    vec3 reflected = vec3(0.0f, 0.0f, 0.0f);
    if (sheen_o > 0.0f)
        reflected = coat.sheen * (SheenBrdf(wo, wi, SheenAlpha(coat.sheen_roughness)) * wi.z);
    if (coat.kind == kCoatNone || !(coat.alpha > 0.0f)) return reflected;
    float cos_oh;
    const float lobe = GgxReflection(wo, wi, coat.alpha, cos_oh);
    const float fresnel = coat.kind == kCoatFresnelMix ? MixFresnel(coat, cos_oh)
                                                       : FresnelDielectric(cos_oh, 1.0f / coat.ior);
    // EnterCoat reaches the layer with probability 1 - P(wo), and the reflection keeps
    // SheenOverReflection of it.
    const float layer = fresnel * lobe * (1.0f - sheen_o) * SheenOverReflection(coat, wo.z, wi.z);
    return vec3(reflected.x + layer, reflected.y + layer, reflected.z + layer);
}

// Rough glass of GGX alpha `alpha`, eta = n on wo's side / n on the other (as ScatterRough's):
// f |cos wi| for a camera path (radiance) with the light along wi on either side -- reflection
// F D G2 / (4 cos_o cos_i), transmission Walter et al. 2007's eq. 21, the BTDF of radiance
// (its n_o^2, eta^2 here, is what ScatterRough's RefractionScale carries) -- and the
// transmitted part tinted by `tint`.
PF_GPU_FN vec3 RoughDielectricResponse(float eta, float alpha, vec3 tint, vec3 wo, vec3 wi) {
    if (!(wo.z > 0.0f) || wi.z == 0.0f) return vec3(0.0f, 0.0f, 0.0f);
    if (wi.z > 0.0f) {
        float cos_oh;
        const float lobe = GgxReflection(wo, wi, alpha, cos_oh);
        const float reflected = FresnelDielectric(cos_oh, eta) * lobe;
        return vec3(reflected, reflected, reflected);
    }
    // The half vector of a refraction: wo eta + wi, up (Walter et al. 2007, eq. 16).
    vec3 h = normalize(vec3(wo.x * eta + wi.x, wo.y * eta + wi.y, wo.z * eta + wi.z));
    if (h.z < 0.0f) h = vec3(-h.x, -h.y, -h.z);
    const float cos_oh = dot(wo, h), cos_ih = dot(wi, h);
    if (!(cos_oh > 0.0f && cos_ih < 0.0f)) return vec3(0.0f, 0.0f, 0.0f);  // a back facet
    const float denominator = eta * cos_oh + cos_ih;
    if (!(abs(denominator) > 1e-7f)) return vec3(0.0f, 0.0f, 0.0f);
    const float masking = 1.0f / (1.0f + GgxLambda(wo.z, alpha) + GgxLambda(-wi.z, alpha));  // G2
    const float transmitted = (1.0f - FresnelDielectric(cos_oh, eta)) *
                              GgxDistribution(h.z, alpha) * masking * cos_oh * (-cos_ih) /
                              (denominator * denominator * wo.z) * (eta * eta);
    return tint * transmitted;
}

// One estimate of f |cos wi| of a layered coat over a conductor (core/shared/coat.h's
// ScatterCoatedConductor, evaluated), averaged over `samples` walks (pbrt-v4's "nsamples"):
// the coat's own reflection (CoatReflection), and the light that crosses the coat, meets the
// conductor and comes out again, by a walk from wo through the layer that follows reflections
// alone (pbrt-v4's LayeredBxDF::f, written for this pair) and at each vertex joins the light:
//  - over a rough base, the light's own way in, drawn from wi as light crosses the coat
//    (flux: its transmittance and masking), reflected by the base toward the walk;
//  - over a mirror under a rough coat, the coat's transmission from wi to the walk going up.
// A mirror under a smooth coat reflects a delta: only the coat's reflection is left. Radiance
// under the coat is ior^2 times larger (CoatInside): the walk in carries 1 / ior^2 as camera
// paths do, which the transmission's eta^2 cancels where the light comes through the coat.
// Draws its numbers from rng.
PF_GPU_FN vec3 CoatedConductorResponse(Coat coat, Conductor conductor, vec3 tint, float base_alpha,
                                       vec3 wo, vec3 wi, uint32_t samples, PF_INOUT(Pcg32) rng) {
    vec3 response = CoatReflection(coat, wo, wi);
    const bool rough_base = base_alpha > 0.0f, rough_coat = coat.alpha > 0.0f;
    if (!(wo.z > 0.0f && wi.z > 0.0f) || (!rough_base && !rough_coat) || samples == 0u)
        return response;
    const float inv_ior = 1.0f / coat.ior;
    // Past the sheen both ways, as EnterCoat and LeaveCoat weigh the light that crosses.
    const float sheen = (1.0f - SheenProbability(coat, wo.z)) *
                        (1.0f - SheenProbability(coat, wi.z)) * SheenInside(coat);
    vec3 through = vec3(0.0f, 0.0f, 0.0f);
    for (uint32_t walk = 0u; walk < samples; ++walk) {
        // The walk in from wo, transmitted: its share 1 - F and its masking.
        float u1 = Pcg32NextFloat(rng), u2 = Pcg32NextFloat(rng);
        vec3 m = CoatMicrofacet(coat, wo, u1, u2);
        vec3 down;
        if (!Refract(vec3(-wo.x, -wo.y, -wo.z), m, inv_ior, down) || !(down.z < 0.0f)) continue;
        vec3 beta = vec3(1.0f, 1.0f, 1.0f) *
                    ((1.0f - FresnelDielectric(dot(wo, m), inv_ior)) *
                     (rough_coat ? GgxMaskingRatio(wo.z, -down.z, coat.alpha) : 1.0f) *
                     CoatLayerTransmittance(coat.thickness, down.z) * inv_ior * inv_ior);
        // The light's way in from wi (a rough base joins it): direction and flux share.
        vec3 light_down = vec3(0.0f, 0.0f, -1.0f);
        float light_share = 0.0f;
        if (rough_base) {
            u1 = Pcg32NextFloat(rng);
            u2 = Pcg32NextFloat(rng);
            m = CoatMicrofacet(coat, wi, u1, u2);
            if (Refract(vec3(-wi.x, -wi.y, -wi.z), m, inv_ior, light_down) && light_down.z < 0.0f)
                light_share =
                    (1.0f - FresnelDielectric(dot(wi, m), inv_ior)) *
                    (rough_coat ? GgxMaskingRatio(wi.z, -light_down.z, coat.alpha) : 1.0f) *
                    CoatLayerTransmittance(coat.thickness, light_down.z);
        }
        for (uint32_t bounce = 0u; bounce < coat.depth; ++bounce) {
            // At the base, arrived along `down`; toward the walk is -down.
            const vec3 back = vec3(-down.x, -down.y, -down.z);
            if (light_share > 0.0f) {
                const vec3 toward_light = vec3(-light_down.x, -light_down.y, -light_down.z);
                float cos_bh;
                const float lobe = GgxReflection(back, toward_light, base_alpha, cos_bh);
                if (lobe > 0.0f)
                    through = through + beta * ConductorFresnel(conductor, cos_bh, tint, coat.ior) *
                                            (lobe / toward_light.z * light_share * wi.z);
            }
            // Reflected by the base, as ScatterCoatedConductor reflects it.
            vec3 up = vec3(down.x, down.y, -down.z);
            float cos_base = back.z;
            if (rough_base) {
                u1 = Pcg32NextFloat(rng);
                u2 = Pcg32NextFloat(rng);
                m = SampleGgxVisibleNormal(back, base_alpha, u1, u2);
                cos_base = dot(back, m);
                up = m * (2.0f * cos_base) - back;
                if (!(up.z > 0.0f)) break;
                beta = beta * GgxMaskingRatio(back.z, up.z, base_alpha);
            }
            beta = beta * ConductorFresnel(conductor, cos_base, tint, coat.ior) *
                   CoatLayerTransmittance(coat.thickness, up.z);
            // At the coat from below, arrived along `up`: over a mirror, the light's
            // transmission from wi to -up (RoughDielectricResponse from inside, whose eta^2 is
            // the walk's 1 / ior^2 undone).
            // Mirrored through the coat's plane, the walk's side is +z, as CrossCoatFromBelow
            // mirrors it.
            if (!rough_base)
                through = through + beta * RoughDielectricResponse(
                                               coat.ior, coat.alpha, vec3(1.0f, 1.0f, 1.0f),
                                               vec3(-up.x, -up.y, up.z), vec3(wi.x, wi.y, -wi.z));
            // Russian roulette once the walk is long and carries little, as the sampling's.
            const float largest = max(beta.x, max(beta.y, beta.z));
            if (bounce > 2u && largest < 0.25f) {
                const float survive = max(largest, 0.05f);
                if (!(Pcg32NextFloat(rng) < survive)) break;
                beta = beta * (1.0f / survive);
            }
            // Reflected back down by the coat: its Fresnel share from inside, and its masking.
            u1 = Pcg32NextFloat(rng);
            u2 = Pcg32NextFloat(rng);
            const vec3 mirrored = vec3(-up.x, -up.y, up.z);  // toward the base, mirrored
            m = CoatMicrofacet(coat, mirrored, u1, u2);
            const float cos_um = dot(mirrored, m);
            const vec3 reflected = m * (2.0f * cos_um) - mirrored;
            if (!(reflected.z > 0.0f)) break;
            beta =
                beta * (FresnelDielectric(cos_um, coat.ior) *
                        (rough_coat ? GgxMaskingRatio(mirrored.z, reflected.z, coat.alpha) : 1.0f));
            down = vec3(reflected.x, reflected.y, -reflected.z);
            beta = beta * CoatLayerTransmittance(coat.thickness, down.z);
        }
    }
    return response + through * (sheen / float(samples));
}

PF_GPU_END

#endif  // PF_CORE_SHARED_GLOSSY_LIGHTS_H
