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
#include "core/scene/material.h"
#include "core/scene/scattering.h"
#include "core/scene/scene.h"
#include "core/shared/glossy_lights.h"

namespace pf {

// What a camera path arriving along -wo at a glossy vertex (GlossyToPunctualLights) sees of
// punctual lights: one light sample, kept where it picked a punctual light, f |cos| times its
// radiance over pdf where its shadow ray is clear; rough glass takes a light on either side.
// Draws three numbers, then a coated conductor's (GlossyResponse), as the Vulkan kernels do.
inline Rgb PunctualLightOnGloss(const Emitters& emitters, const Tracer& tracer,
                                const SurfacePoint& surface, const Bsdf& bsdf, const Rgb& tint,
                                bool front_facing, const Vec3& wo, Rng& rng) {
    const Vec3 geometric = front_facing ? surface.geometric_normal : -surface.geometric_normal;
    const float pick = rng.NextFloat();
    const Point2 u{rng.NextFloat(), rng.NextFloat()};
    LightSample light;
    bool found = emitters.SampleDirect(surface.position, geometric, pick, u, &light);
    if (!found && bsdf.type == gpu::kMaterialRoughDielectric && !bsdf.coated)
        found = emitters.SampleDirect(surface.position, -geometric, pick, u, &light);
    if (!found || light.pdf > 0) return Rgb(0.0f);
    const Rgb f = GlossyResponse(bsdf, tint, surface.shading_normal, front_facing, wo,
                                 light.direction, rng.State());
    if (IsBlack(f) || tracer.Occluded(light.shadow_ray)) return Rgb(0.0f);
    return f * light.radiance_over_pdf;
}

}  // namespace pf
