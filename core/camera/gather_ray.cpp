// Final-gather rays to their diffuse landing.
#include "core/camera/gather_ray.h"

#include "core/job/hit_point.h"

namespace pf {

std::optional<DiffuseLanding> FollowToDiffuse(const Scene& scene, const Tracer& tracer, Ray ray,
                                              Rng& rng) {
    Rgb weight(1.0f);
    for (int depth = 0; depth < kMaxGatherDepth; ++depth) {
        RayHit hit;
        if (!tracer.Intersect(ray, &hit)) return std::nullopt;
        const SurfacePoint surface = scene.Surface(hit);
        std::optional<Material> shading;  // where a texture sets the roughness
        const Material& material = scene.ShadingMaterial(surface, shading);
        const Bsdf bsdf = BsdfOf(material);
        const bool front_facing = Dot(ray.direction, surface.geometric_normal) < 0;
        weight *= SegmentTransmittance(material.absorption, material.outside_absorption,
                                       front_facing, hit.t);
        const Rgb base_color = scene.BaseColor(surface);
        const CoatArrival arrival = material.type == MaterialType::kDiffuse
                                        ? ArriveAtCoat(bsdf, ray.direction, surface.shading_normal,
                                                       front_facing, rng.State())
                                        : CoatArrival{};
        if (material.type == MaterialType::kDiffuse && arrival.at_base) {
            const DiffuseSide side = ChooseDiffuseSide(bsdf, base_color, rng.State());
            const Vec3 normal =
                front_facing != side.through ? surface.shading_normal : -surface.shading_normal;
            return DiffuseLanding{surface.position, normal, side.albedo,
                                  weight * CoatedRadianceFactor(material, arrival),
                                  material.HasCoat() ? surface.material : kNoCoat};
        }
        const SpecularBounce bounce =
            material.type == MaterialType::kDiffuse
                ? arrival.reflected
                : ScatterNonDiffuse(bsdf, ray.direction, surface.shading_normal, front_facing,
                                    base_color, rng.State(), kCarriesRadiance);
        weight *= bounce.weight;
        if (IsBlack(weight)) return std::nullopt;
        const Vec3 side = front_facing == bounce.transmitted ? -surface.geometric_normal
                                                             : surface.geometric_normal;
        ray = {OffsetRayOrigin(surface.position, side, scene.bounds.Magnitude()), bounce.direction};
    }
    return std::nullopt;
}

}  // namespace pf
