// One step of a photon's random walk, shared by the progressive photon pass and classic
// photon mapping's map building: at a diffuse surface the photon may land (the caller
// decides whether to keep it), then Russian roulette by albedo and a cosine-weighted bounce
// (through the coat over it, if any; through to the other side of a translucent surface); at any
// other surface ScatterNonDiffuse and roulette by its weight (Jensen 2001, 2.3.3). Where the
// shading normal is not the surface's, the photon carries Veach's adjoint factors
// (core/shared/shading_normal.h).
#pragma once

#include <algorithm>
#include <limits>
#include <optional>

#include "core/geometry/ray.h"
#include "core/sampling/frame.h"
#include "core/sampling/rng.h"
#include "core/sampling/sampling.h"
#include "core/scene/scattering.h"
#include "core/scene/scene.h"
#include "core/shared/shading_normal.h"

namespace pf {

enum class PhotonEvent { kEnded, kDiffuse, kNonDiffuse };

// Under a coat: the photon leaving the base along `local` (in `frame`) is let out by the coat
// (ray.direction set, true) or turned back to the base, where it lands again, survives
// roulette by albedo and leaves again, until it gets out or ends (false).
template <typename Land>
bool LeaveCoatedBase(const Material& material, const Vec3& position, const Frame& frame,
                     const Rgb& base_color, Vec3 local, Ray& ray, Rgb& flux, Rng& rng, Land& land) {
    const gpu::Coat coat = CoatOf(material);
    for (int returns = 0;; ++returns) {
        const CoatLeaving leaving = LeaveCoatAt(coat, frame, local, rng.State());
        flux *= leaving.weight;
        ray.direction = leaving.direction;
        if (leaving.escaped) return true;
        // The coat's visits to the base (Material::coat_depth), this landing's the first.
        if (IsBlack(flux) || returns + 1 >= static_cast<int>(material.coat_depth)) return false;
        land(position, ray.direction, flux, true, std::abs(Dot(ray.direction, frame.n)), frame.n);
        const float survive = std::min(1.0f, MaxComponent(base_color));
        if (!(rng.NextFloat() < survive)) return false;
        flux *= base_color / survive;
        local = SampleCosineHemisphere(rng.NextFloat(), rng.NextFloat());
    }
}

// Continues the photon (ray, flux) at `hit`: calls land(position, direction, flux, returned,
// cosine, normal) at a diffuse surface before scattering (again, with `returned` true, each time a
// coat over it turns the photon back to it), then moves ray and flux to the next segment. `cosine`
// is |direction . the normal the flux crossed| (the surface's; the shading normal's under a
// coat): where shading normals differ from the surface's, a point gathering the photon weighs
// its flux by |direction . its own shading normal| / cosine (Veach's arrival factor, taken at
// the gathering point, whose normal may differ from the photon's); `normal`, the surface's,
// turned toward the side the photon arrived from (the surface it landed on, for a gather
// that keeps to the hit point's own surface: HashGrid::ForEachGathering). Returns where
// it scattered, or kEnded where roulette or a bounce below the surface ends it. Instantiated
// for the scene's features: without specular materials or coats every surface is diffuse,
// without textures every base colour is the material's.
template <bool kSpecular, bool kTextures, typename Land>
PhotonEvent ScatterPhotonAt(const Scene& scene, const RayHit& hit, Ray& ray, Rgb& flux, Rng& rng,
                            Land&& land) {
    const SurfacePoint surface = scene.Surface(hit);
    std::optional<Material> shading;  // where a texture sets the roughness
    const Material& material = scene.ShadingMaterial(surface, shading);
    const Bsdf bsdf = BsdfOf(material);
    const bool front_facing = Dot(ray.direction, surface.geometric_normal) < 0;
    if (kSpecular)
        flux *= SegmentTransmittance(material.absorption, material.outside_absorption, front_facing,
                                     hit.t);
    // Veach's adjoint for shading normals: one factor where the photon arrives (after it lands:
    // the points gathering it weigh it by their own normals), one where it leaves.
    const bool shaded = !(surface.shading_normal == surface.geometric_normal);
    const float arrival = shaded ? gpu::ShadingArrival(ray.direction, surface.shading_normal,
                                                       surface.geometric_normal)
                                 : 1.0f;
    const auto leave = [&](const Vec3& direction) {
        if (shaded)
            flux *=
                gpu::ShadingDeparture(direction, surface.shading_normal, surface.geometric_normal);
    };
    const Rgb base_color = kTextures ? scene.BaseColor(surface) : material.base_color;
    ray.t_max = std::numeric_limits<float>::infinity();
    SpecularBounce bounce;
    if (!kSpecular || material.type == MaterialType::kDiffuse) {
        const bool coated = kSpecular && material.HasCoat();
        CoatArrival coat;  // uncoated: at the base, weight 1
        if (coated) {
            coat = ArriveAtCoat(bsdf, ray.direction, surface.shading_normal, front_facing,
                                rng.State());
            if (coat.at_base) flux *= coat.weight;  // a reflection carries its own
        }
        if (coat.at_base) {
            land(surface.position, ray.direction, flux, false,
                 std::abs(Dot(ray.direction, surface.geometric_normal)),
                 front_facing ? surface.geometric_normal : -surface.geometric_normal);
            if (!(arrival > 0)) return PhotonEvent::kEnded;  // from below the shading normal
            flux *= arrival;
            // Back to its side or, through a translucent surface, on to the other.
            const DiffuseSide side = kSpecular ? ChooseDiffuseSide(bsdf, base_color, rng.State())
                                               : DiffuseSide{false, base_color};
            // Russian roulette by albedo: survivors carry flux * albedo / p.
            const float survive = std::min(1.0f, MaxComponent(side.albedo));
            if (!(rng.NextFloat() < survive)) return PhotonEvent::kEnded;
            flux *= side.albedo / survive;
            const Vec3 normal = front_facing ? surface.shading_normal : -surface.shading_normal;
            const Vec3 geometric =
                front_facing != side.through ? surface.geometric_normal : -surface.geometric_normal;
            const Vec3 local = SampleCosineHemisphere(rng.NextFloat(), rng.NextFloat());
            if (!coated) {
                // Lambertian reflection (and transmission) is the same toward every direction
                // on its side of the surface, whatever the shading normal (as the path tracer
                // sees it): the photon leaves by the surface's own cosine, where Veach's
                // departure factor is 1.
                ray.direction = ToWorld(FrameFromNormal(geometric), local);
            } else {
                if (!LeaveCoatedBase(material, surface.position, FrameFromNormal(normal),
                                     base_color, local, ray, flux, rng, land))
                    return PhotonEvent::kEnded;
                if (!(Dot(ray.direction, geometric) > 0))
                    return PhotonEvent::kEnded;  // shading normal pointed it inside
                leave(ray.direction);
            }
            ray.origin = OffsetRayOrigin(surface.position, geometric, scene.bounds.Magnitude());
            return PhotonEvent::kDiffuse;
        }
        bounce = coat.reflected;
    } else {
        bounce = ScatterNonDiffuse(bsdf, ray.direction, surface.shading_normal, front_facing,
                                   base_color, rng.State(), kCarriesFlux);
    }
    const float survive = std::min(1.0f, MaxComponent(bounce.weight));
    if (!(rng.NextFloat() < survive) || !(arrival > 0)) return PhotonEvent::kEnded;
    flux *= bounce.weight * (arrival / survive);
    leave(bounce.direction);
    const Vec3 side =
        front_facing == bounce.transmitted ? -surface.geometric_normal : surface.geometric_normal;
    ray.origin = OffsetRayOrigin(surface.position, side, scene.bounds.Magnitude());
    ray.direction = bounce.direction;
    return PhotonEvent::kNonDiffuse;
}

}  // namespace pf
