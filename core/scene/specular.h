// Specular scattering shared by the camera and photon passes: mirrors, solid glass (Fresnel
// reflection and refraction) and thin glass. Branches are chosen with probability equal to
// their Fresnel weight, so the carried weight is only the tint.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/math/vec3.h"
#include "core/scene/material.h"
#include "core/shared/conductor.h"
#include "core/shared/path_sampling.h"

namespace pf {

// Fresnel reflectance and refraction, defined once for the CPU and the Vulkan kernels.
using gpu::FresnelDielectric;  // (cos_incident, eta = n_incident / n_transmitted)
using gpu::kCarriesFlux;       // what a path carries (core/shared/path_sampling.h): photons
using gpu::kCarriesRadiance;   // camera paths, whose radiance refraction scales by eta^2
using gpu::Refract;            // (d, n facing d's side, eta, out refracted); false under TIR
using gpu::RefractionScale;

// The material's conductor Fresnel term, as core/shared/conductor.h takes it.
inline gpu::Conductor ConductorOf(const Material& material) {
    return {material.conductor, material.conductor_eta, material.conductor_k};
}

// Mirror direction of d about n.
inline Vec3 Reflect(const Vec3& d, const Vec3& n) { return d - n * (2.0f * Dot(d, n)); }

struct SpecularBounce {
    Vec3 direction;
    Rgb weight;        // throughput factor of the branch, given that it was chosen
    bool transmitted;  // the new ray leaves through the other side of the surface
};

// The probability that light arriving along d at a specular surface is reflected rather than
// transmitted: Fresnel's for solid glass (1 under total internal reflection), the sum over a
// thin sheet's internal reflections 2R/(1+R) for thin glass, 1 for a mirror. `normal` is the
// shading normal on the triangle's front side, `front_facing` whether d arrives at that side.
inline float ReflectionProbability(const Material& material, const Vec3& d, const Vec3& normal,
                                   bool front_facing) {
    const Vec3 n = front_facing ? normal : -normal;  // facing the incident side
    switch (material.type) {
        case MaterialType::kDielectric:
            // Front faces lead into the glass (the volume lies behind the winding's front).
            return FresnelDielectric(-Dot(d, n), front_facing ? 1.0f / material.ior : material.ior);
        case MaterialType::kThinDielectric: {
            const float r = FresnelDielectric(-Dot(d, n), 1.0f / material.ior);
            return 2.0f * r / (1.0f + r);
        }
        case MaterialType::kMirror:
            return 1.0f;
        case MaterialType::kDiffuse:
        case MaterialType::kRoughConductor:
        case MaterialType::kRoughDielectric:
        case MaterialType::kMix:  // resolved by Scene::Surface before any scattering
            break;                // not specular (glossy.h)
    }
    return 0.0f;
}

// The reflected branch: a mirror reflects its tint's Fresnel term (core/shared/conductor.h),
// glass reflects untinted.
inline SpecularBounce ReflectSpecular(const Material& material, const Vec3& d, const Vec3& normal,
                                      bool front_facing, const Rgb& tint) {
    const Vec3 n = front_facing ? normal : -normal;
    if (material.type != MaterialType::kMirror) return {Reflect(d, n), Rgb(1.0f), false};
    return {Reflect(d, n), gpu::ConductorFresnel(ConductorOf(material), -Dot(d, n), tint, 1.0f),
            false};
}

// The transmitted branch, tinted by the base colour: refracted through solid glass (reflected
// instead should rounding disagree with ReflectionProbability about total internal
// reflection), straight through a thin sheet. `carries` (kCarriesRadiance or kCarriesFlux)
// says whether the refraction scales the weight by eta^2 (RefractionScale).
inline SpecularBounce TransmitSpecular(const Material& material, const Vec3& d, const Vec3& normal,
                                       bool front_facing, const Rgb& tint, uint32_t carries) {
    if (material.type == MaterialType::kThinDielectric) return {d, tint, true};
    const Vec3 n = front_facing ? normal : -normal;
    const float eta = front_facing ? 1.0f / material.ior : material.ior;
    Vec3 refracted;
    if (!Refract(d, n, eta, refracted))
        return ReflectSpecular(material, d, normal, front_facing, tint);
    return {refracted, tint * RefractionScale(carries, eta), true};
}

// The scale of radiance that a camera path transmitted through `material` took
// (RefractionScale of kCarriesRadiance): eta^2 through solid glass, smooth or rough, 1 through
// a thin sheet. Russian roulette divides it out.
inline float RefractionOf(const Material& material, bool front_facing) {
    if (material.type != MaterialType::kDielectric &&
        material.type != MaterialType::kRoughDielectric)
        return 1.0f;
    const float eta = front_facing ? 1.0f / material.ior : material.ior;
    return eta * eta;
}

// Scatters incoming direction d at a specular surface, choosing the branch with its
// probability (u uniform in [0, 1)), so the carried weight is only the branch's tint (and a
// refraction's scale of radiance, for camera paths).
inline SpecularBounce ScatterSpecular(const Material& material, const Vec3& d, const Vec3& normal,
                                      bool front_facing, const Rgb& tint, float u,
                                      uint32_t carries) {
    if (u < ReflectionProbability(material, d, normal, front_facing))
        return ReflectSpecular(material, d, normal, front_facing, tint);
    return TransmitSpecular(material, d, normal, front_facing, tint, carries);
}

}  // namespace pf
