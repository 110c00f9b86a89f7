// Scattering at the surfaces that are not diffuse, shared by the camera, photon and light
// paths of every integrator: specular ones (core/scene/specular.h) and the rough ones, whose
// GGX lobes are sampled through their visible normals (core/shared/microfacet.h). As at
// specular surfaces, a branch of rough glass is chosen with its Fresnel probability, so the
// carried weight is the tint times the masking ratio G2 / G1.
#pragma once

#include <algorithm>

#include "core/sampling/frame.h"
#include "core/sampling/rng.h"
#include "core/scene/material.h"
#include "core/scene/specular.h"
#include "core/shared/coat.h"
#include "core/shared/microfacet.h"
#include "core/shared/translucent.h"

namespace pf {

using gpu::CoatInside;
using gpu::GgxDistribution;
using gpu::GgxMaskingRatio;
using gpu::GgxReflectionPdf;
using gpu::kMaxCoatReturns;
using gpu::SampleGgxVisibleNormal;

// The material's coat, as core/shared/coat.h takes it.
inline gpu::Coat CoatOf(const Material& material) {
    return {material.coat_kind,      material.coat_ior,       material.coat_roughness,
            material.coat_thickness, material.coat_weight,    material.coat_depth,
            material.sheen_color,    material.sheen_roughness};
}

// What survives of a path's weight along the segment of length `distance` that ends where it
// meets `material`: the segment crossed the medium on the side it arrived from
// (Material::absorption behind the surface, outside_absorption in front; gpu::BeerLambert),
// where the surfaces bounding a medium name it. 1 without. Every pass multiplies by it at
// every hit, the Vulkan kernels too (specular.glsl's SegmentTransmittance).
inline Rgb SegmentTransmittance(const Material& material, bool front_facing, float distance) {
    if (!material.HasVolume()) return Rgb(1.0f);
    return gpu::BeerLambert(front_facing ? material.outside_absorption : material.absorption,
                            distance);
}

// The side of a diffuse surface a path reads or leaves by (core/shared/translucent.h): its
// own (`through` false) or, through a translucent surface, the other; `albedo` is what the
// side passes (base_color or the transmittance) over the probability of choosing it. Draws a
// number from rng only where the material is translucent.
struct DiffuseSide {
    bool through = false;
    Rgb albedo;
};
inline DiffuseSide ChooseDiffuseSide(const Material& material, const Rgb& base_color, Rng& rng) {
    if (!material.IsTranslucent()) return {false, base_color};
    const float through = gpu::TransmitProbability(base_color, material.transmittance);
    if (rng.NextFloat() < through) return {true, material.transmittance / through};
    return {false, base_color / (1.0f - through)};
}

// Scatters d at a rough surface; `normal` is the shading normal on the triangle's front
// side, u_branch chooses reflection or refraction (rough glass), (u1, u2) the microfacet. A
// black weight ends the path (the sample left the hemisphere it must stay in). `carries` as
// TransmitSpecular's: a camera path's radiance refracted scales by eta^2.
inline SpecularBounce ScatterRough(const Material& material, const Vec3& d, const Vec3& normal,
                                   bool front_facing, const Rgb& tint, float u_branch, float u1,
                                   float u2, uint32_t carries) {
    const Vec3 n = front_facing ? normal : -normal;  // facing the incident side
    const Frame frame = Frame::FromNormal(n);
    const Vec3 wo = frame.ToLocal(-d);
    const SpecularBounce absorbed{d, Rgb(0.0f), false};
    if (!(wo.z > 0)) return absorbed;  // arrives from behind the shading normal
    const float alpha = std::max(material.roughness, kMinRoughness);
    const Vec3 m = SampleGgxVisibleNormal(wo, alpha, u1, u2);
    const float cos_om = Dot(wo, m);
    const auto reflect = [&](const Rgb& weight) {
        const Vec3 wi = m * (2.0f * cos_om) - wo;
        if (!(wi.z > 0)) return absorbed;
        return SpecularBounce{frame.ToWorld(wi), weight * GgxMaskingRatio(wo.z, wi.z, alpha),
                              false};
    };
    if (material.type == MaterialType::kRoughConductor)
        return reflect(gpu::ConductorFresnel(ConductorOf(material), cos_om, tint, 1.0f));
    // Rough glass: front faces lead into the glass, as for smooth glass.
    const float eta = front_facing ? 1.0f / material.ior : material.ior;
    if (u_branch < FresnelDielectric(cos_om, eta)) return reflect(Rgb(1.0f));
    Vec3 wi;
    if (!Refract(-wo, m, eta, wi)) return reflect(Rgb(1.0f));  // rounding against the Fresnel term
    if (!(wi.z < 0)) return absorbed;
    return {frame.ToWorld(wi),
            tint * (GgxMaskingRatio(wo.z, -wi.z, alpha) * RefractionScale(carries, eta)), true};
}

// Scatters d at a surface that is not diffuse, drawing one number (specular) or three
// (rough) from rng; `carries` says whether a refraction scales the weight (kCarriesRadiance:
// camera paths) or not (kCarriesFlux: photons).
inline SpecularBounce ScatterNonDiffuse(const Material& material, const Vec3& d, const Vec3& normal,
                                        bool front_facing, const Rgb& tint, Rng& rng,
                                        uint32_t carries) {
    if (material.HasCoat()) {  // a coated conductor
        const Frame frame = Frame::FromNormal(front_facing ? normal : -normal);
        Vec3 wi;
        const Rgb weight = gpu::ScatterCoatedConductor(
            CoatOf(material), ConductorOf(material), frame.ToLocal(-d), tint,
            material.IsRough() ? std::max(material.roughness, kMinRoughness) : 0.0f, rng.State(),
            wi);
        return {frame.ToWorld(wi), weight, false};
    }
    const float u_branch = rng.NextFloat();
    if (!material.IsRough())
        return ScatterSpecular(material, d, normal, front_facing, tint, u_branch, carries);
    const float u1 = rng.NextFloat();
    const float u2 = rng.NextFloat();
    return ScatterRough(material, d, normal, front_facing, tint, u_branch, u1, u2, carries);
}

// Where a ray along d meets a coated diffuse surface: the coat reflects it (a non-diffuse
// bounce), or it enters and reaches the base, carrying `weight` (the coat's masking and the
// layer's transmittance; core/shared/coat.h). Radiance carried by camera paths changes by
// CoatInside on the way in (the caller's: photons carry flux). An uncoated surface is its base.
struct CoatArrival {
    bool at_base = true;
    float weight = 1.0f;
    SpecularBounce reflected{};
};
inline CoatArrival ArriveAtCoat(const Material& material, const Vec3& d, const Vec3& normal,
                                bool front_facing, Rng& rng) {
    if (!material.HasCoat()) return {};
    const Frame frame = Frame::FromNormal(front_facing ? normal : -normal);
    const float u_branch = rng.NextFloat();
    const float u1 = rng.NextFloat();
    const float u2 = rng.NextFloat();
    Vec3 wi;
    const Rgb weight = gpu::EnterCoat(CoatOf(material), frame.ToLocal(-d), u_branch, u1, u2, wi);
    if (wi.z < 0) return {true, weight.x, {}};  // grey on the way in
    return {false, 0.0f, {frame.ToWorld(wi), weight, false}};
}

// A path leaving a coated diffuse base upward along `up` (in `frame`, the shading normal on
// the path's side): out through the coat (`escaped`, along `direction`), or turned back down
// to the base; `weight` as ArriveAtCoat's (camera paths' radiance changes by 1 / CoatInside
// on the way out).
struct CoatLeaving {
    bool escaped = false;
    Vec3 direction;
    float weight = 0;
};
inline CoatLeaving LeaveCoatAt(const Material& material, const Frame& frame, const Vec3& up,
                               Rng& rng) {
    const float u_branch = rng.NextFloat();
    const float u1 = rng.NextFloat();
    const float u2 = rng.NextFloat();
    Vec3 wi;
    const float weight = gpu::LeaveCoat(CoatOf(material), up, u_branch, u1, u2, wi);
    return {wi.z > 0, frame.ToWorld(wi), weight};
}

// For light sampling at rough metal (the path tracer's next-event estimation): with wo toward
// the viewer and wi toward the light, both unit and in world space, and `n` the shading
// normal on the viewer's side, f cos(wi) and the density in solid angle of ScatterRough
// choosing wi. Zero below the surface.
struct RoughReflection {
    Rgb value;  // f(wo, wi) cos(wi)
    float pdf = 0;
};
inline RoughReflection EvaluateRoughConductor(const Material& material, const Rgb& tint,
                                              const Vec3& n, const Vec3& wo, const Vec3& wi) {
    const float cos_o = Dot(wo, n), cos_i = Dot(wi, n);
    if (!(cos_o > 0 && cos_i > 0)) return {Rgb(0.0f), 0.0f};
    const Vec3 h = Normalize(wo + wi);
    const float cos_h = Dot(h, n);
    const float alpha = std::max(material.roughness, kMinRoughness);
    const Rgb fresnel = gpu::ConductorFresnel(ConductorOf(material), Dot(wo, h), tint, 1.0f);
    return {fresnel * gpu::GgxReflectionCosine(cos_o, cos_i, cos_h, alpha),
            GgxReflectionPdf(cos_o, cos_h, alpha)};
}

}  // namespace pf
