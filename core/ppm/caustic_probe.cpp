// The caustic probe: light paths followed through specular bounces to their first diffuse hit.
#include "core/ppm/caustic_probe.h"

#include <optional>

#include "core/camera/camera_pass.h"
#include "core/sampling/rng.h"
#include "core/scene/scattering.h"

namespace pf {

CausticProbe ProbeCaustics(const Scene& scene, const Emitters& emitters, const Tracer& tracer,
                           uint64_t seed, uint32_t paths) {
    CausticProbe probe;
    if (!emitters.HasPower()) return probe;
    constexpr uint64_t kProbeStream = 0x63617573746963ull;  // "caustic"
    for (uint32_t i = 0; i < paths; ++i) {
        Rng rng(HashSeed(seed, kProbeStream, i));
        Ray ray = emitters.Emit(rng).ray;
        ++probe.paths;
        for (int bounce = 0; bounce < kMaxCameraDepth; ++bounce) {
            RayHit hit;
            if (!tracer.Intersect(ray, &hit)) break;
            const SurfacePoint surface = scene.Surface(hit);
            std::optional<Material> shading;  // where a texture sets the roughness
            const Material& material = scene.ShadingMaterial(surface, shading);
            const Bsdf bsdf = BsdfOf(material);
            const bool front_facing = Dot(ray.direction, surface.geometric_normal) < 0;
            const CoatArrival arrival =
                material.type == MaterialType::kDiffuse
                    ? ArriveAtCoat(bsdf, ray.direction, surface.shading_normal, front_facing,
                                   rng.State())
                    : CoatArrival{};
            if (material.type == MaterialType::kDiffuse && arrival.at_base) {
                probe.caustic += bounce > 0;
                break;
            }
            const SpecularBounce next =
                material.type == MaterialType::kDiffuse
                    ? arrival.reflected
                    : ScatterNonDiffuse(bsdf, ray.direction, surface.shading_normal, front_facing,
                                        scene.BaseColor(surface), rng.State(), kCarriesFlux);
            if (IsBlack(next.weight)) break;
            const Vec3 side = front_facing == next.transmitted ? -surface.geometric_normal
                                                               : surface.geometric_normal;
            ray = {OffsetRayOrigin(surface.position, side, scene.bounds.Magnitude()),
                   next.direction};
        }
    }
    return probe;
}

}  // namespace pf
