// Specular and rough scattering, as core/scene/specular.h and core/scene/glossy.h (Fresnel
// and refraction from core/shared/path_sampling.h, the GGX lobes from core/shared/microfacet.h):
// the branch is chosen with its Fresnel probability, so the carried weight is the tint alone
// (times the masking ratio G2 / G1 on rough surfaces); coats as core/shared/coat.h walks them.
// Materials the scene lacks are compiled out.
#include "core/shared/microfacet.h"
#include "core/shared/coat.h"
#include "core/shared/glossy_lights.h"

// What survives of a path's weight along the segment of length `distance` that ends where it
// meets `material` (SegmentTransmittance in core/scene/glossy.h): the medium of the side it
// arrived from, behind the surface or in front.
vec3 SegmentTransmittance(GpuMaterial material, bool front_facing, float distance) {
    return BeerLambert(front_facing ? material.outside_absorption.xyz : material.absorption.xyz, distance);
}

// The material's coat, as core/shared/coat.h takes it (glossy.h's CoatOf).
Coat CoatOf(GpuMaterial material) {
    return Coat(floatBitsToUint(material.layer.x), material.coat.x, material.coat.y, material.coat.z, material.layer.y,
                floatBitsToUint(material.coat.w), material.sheen.xyz, material.sheen.w);
}

// The material's conductor Fresnel term, as core/shared/conductor.h takes it (specular.h's
// ConductorOf); the tint alone in a scene whose metals all reflect it at every angle.
Conductor ConductorOf(GpuMaterial material) {
    return Conductor(kHasConductorFresnel ? floatBitsToUint(material.conductor_eta.w) : kConductorTint,
                     material.conductor_eta.xyz, material.conductor_k.xyz);
}

struct SpecularBounce {
    vec3 direction;
    vec3 weight;
    bool transmitted;
};

// d arrives at a specular surface of `material` whose front-side shading normal is `normal`.
// `carries` (kCarriesRadiance, kCarriesFlux) as TransmitSpecular's in core/scene/specular.h.
SpecularBounce ScatterSpecular(GpuMaterial material, vec3 d, vec3 normal, bool front_facing, vec3 tint, float u,
                               uint carries) {
    const vec3 n = front_facing ? normal : -normal;  // facing the incident side
    const float ior = material.base_color.w;
    const float cos_i = -dot(d, n);
    float reflect_probability = 1.0;
    if (kHasDielectric && material.type == kMaterialDielectric) {
        // Front faces lead into the glass.
        reflect_probability = FresnelDielectric(cos_i, front_facing ? 1.0 / ior : ior);
    } else if (kHasThinDielectric && material.type == kMaterialThinDielectric) {
        const float r = FresnelDielectric(cos_i, 1.0 / ior);
        reflect_probability = 2.0 * r / (1.0 + r);
    }
    const SpecularBounce reflected = SpecularBounce(
        d + n * (2.0 * cos_i),
        material.type == kMaterialMirror ? ConductorFresnel(ConductorOf(material), cos_i, tint, 1.0) : vec3(1.0), false);
    if (u < reflect_probability) return reflected;
    if (kHasThinDielectric && material.type == kMaterialThinDielectric) return SpecularBounce(d, tint, true);
    // Refraction through solid glass; reflected instead should rounding disagree with the
    // Fresnel term about total internal reflection.
    const float eta = front_facing ? 1.0 / ior : ior;
    vec3 refracted;
    if (!Refract(d, n, eta, refracted)) return reflected;
    return SpecularBounce(refracted, tint * RefractionScale(carries, eta), true);
}

// d arrives at a rough surface; u_branch chooses reflection or refraction (rough glass),
// (u1, u2) the microfacet. A black weight ends the path.
SpecularBounce ScatterRough(GpuMaterial material, vec3 d, vec3 normal, bool front_facing, vec3 tint, float u_branch,
                            float u1, float u2, uint carries) {
    const vec3 n = front_facing ? normal : -normal;  // facing the incident side
    const mat3 frame = FrameFromNormal(n);
    const vec3 wo = -d * frame;  // to the local frame: the transpose
    const SpecularBounce absorbed = SpecularBounce(d, vec3(0.0), false);
    if (!(wo.z > 0.0)) return absorbed;
    const float alpha = max(material.roughness, 1e-3);
    const vec3 m = SampleGgxVisibleNormal(wo, alpha, u1, u2);
    const float cos_om = dot(wo, m);
    const vec3 reflected = m * (2.0 * cos_om) - wo;
    const bool conductor = material.type == kMaterialRoughConductor;
    const float ior = material.base_color.w;
    const float eta = front_facing ? 1.0 / ior : ior;
    vec3 wi;
    const bool refracts = !conductor && u_branch >= FresnelDielectric(cos_om, eta) && Refract(-wo, m, eta, wi);
    if (!refracts) {
        if (!(reflected.z > 0.0)) return absorbed;
        const vec3 weight = conductor ? ConductorFresnel(ConductorOf(material), cos_om, tint, 1.0) : vec3(1.0);
        return SpecularBounce(frame * reflected, weight * GgxMaskingRatio(wo.z, reflected.z, alpha), false);
    }
    if (!(wi.z < 0.0)) return absorbed;
    return SpecularBounce(frame * wi, tint * (GgxMaskingRatio(wo.z, -wi.z, alpha) * RefractionScale(carries, eta)),
                          true);
}

// Scatters d at a non-diffuse surface (ScatterNonDiffuse): a coated conductor through its coat,
// a rough surface by its microfacets (three numbers), a specular one by Fresnel (one).
SpecularBounce ScatterNonDiffuse(GpuMaterial material, Surface surface, vec3 d, bool front_facing, inout Pcg32 rng,
                                 uint carries) {
    if (kHasCoats && material.coat.x > 0.0) {  // a coated conductor
        const mat3 frame = FrameFromNormal(front_facing ? surface.shading_normal : -surface.shading_normal);
        const float base_alpha = material.type == kMaterialRoughConductor ? max(material.roughness, 1e-3) : 0.0;
        vec3 wi;
        const vec3 weight = ScatterCoatedConductor(CoatOf(material), ConductorOf(material), -d * frame,
                                                   surface.base_color, base_alpha, rng, wi);
        return SpecularBounce(frame * wi, weight, false);
    }
    const float u_branch = Pcg32NextFloat(rng);
    if ((kHasRoughConductor && material.type == kMaterialRoughConductor) ||
        (kHasRoughDielectric && material.type == kMaterialRoughDielectric)) {
        const float u1 = Pcg32NextFloat(rng), u2 = Pcg32NextFloat(rng);
        return ScatterRough(material, d, surface.shading_normal, front_facing, surface.base_color, u_branch, u1, u2,
                            carries);
    }
    return ScatterSpecular(material, d, surface.shading_normal, front_facing, surface.base_color, u_branch, carries);
}

// The scale of radiance a camera path transmitted through `material` took (RefractionOf in
// core/scene/specular.h), which Russian roulette divides out.
float RefractionOf(GpuMaterial material, bool front_facing) {
    const bool solid = (kHasDielectric && material.type == kMaterialDielectric) ||
                       (kHasRoughDielectric && material.type == kMaterialRoughDielectric);
    if (!solid) return 1.0;
    const float eta = front_facing ? 1.0 / material.base_color.w : material.base_color.w;
    return eta * eta;
}

// Whether the scene has lights that are deltas (SceneFeatures::PunctualLights).
const bool kHasPunctualLights = kHasPointLights || kHasSpotLights || kHasDirectionalLights || kHasImageLights;

// The walks of a coated conductor's response to a punctual light (Material::coat_samples).
uint CoatSamples(GpuMaterial material) { return floatBitsToUint(material.conductor_k.w); }

// Light sampling at rough metal (EvaluateRoughConductor in core/scene/glossy.h): f cos(wi) into
// `value` and the density with which ScatterRough chooses wi; n the shading normal on wo's side.
float EvaluateRoughConductor(GpuMaterial material, vec3 tint, vec3 n, vec3 wo, vec3 wi, out vec3 value) {
    value = vec3(0.0);
    const float cos_o = dot(wo, n), cos_i = dot(wi, n);
    if (!(cos_o > 0.0 && cos_i > 0.0)) return 0.0;
    const vec3 h = normalize(wo + wi);
    const float cos_h = dot(h, n);
    const float alpha = max(material.roughness, 1e-3);
    value = ConductorFresnel(ConductorOf(material), dot(wo, h), tint, 1.0) * GgxReflectionCosine(cos_o, cos_i, cos_h, alpha);
    return GgxReflectionPdf(cos_o, cos_h, alpha);
}

// Whether a camera path at `material` takes punctual lights by light sampling there
// (GlossyToPunctualLights in core/scene/glossy_lights.h); false in a scene without them.
bool GlossyToPunctualLights(GpuMaterial material) {
    if (!kHasPunctualLights) return false;
    if (kHasCoats && material.coat.x > 0.0)
        return material.coat.y > 0.0 || (kHasSheen && MaxComponent(material.sheen.xyz) > 0.0) ||
               (kHasRoughConductor && material.type == kMaterialRoughConductor);
    return (kHasRoughConductor && material.type == kMaterialRoughConductor) ||
           (kHasRoughDielectric && material.type == kMaterialRoughDielectric);
}

// f(wo, wi) |cos wi| of what `material` reflects of a punctual light along wi toward wo
// (GlossyResponse in core/scene/glossy_lights.h); draws numbers for a coated conductor only.
vec3 GlossyResponse(GpuMaterial material, Surface surface, bool front_facing, vec3 wo, vec3 wi, inout Pcg32 rng) {
    const vec3 n = front_facing ? surface.shading_normal : -surface.shading_normal;
    const mat3 frame = FrameFromNormal(n);
    const vec3 local_o = wo * frame, local_i = wi * frame;  // to the local frame: the transpose
    if (kHasCoats && material.coat.x > 0.0) {
        if (material.type == kMaterialDiffuse) return CoatReflection(CoatOf(material), local_o, local_i);
        const float base_alpha = material.type == kMaterialRoughConductor ? max(material.roughness, 1e-3) : 0.0;
        return CoatedConductorResponse(CoatOf(material), ConductorOf(material), surface.base_color, base_alpha,
                                       local_o, local_i, CoatSamples(material), rng);
    }
    if (kHasRoughConductor && material.type == kMaterialRoughConductor) {
        vec3 value;
        EvaluateRoughConductor(material, surface.base_color, n, wo, wi, value);
        return value;
    }
    if (kHasRoughDielectric && material.type == kMaterialRoughDielectric) {
        const float ior = material.base_color.w;
        return RoughDielectricResponse(front_facing ? 1.0 / ior : ior, max(material.roughness, 1e-3),
                                       surface.base_color, local_o, local_i);
    }
    return vec3(0.0);
}
