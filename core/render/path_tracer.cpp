// Path tracing with next-event estimation, weighted against BSDF sampling by the power
// heuristic (Veach 1997, section 9.2.4).
#include "core/render/path_tracer.h"

#include <algorithm>
#include <optional>

#include "core/sampling/frame.h"
#include "core/sampling/sampling.h"
#include "core/scene/glossy_lights.h"
#include "core/scene/scattering.h"

namespace pf {
namespace {

// The light leaving a coated diffuse base toward a path that entered the coat carrying
// `entered` (core/shared/coat.h): at each visit to the base, light sampling through the coat
// (no MIS: the path out of the coat has no density to weigh it by, so emission it finds is
// left to light sampling), then a cosine bounce inside, which the coat lets out or turns back
// to the base. Sets `throughput` and `ray` to the path leaving the coat; false where it ends
// inside.
bool TraceCoatedBase(const PathInputs& inputs, const SurfacePoint& surface, bool front_facing,
                     const Material& material, const Rgb& base_color, const Rgb& entered, Rng& rng,
                     Rgb& radiance, Rgb& throughput, Ray& ray) {
    const gpu::Coat coat = CoatOf(material);
    Rgb inside = entered * CoatInside(coat);  // a layer's radiance inside is ior^2 times larger
    const Vec3 normal = front_facing ? surface.shading_normal : -surface.shading_normal;
    const Vec3 geometric = front_facing ? surface.geometric_normal : -surface.geometric_normal;
    const Frame frame = FrameFromNormal(normal);
    for (uint32_t visit = 0; visit < coat.depth; ++visit) {  // each with its chance to leave
        LightSample light;
        if (inputs.emitters->SampleDirect(surface.position, normal, rng, &light) &&
            !inputs.tracer->Occluded(light.shadow_ray)) {
            const float u1 = rng.NextFloat();
            const float u2 = rng.NextFloat();
            const float through =
                gpu::CoatTransmittance(coat, ToLocal(frame, light.direction), u1, u2);
            radiance += inside * base_color / kPi * light.radiance_over_pdf *
                        (Dot(light.direction, normal) * through);
        }
        // Russian roulette by albedo at each visit, as photons do.
        const float survive = std::min(1.0f, MaxComponent(base_color));
        if (!(rng.NextFloat() < survive)) return false;
        inside *= base_color / survive;
        const float u1 = rng.NextFloat();
        const float u2 = rng.NextFloat();
        const CoatLeaving leaving =
            LeaveCoatAt(coat, frame, SampleCosineHemisphere(u1, u2), rng.State());
        inside *= leaving.weight;
        if (IsBlack(inside)) return false;
        if (leaving.escaped) {
            if (!(Dot(leaving.direction, geometric) > 0)) return false;
            throughput = inside / CoatInside(coat);
            ray = {OffsetRayOrigin(surface.position, geometric, inputs.scene->bounds.Magnitude()),
                   leaving.direction};
            return true;
        }
    }
    return false;
}

// Instantiated for the scene's features, as the camera and photon passes are: without
// specular materials every surface is diffuse, without textures every base colour is the
// material's.
template <bool kSpecular, bool kTextures>
Rgb TracePathFor(const PathInputs& inputs, Ray ray, Rng& rng) {
    const Scene& scene = *inputs.scene;
    const float scale = scene.bounds.Magnitude();
    Rgb radiance(0.0f), throughput(1.0f);
    // The refractions' scales of radiance in throughput (RefractionOf), which Russian roulette
    // leaves out (pbrt-v4's etaScale): inside glass a path is worth following as much as outside.
    float refraction = 1.0f;
    // Emission found by a specular bounce (or seen directly) counts in full: light sampling
    // cannot find it. After a diffuse bounce it is weighed against light sampling.
    bool specular_bounce = true;
    bool coat_exit = false;  // the last bounce left a coated base: light sampling found its light
    float bsdf_pdf = 0;      // of the last diffuse bounce, solid angle
    Vec3 bounced_at;         // where that bounce left from
    float length = 0;        // travelled before the first diffuse hit, for the texture footprint
    bool diffuse_seen = false;
    for (int depth = 0; depth < kMaxPathDepth; ++depth) {
        RayHit hit;
        if (!inputs.tracer->Intersect(ray, &hit)) {
            // Escaped to the environment: after a diffuse or rough bounce weighed against
            // light sampling, which finds it too.
            const Emitters::Hit escaped = inputs.emitters->Escaped(ray.origin, ray.direction);
            const float weight = specular_bounce ? 1.0f
                                 : coat_exit     ? (escaped.pdf > 0 ? 0.0f : 1.0f)
                                                 : PowerHeuristic(bsdf_pdf, escaped.pdf);
            if (!IsBlack(escaped.radiance)) radiance += throughput * escaped.radiance * weight;
            break;
        }
        if (!diffuse_seen) length += hit.t;
        const SurfacePoint surface = scene.Surface(hit);
        std::optional<Material> shading;  // where a texture sets the roughness
        const Material& material = scene.ShadingMaterial(surface, shading);
        const Bsdf bsdf = BsdfOf(material);
        const bool front_facing = Dot(ray.direction, surface.geometric_normal) < 0;
        throughput *= SegmentTransmittance(material.absorption, material.outside_absorption,
                                           front_facing, hit.t);
        if (material.EmitsToward(front_facing)) {
            float weight = 1.0f;
            if (!specular_bounce) {
                const float light_pdf =
                    hit.instance == Instance::kNone
                        ? inputs.emitters->PdfDirect(hit.triangle, bounced_at, surface.position)
                        : 0.0f;
                // Out of a coat, light sampling alone counts what it can find.
                weight =
                    coat_exit ? (light_pdf > 0 ? 0.0f : 1.0f) : PowerHeuristic(bsdf_pdf, light_pdf);
            }
            radiance += throughput * scene.Emission(surface) * weight;
        }
        if (depth >= inputs.max_depth) break;
        Rgb base_color = material.base_color;
        if constexpr (kTextures)
            base_color = diffuse_seen || inputs.filter_angle <= 0
                             ? scene.BaseColor(surface)
                             : scene.BaseColor(surface, length * inputs.filter_angle);
        // Punctual lights on a glossy surface, which no path finds (core/scene/glossy_lights.h);
        // bare rough metal's light sampling below takes every light.
        if (kSpecular && inputs.features.PunctualLights() && GlossyToPunctualLights(bsdf) &&
            (material.type != MaterialType::kRoughConductor || material.HasCoat()))
            radiance +=
                throughput * PunctualLightOnGloss(*inputs.emitters, *inputs.tracer, surface, bsdf,
                                                  base_color, front_facing, -ray.direction, rng);
        const CoatArrival arrival = kSpecular && material.type == MaterialType::kDiffuse
                                        ? ArriveAtCoat(bsdf, ray.direction, surface.shading_normal,
                                                       front_facing, rng.State())
                                        : CoatArrival{};
        if ((!kSpecular || material.type == MaterialType::kDiffuse) && !material.HasCoat()) {
            diffuse_seen = true;
            // Light sampled on the path's side and, through a translucent surface, on the other
            // too; the bounce on one of them, chosen with its probability p (ChooseDiffuseSide),
            // so the bounce's density there is p cos / pi, against which each side's light
            // sample is weighed.
            const float through = kSpecular && material.IsTranslucent()
                                      ? gpu::TransmitProbability(base_color, material.transmittance)
                                      : 0.0f;
            for (const bool other : {false, true}) {
                if (other && !(through > 0)) break;
                const Vec3 facing =
                    front_facing != other ? surface.shading_normal : -surface.shading_normal;
                const Rgb& albedo = other ? material.transmittance : base_color;
                const float chosen = other ? through : 1.0f - through;
                LightSample light;
                if (inputs.emitters->SampleDirect(surface.position, facing, rng, &light) &&
                    !inputs.tracer->Occluded(light.shadow_ray)) {
                    const float cosine = Dot(light.direction, facing);
                    const float weight =
                        light.pdf > 0 ? PowerHeuristic(light.pdf, chosen * cosine / kPi) : 1.0f;
                    radiance +=
                        throughput * (albedo / kPi) * light.radiance_over_pdf * (cosine * weight);
                }
            }
            const DiffuseSide side = kSpecular ? ChooseDiffuseSide(bsdf, base_color, rng.State())
                                               : DiffuseSide{false, base_color};
            const bool toward = front_facing != side.through;
            const Vec3 normal = toward ? surface.shading_normal : -surface.shading_normal;
            const Vec3 geometric = toward ? surface.geometric_normal : -surface.geometric_normal;
            const float u1 = rng.NextFloat();
            const float u2 = rng.NextFloat();
            const Vec3 local = SampleCosineHemisphere(u1, u2);
            const Vec3 direction = ToWorld(FrameFromNormal(normal), local);
            if (!(Dot(direction, geometric) > 0)) break;  // the shading normal pointed it inside
            throughput *= side.albedo;  // f cos / pdf = (rho / pi) cos / (p cos / pi), / p in it
            bsdf_pdf = (side.through ? through : 1.0f - through) * local.z / kPi;
            bounced_at = surface.position;
            specular_bounce = false;
            coat_exit = false;
            ray = {OffsetRayOrigin(surface.position, geometric, scale), direction};
        } else if (material.type == MaterialType::kDiffuse && arrival.at_base) {
            diffuse_seen = true;
            if (!TraceCoatedBase(inputs, surface, front_facing, material, base_color,
                                 throughput * arrival.weight, rng, radiance, throughput, ray))
                break;
            // Where light sampling looked from: an emitter the path meets next is the one it
            // could have found, its density from here (PdfDirect) says so.
            bounced_at = surface.position;
            specular_bounce = false;
            coat_exit = true;
        } else if (material.type == MaterialType::kDiffuse) {
            // The coat's reflection, found by its own sampling alone, as specular bounces are.
            throughput *= arrival.reflected.weight;
            specular_bounce = true;
            coat_exit = false;
            ray = {OffsetRayOrigin(
                       surface.position,
                       front_facing ? surface.geometric_normal : -surface.geometric_normal, scale),
                   arrival.reflected.direction};
        } else if (material.type == MaterialType::kRoughConductor && !material.HasCoat()) {
            // Light sampling weighed against the GGX lobe's own sampling, as at diffuse surfaces.
            const Vec3 normal = front_facing ? surface.shading_normal : -surface.shading_normal;
            const Vec3 wo = -ray.direction;
            LightSample light;
            if (inputs.emitters->SampleDirect(surface.position, normal, rng, &light) &&
                !inputs.tracer->Occluded(light.shadow_ray)) {
                const RoughReflection f =
                    EvaluateRoughConductor(bsdf, base_color, normal, wo, light.direction);
                const float weight = light.pdf > 0 ? PowerHeuristic(light.pdf, f.pdf) : 1.0f;
                radiance += throughput * f.value * light.radiance_over_pdf * weight;
            }
            const SpecularBounce bounce =
                ScatterNonDiffuse(bsdf, ray.direction, surface.shading_normal, front_facing,
                                  base_color, rng.State(), kCarriesRadiance);
            throughput *= bounce.weight;
            bsdf_pdf = EvaluateRoughConductor(bsdf, base_color, normal, wo, bounce.direction).pdf;
            bounced_at = surface.position;
            specular_bounce = false;
            coat_exit = false;
            ray = {OffsetRayOrigin(
                       surface.position,
                       front_facing ? surface.geometric_normal : -surface.geometric_normal, scale),
                   bounce.direction};
        } else {
            // Specular surfaces, and rough glass, whose light is found by its own sampling alone.
            const SpecularBounce bounce =
                ScatterNonDiffuse(bsdf, ray.direction, surface.shading_normal, front_facing,
                                  base_color, rng.State(), kCarriesRadiance);
            throughput *= bounce.weight;
            if (bounce.transmitted) refraction *= RefractionOf(bsdf, front_facing);
            specular_bounce = true;
            coat_exit = false;
            const Vec3 side = front_facing == bounce.transmitted ? -surface.geometric_normal
                                                                 : surface.geometric_normal;
            ray = {OffsetRayOrigin(surface.position, side, scale), bounce.direction};
        }
        if (depth >= kPathRouletteDepth) {
            const float survive = std::min(1.0f, MaxComponent(throughput) / refraction);
            if (!(rng.NextFloat() < survive)) break;
            throughput /= survive;
        }
        if (IsBlack(throughput)) break;
    }
    return radiance;
}

}  // namespace

Rgb TracePath(const PathInputs& inputs, Ray ray, Rng& rng) {
    const SceneFeatures& features = inputs.features;
    if (features.GeneralSurfaces())
        return features.VaryingBaseColor() ? TracePathFor<true, true>(inputs, ray, rng)
                                           : TracePathFor<true, false>(inputs, ray, rng);
    return features.VaryingBaseColor() ? TracePathFor<false, true>(inputs, ray, rng)
                                       : TracePathFor<false, false>(inputs, ray, rng);
}

}  // namespace pf
