// The rendering pass of classic photon mapping.
#include "core/pm/photon_mapping.h"

#include <algorithm>
#include <optional>

#include "core/camera/camera_pass.h"
#include "core/camera/gather_ray.h"
#include "core/pm/density_estimate.h"
#include "core/ppm/direct_light.h"
#include "core/sampling/frame.h"
#include "core/sampling/sampling.h"
#include "core/scene/glossy_lights.h"
#include "core/scene/scattering.h"

namespace pf {
namespace {

// Reflected radiance from the global map where a gather ray from `origin` lands
// (FollowToDiffuse), times the weight of the way there.
Rgb GatherRay(const PhotonMappingInputs& inputs, const Ray& ray, Rng& rng,
              NearestPhotons& scratch) {
    const std::optional<DiffuseLanding> landing =
        FollowToDiffuse(*inputs.scene, *inputs.tracer, ray, rng);
    if (!landing) return Rgb(0.0f);
    const float max_radius_sq = inputs.max_radius * inputs.max_radius;
    return landing->weight * EstimateDiffuseRadiance(
                                 *inputs.maps->global, landing->position, landing->normal,
                                 landing->albedo, inputs.settings.nearest, max_radius_sq,
                                 inputs.settings.filter, inputs.features.ShadingNormals(), scratch);
}

// The light leaving diffuse point `surface` toward the camera path, its albedo `albedo`, the
// material `coat` over it if any. Under a coat the global map's estimate stands in for final
// gathering (gather rays would have to cross the coat; the map holds the photons it turned
// back), and with final gathering, whose global map holds every landing, for all of it.
Rgb DiffuseRadiance(const PhotonMappingInputs& inputs, const SurfacePoint& surface,
                    const Vec3& normal, const Vec3& geometric, const Rgb& albedo,
                    const Material* coat, Rng& rng, NearestPhotons& scratch) {
    const float max_radius_sq = inputs.max_radius * inputs.max_radius;
    const PhotonMapSettings& settings = inputs.settings;
    // Under a coat with final gathering, the global map holds every landing, direct light's and
    // caustics' included: it alone tells the light there (with the light sample and the caustic
    // map besides, both would count twice).
    if (settings.final_gather > 0 && coat != nullptr)
        return EstimateDiffuseRadiance(*inputs.maps->global, surface.position, normal, albedo,
                                       settings.nearest, max_radius_sq, settings.filter,
                                       inputs.features.ShadingNormals(), scratch);
    Rgb radiance = albedo / kPi *
                   SampleDirectIrradiance(*inputs.emitters, *inputs.tracer, surface.position,
                                          normal, coat, rng);
    if (!inputs.maps->caustic->Photons().empty())
        radiance += EstimateDiffuseRadiance(*inputs.maps->caustic, surface.position, normal, albedo,
                                            settings.nearest, max_radius_sq, settings.filter,
                                            inputs.features.ShadingNormals(), scratch);
    if (settings.final_gather == 0 || coat != nullptr)
        return radiance + EstimateDiffuseRadiance(*inputs.maps->global, surface.position, normal,
                                                  albedo, settings.nearest, max_radius_sq,
                                                  settings.filter, inputs.features.ShadingNormals(),
                                                  scratch);
    // Final gathering: cosine-weighted rays, each carrying albedo (f cos / pdf = rho).
    const Frame frame = FrameFromNormal(normal);
    const Vec3 origin =
        OffsetRayOrigin(surface.position, geometric, inputs.scene->bounds.Magnitude());
    Rgb gathered(0.0f);
    for (uint32_t i = 0; i < settings.final_gather; ++i) {
        const float u1 = rng.NextFloat();
        const float u2 = rng.NextFloat();
        const Vec3 direction = ToWorld(frame, SampleCosineHemisphere(u1, u2));
        if (!(Dot(direction, geometric) > 0)) continue;
        gathered += GatherRay(inputs, {origin, direction}, rng, scratch);
    }
    return radiance + albedo * gathered / static_cast<float>(settings.final_gather);
}

}  // namespace

Rgb PhotonMappingRadiance(const PhotonMappingInputs& inputs, Ray ray, Rng& rng) {
    thread_local NearestPhotons scratch;
    const Scene& scene = *inputs.scene;
    Rgb radiance(0.0f), throughput(1.0f);
    float refraction = 1.0f;  // the refractions' scales in throughput, out of Russian roulette
    float length = 0;
    for (int depth = 0; depth < DepthLimit(inputs.max_depth, kMaxCameraDepth); ++depth) {
        RayHit hit;
        if (!inputs.tracer->Intersect(ray, &hit)) {
            // The environment, seen directly or through specular and rough bounces.
            if (scene.environment)
                radiance += throughput * scene.environment->RadianceFrom(ray.origin, ray.direction);
            break;
        }
        length += hit.t;
        const SurfacePoint surface = scene.Surface(hit);
        std::optional<Material> shading;  // where a texture sets the roughness
        const Material& material = scene.ShadingMaterial(surface, shading);
        const Bsdf bsdf = BsdfOf(material);
        const bool front_facing = Dot(ray.direction, surface.geometric_normal) < 0;
        throughput *= SegmentTransmittance(material.absorption, material.outside_absorption,
                                           front_facing, hit.t);
        // Emission seen directly or through specular and rough bounces (no light map holds it).
        if (material.EmitsToward(front_facing)) radiance += throughput * scene.Emission(surface);
        // Punctual lights on a glossy surface, which no path finds (core/scene/glossy_lights.h).
        if (inputs.features.PunctualLights() && GlossyToPunctualLights(bsdf))
            radiance += throughput * PunctualLightOnGloss(*inputs.emitters, *inputs.tracer, surface,
                                                          bsdf, scene.BaseColor(surface),
                                                          front_facing, -ray.direction, rng);
        const CoatArrival arrival = material.type == MaterialType::kDiffuse
                                        ? ArriveAtCoat(bsdf, ray.direction, surface.shading_normal,
                                                       front_facing, rng.State())
                                        : CoatArrival{};
        if (material.type == MaterialType::kDiffuse && arrival.at_base) {
            const Rgb base_color = inputs.filter_angle > 0
                                       ? scene.BaseColor(surface, length * inputs.filter_angle)
                                       : scene.BaseColor(surface);
            // The light reflected on the path's side and, through a translucent surface, the
            // light let through from the other.
            const auto side = [&](bool toward, const Rgb& albedo) {
                const Vec3 normal = toward ? surface.shading_normal : -surface.shading_normal;
                const Vec3 geometric =
                    toward ? surface.geometric_normal : -surface.geometric_normal;
                return DiffuseRadiance(inputs, surface, normal, geometric, albedo,
                                       material.HasCoat() ? &material : nullptr, rng, scratch);
            };
            Rgb diffuse = side(front_facing, base_color);
            if (material.IsTranslucent()) diffuse += side(!front_facing, material.transmittance);
            return radiance + throughput * CoatedRadianceFactor(material, arrival) * diffuse;
        }
        const SpecularBounce bounce =
            material.type == MaterialType::kDiffuse
                ? arrival.reflected
                : ScatterNonDiffuse(bsdf, ray.direction, surface.shading_normal, front_facing,
                                    scene.BaseColor(surface), rng.State(), kCarriesRadiance);
        throughput *= bounce.weight;
        if (bounce.transmitted) refraction *= RefractionOf(bsdf, front_facing);
        if (depth >= kCameraRouletteDepth) {
            const float survive = std::min(1.0f, MaxComponent(throughput) / refraction);
            if (!(rng.NextFloat() < survive)) break;
            throughput /= survive;
        }
        if (IsBlack(throughput)) break;
        const Vec3 side = front_facing == bounce.transmitted ? -surface.geometric_normal
                                                             : surface.geometric_normal;
        ray = {OffsetRayOrigin(surface.position, side, scene.bounds.Magnitude()), bounce.direction};
    }
    return radiance;
}

}  // namespace pf
