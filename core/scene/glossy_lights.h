// Punctual lights at the glossy vertices of camera paths: what a surface whose reflection is not
// a delta shows of point, spot, distant and image lights, which no sampled direction finds
// (core/shared/glossy_lights.h evaluates it), taken by light sampling there. Area lights and
// the environment are left to the surfaces' own sampling, which finds them: nothing counts
// twice. Every camera path does this: the camera passes (ppm, sppm, rpm), classic photon
// mapping's and the path tracer's, on the CPU and in the Vulkan kernels
// (path_vertex.glsl's PunctualLightOnGloss).
#pragma once

#include <algorithm>

#include "core/geometry/ray.h"
#include "core/geometry/tracer.h"
#include "core/sampling/frame.h"
#include "core/sampling/rng.h"
#include "core/scene/emitters.h"
#include "core/scene/glossy.h"
#include "core/scene/material.h"
#include "core/scene/scene.h"
#include "core/shared/glossy_lights.h"

namespace pf {

// Whether a camera path at `material` takes punctual lights by light sampling there: where its
// reflection is not a delta (GlossyResponse is not black) -- rough metal and rough glass, and a
// coat with a rough interface, a sheen, or a rough conductor under it. A coat over a diffuse
// base counts its own reflection here alone: the light through it is the base's.
inline bool GlossyToPunctualLights(const Material& material) {
    if (material.HasCoat())
        return material.coat_roughness > 0 || material.HasSheen() ||
               material.type == MaterialType::kRoughConductor;
    return material.IsRough();
}

// f(wo, wi) |cos wi| of what `material` reflects of a punctual light along wi toward wo (world
// space, unit; `normal` the shading normal on the triangle's front side): the parts of its BSDF
// that are not deltas (core/shared/glossy_lights.h). Draws numbers from rng for a coated
// conductor only.
inline Rgb GlossyResponse(const Material& material, const Rgb& tint, const Vec3& normal,
                          bool front_facing, const Vec3& wo, const Vec3& wi, Rng& rng) {
    const Vec3 n = front_facing ? normal : -normal;
    const Frame frame = Frame::FromNormal(n);
    const Vec3 local_o = frame.ToLocal(wo), local_i = frame.ToLocal(wi);
    if (material.HasCoat()) {
        if (material.type == MaterialType::kDiffuse)
            return gpu::CoatReflection(CoatOf(material), local_o, local_i);
        return gpu::CoatedConductorResponse(
            CoatOf(material), ConductorOf(material), tint,
            material.IsRough() ? std::max(material.roughness, kMinRoughness) : 0.0f, local_o,
            local_i, material.coat_samples, rng.State());
    }
    if (material.type == MaterialType::kRoughConductor)
        return EvaluateRoughConductor(material, tint, n, wo, wi).value;
    if (material.type == MaterialType::kRoughDielectric)
        return gpu::RoughDielectricResponse(front_facing ? 1.0f / material.ior : material.ior,
                                            std::max(material.roughness, kMinRoughness), tint,
                                            local_o, local_i);
    return Rgb(0.0f);
}

// What a camera path arriving along -wo at a glossy vertex (GlossyToPunctualLights) sees of
// punctual lights: one light sample, kept where it picked a punctual light, f |cos| times its
// radiance over pdf where its shadow ray is clear; rough glass takes a light on either side.
// Draws three numbers, then a coated conductor's (GlossyResponse), as the Vulkan kernels do.
inline Rgb PunctualLightOnGloss(const Emitters& emitters, const Tracer& tracer,
                                const SurfacePoint& surface, const Material& material,
                                const Rgb& tint, bool front_facing, const Vec3& wo, Rng& rng) {
    const Vec3 geometric = front_facing ? surface.geometric_normal : -surface.geometric_normal;
    const float pick = rng.NextFloat();
    const Point2 u{rng.NextFloat(), rng.NextFloat()};
    LightSample light;
    bool found = emitters.SampleDirect(surface.position, geometric, pick, u, &light);
    if (!found && material.type == MaterialType::kRoughDielectric && !material.HasCoat())
        found = emitters.SampleDirect(surface.position, -geometric, pick, u, &light);
    if (!found || light.pdf > 0) return Rgb(0.0f);
    const Rgb f = GlossyResponse(material, tint, surface.shading_normal, front_facing, wo,
                                 light.direction, rng);
    if (IsBlack(f) || tracer.Occluded(light.shadow_ray)) return Rgb(0.0f);
    return f * light.radiance_over_pdf;
}

}  // namespace pf
