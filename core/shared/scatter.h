// Scattering at a surface, written once for the CPU passes and the Vulkan kernels: specular
// surfaces (mirrors, solid and thin glass, each branch chosen with its Fresnel probability, so
// the carried weight is the tint alone), rough ones (GGX lobes sampled through their visible
// normals, core/shared/microfacet.h, the weight times the masking ratio G2 / G1), coats
// (core/shared/coat.h), the side a translucent diffuse surface is read from, the media a
// segment crosses, and what a glossy surface shows of a punctual light. Every pass and both
// backends call these, so the numbers they draw are drawn in one order by construction.
//
// A material reaches them as a Bsdf: what scattering reads of it at a point, textures applied.
// BsdfOf builds one from the material's storage on each side (core/scene/material.h for the
// CPU's Material, worker/backends/vulkan/shaders/bsdf.glsl for GpuMaterial). Materials a
// scene lacks are compiled out of the kernels (core/shared/features.h).
#ifndef PF_CORE_SHARED_SCATTER_H
#define PF_CORE_SHARED_SCATTER_H

#include "core/shared/coat.h"
#include "core/shared/conductor.h"
#include "core/shared/features.h"
#include "core/shared/frame.h"
#include "core/shared/glossy_lights.h"
#include "core/shared/gpu_prelude.h"
#include "core/shared/gpu_types.h"
#include "core/shared/microfacet.h"
#include "core/shared/path_sampling.h"
#include "core/shared/rng.h"
#include "core/shared/translucent.h"

PF_GPU_BEGIN

// Roughness below this is taken as this: a GGX lobe narrower is a mirror to float precision
// (the loaders make a smooth surface a specular material instead).
PF_CONST(float) kMinRoughness = 1e-3f;

// A material at a point, as scattering reads it.
struct Bsdf {
    uint32_t type;          // kMaterial*, never kMaterialMix (resolved where the point is shaded)
    float ior;              // a dielectric's index of refraction, inside over outside
    float roughness;        // the rough materials' GGX alpha (at least kMinRoughness when used)
    bool coated;            // a coat over a diffuse, mirror or rough conductor base
    Coat coat;              // ... and what it is
    Conductor conductor;    // a mirror's or rough conductor's Fresnel term
    uint32_t coat_samples;  // walks a coated conductor's response to a punctual light averages
    vec3 transmittance;     // a diffuse surface's diffuse transmission (black: opaque)
};

// Where a path goes from a surface: the new direction, the weight it carries given that this
// branch was chosen, and whether it leaves through the other side.
struct SpecularBounce {
    vec3 direction;
    vec3 weight;
    bool transmitted;
#ifdef __cplusplus
    // GLSL's constructor syntax (clang before 16 lacks parenthesised aggregate initialisation).
    SpecularBounce() = default;
    SpecularBounce(vec3 direction_in, vec3 weight_in, bool transmitted_in)
        : direction(direction_in), weight(weight_in), transmitted(transmitted_in) {}
#endif
};

PF_GPU_FN bool IsRough(PF_IN(Bsdf) bsdf) {
    return (kHasRoughConductor && bsdf.type == kMaterialRoughConductor) ||
           (kHasRoughDielectric && bsdf.type == kMaterialRoughDielectric);
}
PF_GPU_FN bool IsCoated(PF_IN(Bsdf) bsdf) { return kHasCoats && bsdf.coated; }
PF_GPU_FN bool HasSheen(PF_IN(Bsdf) bsdf) {
    return kHasSheen && IsCoated(bsdf) &&
           !(bsdf.coat.sheen.x == 0.0f && bsdf.coat.sheen.y == 0.0f && bsdf.coat.sheen.z == 0.0f);
}
// Whether light crosses the diffuse surface to its other side.
PF_GPU_FN bool IsTranslucent(PF_IN(Bsdf) bsdf) {
    return kHasTranslucency && !(bsdf.transmittance.x == 0.0f && bsdf.transmittance.y == 0.0f &&
                                 bsdf.transmittance.z == 0.0f);
}
PF_GPU_FN float RoughAlpha(PF_IN(Bsdf) bsdf) { return max(bsdf.roughness, kMinRoughness); }
// The GGX alpha of a coated conductor's base: 0 for a mirror.
PF_GPU_FN float BaseAlpha(PF_IN(Bsdf) bsdf) { return IsRough(bsdf) ? RoughAlpha(bsdf) : 0.0f; }
// eta = n_incident / n_transmitted for light arriving at a dielectric: front faces lead in.
PF_GPU_FN float IncidentEta(PF_IN(Bsdf) bsdf, bool front_facing) {
    return front_facing ? 1.0f / bsdf.ior : bsdf.ior;
}

// What survives of a path's weight along the segment of length `distance` that ends at a
// surface whose media absorb with `behind` (inside) and `in_front` (outside): the medium of the
// side the segment arrived from (Beer-Lambert). Every pass multiplies by it at every hit.
PF_GPU_FN vec3 SegmentTransmittance(vec3 behind, vec3 in_front, bool front_facing, float distance) {
    if (behind.x == 0.0f && behind.y == 0.0f && behind.z == 0.0f && in_front.x == 0.0f &&
        in_front.y == 0.0f && in_front.z == 0.0f)
        return vec3(1.0f);
    return BeerLambert(front_facing ? in_front : behind, distance);
}

// The probability that light arriving along d at a specular surface is reflected rather than
// transmitted: Fresnel's for solid glass (1 under total internal reflection), the sum over a
// thin sheet's internal reflections 2R/(1+R) for thin glass, 1 for a mirror, 0 otherwise.
// `normal` is the shading normal on the triangle's front side, `front_facing` whether d
// arrives at that side.
PF_GPU_FN float ReflectionProbability(PF_IN(Bsdf) bsdf, vec3 d, vec3 normal, bool front_facing) {
    const vec3 n = front_facing ? normal : -normal;  // facing the incident side
    if (kHasDielectric && bsdf.type == kMaterialDielectric)
        return FresnelDielectric(-dot(d, n), IncidentEta(bsdf, front_facing));
    if (kHasThinDielectric && bsdf.type == kMaterialThinDielectric) {
        const float r = FresnelDielectric(-dot(d, n), 1.0f / bsdf.ior);
        return 2.0f * r / (1.0f + r);
    }
    return bsdf.type == kMaterialMirror ? 1.0f : 0.0f;
}

// The reflected branch: a mirror reflects its tint's Fresnel term (core/shared/conductor.h),
// glass reflects untinted.
PF_GPU_FN SpecularBounce ReflectSpecular(PF_IN(Bsdf) bsdf, vec3 d, vec3 normal, bool front_facing,
                                         vec3 tint) {
    const vec3 n = front_facing ? normal : -normal;
    const vec3 reflected = d - n * (2.0f * dot(d, n));
    if (bsdf.type != kMaterialMirror) return SpecularBounce(reflected, vec3(1.0f), false);
    return SpecularBounce(reflected, ConductorFresnel(bsdf.conductor, -dot(d, n), tint, 1.0f),
                          false);
}

// The transmitted branch, tinted by the base colour: refracted through solid glass (reflected
// instead should rounding disagree with ReflectionProbability about total internal reflection),
// straight through a thin sheet. `carries` (kCarriesRadiance or kCarriesFlux) says whether the
// refraction scales the weight by eta^2 (RefractionScale).
PF_GPU_FN SpecularBounce TransmitSpecular(PF_IN(Bsdf) bsdf, vec3 d, vec3 normal, bool front_facing,
                                          vec3 tint, uint32_t carries) {
    if (kHasThinDielectric && bsdf.type == kMaterialThinDielectric)
        return SpecularBounce(d, tint, true);
    const vec3 n = front_facing ? normal : -normal;
    const float eta = IncidentEta(bsdf, front_facing);
    vec3 refracted;
    if (!Refract(d, n, eta, refracted)) return ReflectSpecular(bsdf, d, normal, front_facing, tint);
    return SpecularBounce(refracted, tint * RefractionScale(carries, eta), true);
}

// The scale of radiance that a camera path transmitted through the surface took (RefractionScale
// of kCarriesRadiance): eta^2 through solid glass, smooth or rough, 1 through a thin sheet.
// Russian roulette divides it out.
PF_GPU_FN float RefractionOf(PF_IN(Bsdf) bsdf, bool front_facing) {
    const bool solid = (kHasDielectric && bsdf.type == kMaterialDielectric) ||
                       (kHasRoughDielectric && bsdf.type == kMaterialRoughDielectric);
    if (!solid) return 1.0f;
    const float eta = IncidentEta(bsdf, front_facing);
    return eta * eta;
}

// Scatters d at a specular surface, choosing the branch with its probability (u uniform in
// [0, 1)), so the carried weight is only the branch's tint (and a refraction's scale of
// radiance, for camera paths).
PF_GPU_FN SpecularBounce ScatterSpecular(PF_IN(Bsdf) bsdf, vec3 d, vec3 normal, bool front_facing,
                                         vec3 tint, float u, uint32_t carries) {
    if (u < ReflectionProbability(bsdf, d, normal, front_facing))
        return ReflectSpecular(bsdf, d, normal, front_facing, tint);
    return TransmitSpecular(bsdf, d, normal, front_facing, tint, carries);
}

// The reflection of wo (local) off the microfacet m, carrying `weight` times the masking ratio;
// absorbed (a black weight) where it leaves the hemisphere.
PF_GPU_FN SpecularBounce ReflectOffMicrofacet(Frame frame, vec3 d, vec3 wo, vec3 m, float cos_om,
                                              float alpha, vec3 weight) {
    const vec3 wi = m * (2.0f * cos_om) - wo;
    if (!(wi.z > 0.0f)) return SpecularBounce(d, vec3(0.0f), false);
    return SpecularBounce(ToWorld(frame, wi), weight * GgxMaskingRatio(wo.z, wi.z, alpha), false);
}

// Scatters d at a rough surface; u_branch chooses reflection or refraction (rough glass),
// (u1, u2) the microfacet. A black weight ends the path (the sample left the hemisphere it must
// stay in).
PF_GPU_FN SpecularBounce ScatterRough(PF_IN(Bsdf) bsdf, vec3 d, vec3 normal, bool front_facing,
                                      vec3 tint, float u_branch, float u1, float u2,
                                      uint32_t carries) {
    const vec3 n = front_facing ? normal : -normal;  // facing the incident side
    const Frame frame = FrameFromNormal(n);
    const vec3 wo = ToLocal(frame, -d);
    const SpecularBounce absorbed = SpecularBounce(d, vec3(0.0f), false);
    if (!(wo.z > 0.0f)) return absorbed;  // arrives from behind the shading normal
    const float alpha = RoughAlpha(bsdf);
    const vec3 m = SampleGgxVisibleNormal(wo, alpha, u1, u2);
    const float cos_om = dot(wo, m);
    if (bsdf.type == kMaterialRoughConductor)
        return ReflectOffMicrofacet(frame, d, wo, m, cos_om, alpha,
                                    ConductorFresnel(bsdf.conductor, cos_om, tint, 1.0f));
    // Rough glass: front faces lead into the glass, as for smooth glass.
    const float eta = IncidentEta(bsdf, front_facing);
    if (u_branch < FresnelDielectric(cos_om, eta))
        return ReflectOffMicrofacet(frame, d, wo, m, cos_om, alpha, vec3(1.0f));
    vec3 wi;
    if (!Refract(-wo, m, eta, wi))  // rounding against the Fresnel term
        return ReflectOffMicrofacet(frame, d, wo, m, cos_om, alpha, vec3(1.0f));
    if (!(wi.z < 0.0f)) return absorbed;
    return SpecularBounce(
        ToWorld(frame, wi),
        tint * (GgxMaskingRatio(wo.z, -wi.z, alpha) * RefractionScale(carries, eta)), true);
}

// Scatters d at a surface that is not diffuse: a coated conductor through its coat, a rough
// surface by its microfacets (three numbers from rng), a specular one by Fresnel (one).
// `carries` says whether a refraction scales the weight (kCarriesRadiance: camera paths) or
// not (kCarriesFlux: photons).
PF_GPU_FN SpecularBounce ScatterNonDiffuse(PF_IN(Bsdf) bsdf, vec3 d, vec3 normal, bool front_facing,
                                           vec3 tint, PF_INOUT(Pcg32) rng, uint32_t carries) {
    if (IsCoated(bsdf)) {  // a coated conductor
        const Frame frame = FrameFromNormal(front_facing ? normal : -normal);
        vec3 wi;
        const vec3 weight = ScatterCoatedConductor(bsdf.coat, bsdf.conductor, ToLocal(frame, -d),
                                                   tint, BaseAlpha(bsdf), rng, wi);
        return SpecularBounce(ToWorld(frame, wi), weight, false);
    }
    const float u_branch = Pcg32NextFloat(rng);
    if (!IsRough(bsdf))
        return ScatterSpecular(bsdf, d, normal, front_facing, tint, u_branch, carries);
    const float u1 = Pcg32NextFloat(rng);
    const float u2 = Pcg32NextFloat(rng);
    return ScatterRough(bsdf, d, normal, front_facing, tint, u_branch, u1, u2, carries);
}

// The side of a diffuse surface a path reads or leaves by (core/shared/translucent.h): its own
// (`through` false) or, through a translucent surface, the other; `albedo` is what the side
// passes (the base colour or the transmittance) over the probability of choosing it. Draws a
// number from rng only where the surface is translucent.
struct DiffuseSide {
    bool through;
    vec3 albedo;
};
PF_GPU_FN DiffuseSide ChooseDiffuseSide(PF_IN(Bsdf) bsdf, vec3 base_color, PF_INOUT(Pcg32) rng) {
    DiffuseSide side;
    side.through = false;
    side.albedo = base_color;
    if (!IsTranslucent(bsdf)) return side;
    const float through = TransmitProbability(base_color, bsdf.transmittance);
    if (Pcg32NextFloat(rng) < through) {
        side.through = true;
        side.albedo = bsdf.transmittance / through;
    } else {
        side.albedo = base_color / (1.0f - through);
    }
    return side;
}

// Where a ray along d meets a coated diffuse surface: the coat reflects it (`reflected`, a
// non-diffuse bounce), or it enters and reaches the base, carrying `weight` (the coat's masking
// and the layer's transmittance; core/shared/coat.h). Radiance carried by camera paths changes by
// CoatInside on the way in (the caller's: photons carry flux). An uncoated surface is its base.
struct CoatArrival {
    bool at_base;
    float weight;
    SpecularBounce reflected;
#ifdef __cplusplus
    CoatArrival() : at_base(true), weight(1.0f), reflected() {}
    CoatArrival(bool at_base_in, float weight_in, SpecularBounce reflected_in)
        : at_base(at_base_in), weight(weight_in), reflected(reflected_in) {}
#endif
};
PF_GPU_FN CoatArrival ArriveAtCoat(PF_IN(Bsdf) bsdf, vec3 d, vec3 normal, bool front_facing,
                                   PF_INOUT(Pcg32) rng) {
    const SpecularBounce none = SpecularBounce(d, vec3(0.0f), false);
    if (!IsCoated(bsdf)) return CoatArrival(true, 1.0f, none);
    const Frame frame = FrameFromNormal(front_facing ? normal : -normal);
    const float u_branch = Pcg32NextFloat(rng);
    const float u1 = Pcg32NextFloat(rng);
    const float u2 = Pcg32NextFloat(rng);
    vec3 wi;
    const vec3 weight = EnterCoat(bsdf.coat, ToLocal(frame, -d), u_branch, u1, u2, wi);
    if (wi.z < 0.0f) return CoatArrival(true, weight.x, none);  // grey on the way in
    return CoatArrival(false, 0.0f, SpecularBounce(ToWorld(frame, wi), weight, false));
}

// A path leaving a coated diffuse base upward along `up` (in `frame`, the shading normal on the
// path's side): out through the coat (`escaped`, along `direction`), or turned back down to the
// base; `weight` as ArriveAtCoat's (camera paths' radiance changes by 1 / CoatInside on the way
// out). Three numbers from rng.
struct CoatLeaving {
    bool escaped;
    vec3 direction;
    float weight;
};
PF_GPU_FN CoatLeaving LeaveCoatAt(Coat coat, Frame frame, vec3 up, PF_INOUT(Pcg32) rng) {
    const float u_branch = Pcg32NextFloat(rng);
    const float u1 = Pcg32NextFloat(rng);
    const float u2 = Pcg32NextFloat(rng);
    vec3 wi;
    CoatLeaving leaving;
    leaving.weight = LeaveCoat(coat, up, u_branch, u1, u2, wi);
    leaving.escaped = wi.z > 0.0f;
    leaving.direction = ToWorld(frame, wi);
    return leaving;
}

// For light sampling at rough metal (the path tracer's next-event estimation): with wo toward
// the viewer and wi toward the light, both unit and in world space, and `n` the shading normal
// on the viewer's side, f cos(wi) and the density in solid angle of ScatterRough choosing wi.
// Zero below the surface.
struct RoughReflection {
    vec3 value;  // f(wo, wi) cos(wi)
    float pdf;
};
PF_GPU_FN RoughReflection EvaluateRoughConductor(PF_IN(Bsdf) bsdf, vec3 tint, vec3 n, vec3 wo,
                                                 vec3 wi) {
    RoughReflection reflection;
    reflection.value = vec3(0.0f);
    reflection.pdf = 0.0f;
    const float cos_o = dot(wo, n), cos_i = dot(wi, n);
    if (!(cos_o > 0.0f && cos_i > 0.0f)) return reflection;
    const vec3 h = normalize(wo + wi);
    const float cos_h = dot(h, n);
    const float alpha = RoughAlpha(bsdf);
    const vec3 fresnel = ConductorFresnel(bsdf.conductor, dot(wo, h), tint, 1.0f);
    reflection.value = fresnel * GgxReflectionCosine(cos_o, cos_i, cos_h, alpha);
    reflection.pdf = GgxReflectionPdf(cos_o, cos_h, alpha);
    return reflection;
}

// Whether a camera path takes punctual lights by light sampling at the surface: where its
// reflection is not a delta (GlossyResponse is not black) -- rough metal and rough glass, and a
// coat with a rough interface, a sheen, or a rough conductor under it. A coat over a diffuse
// base counts its own reflection here alone: the light through it is the base's. False in a
// scene without punctual lights.
PF_GPU_FN bool GlossyToPunctualLights(PF_IN(Bsdf) bsdf) {
    if (!kHasPunctualLights) return false;
    if (IsCoated(bsdf))
        return bsdf.coat.alpha > 0.0f || HasSheen(bsdf) ||
               (kHasRoughConductor && bsdf.type == kMaterialRoughConductor);
    return IsRough(bsdf);
}

// f(wo, wi) |cos wi| of what the surface reflects of a punctual light along wi toward wo (world
// space, unit; `normal` the shading normal on the triangle's front side): the parts of its BSDF
// that are not deltas (core/shared/glossy_lights.h). Draws numbers from rng for a coated
// conductor only.
PF_GPU_FN vec3 GlossyResponse(PF_IN(Bsdf) bsdf, vec3 tint, vec3 normal, bool front_facing, vec3 wo,
                              vec3 wi, PF_INOUT(Pcg32) rng) {
    const vec3 n = front_facing ? normal : -normal;
    const Frame frame = FrameFromNormal(n);
    const vec3 local_o = ToLocal(frame, wo), local_i = ToLocal(frame, wi);
    if (IsCoated(bsdf)) {
        if (bsdf.type == kMaterialDiffuse) return CoatReflection(bsdf.coat, local_o, local_i);
        return CoatedConductorResponse(bsdf.coat, bsdf.conductor, tint, BaseAlpha(bsdf), local_o,
                                       local_i, bsdf.coat_samples, rng);
    }
    if (kHasRoughConductor && bsdf.type == kMaterialRoughConductor)
        return EvaluateRoughConductor(bsdf, tint, n, wo, wi).value;
    if (kHasRoughDielectric && bsdf.type == kMaterialRoughDielectric)
        return RoughDielectricResponse(IncidentEta(bsdf, front_facing), RoughAlpha(bsdf), tint,
                                       local_o, local_i);
    return vec3(0.0f);
}

PF_GPU_END

#endif  // PF_CORE_SHARED_SCATTER_H
