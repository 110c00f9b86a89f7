// Path tracing with next-event estimation, weighted against BSDF sampling by the power
// heuristic (Veach 1997, section 9.2.4).
#include "core/render/path_tracer.h"

#include <algorithm>

#include "core/sampling/frame.h"
#include "core/sampling/sampling.h"
#include "core/scene/glossy.h"

namespace pf {
namespace {

// Instantiated for the scene's features, as the camera and photon passes are: without
// specular materials every surface is diffuse, without textures every base colour is the
// material's.
template <bool kSpecular, bool kTextures>
Rgb TracePathFor(const PathInputs& inputs, Ray ray, Rng& rng) {
    const Scene& scene = *inputs.scene;
    const float scale = scene.bounds.Magnitude();
    Rgb radiance(0.0f), throughput(1.0f);
    // Emission found by a specular bounce (or seen directly) counts in full: light sampling
    // cannot find it. After a diffuse bounce it is weighed against light sampling.
    bool specular_bounce = true;
    float bsdf_pdf = 0;  // of the last diffuse bounce, solid angle
    Vec3 bounced_at;     // where that bounce left from
    float length = 0;    // travelled before the first diffuse hit, for the texture footprint
    bool diffuse_seen = false;
    for (int depth = 0; depth < kMaxPathDepth; ++depth) {
        RayHit hit;
        if (!inputs.tracer->Intersect(ray, &hit)) {
            // Escaped to the environment: after a diffuse or rough bounce weighed against
            // light sampling, which finds it too.
            const Emitters::Hit escaped = inputs.emitters->Escaped(ray.origin, ray.direction);
            if (!IsBlack(escaped.radiance))
                radiance += throughput * escaped.radiance *
                            (specular_bounce ? 1.0f : PowerHeuristic(bsdf_pdf, escaped.pdf));
            break;
        }
        if (!diffuse_seen) length += hit.t;
        const SurfacePoint surface = scene.Surface(hit);
        const Material& material = scene.materials[surface.material];
        const bool front_facing = Dot(ray.direction, surface.geometric_normal) < 0;
        if (material.EmitsToward(front_facing)) {
            float weight = 1.0f;
            if (!specular_bounce) {
                const float light_pdf =
                    hit.instance == Instance::kNone
                        ? inputs.emitters->PdfDirect(hit.triangle, bounced_at, surface.position)
                        : 0.0f;
                weight = PowerHeuristic(bsdf_pdf, light_pdf);
            }
            radiance += throughput * scene.Emission(surface) * weight;
        }
        if (depth >= inputs.max_depth) break;
        Rgb base_color = material.base_color;
        if constexpr (kTextures)
            base_color = diffuse_seen || inputs.filter_angle <= 0
                             ? scene.BaseColor(surface)
                             : scene.BaseColor(surface, length * inputs.filter_angle);
        if (!kSpecular || material.type == MaterialType::kDiffuse) {
            diffuse_seen = true;
            const Vec3 normal = front_facing ? surface.shading_normal : -surface.shading_normal;
            const Vec3 geometric =
                front_facing ? surface.geometric_normal : -surface.geometric_normal;
            const Rgb bsdf = base_color / kPi;
            LightSample light;
            if (inputs.emitters->SampleDirect(surface.position, normal, rng, &light) &&
                !inputs.tracer->Occluded(light.shadow_ray)) {
                const float cosine = Dot(light.direction, normal);
                const float weight = light.pdf > 0 ? PowerHeuristic(light.pdf, cosine / kPi) : 1.0f;
                radiance += throughput * bsdf * light.radiance_over_pdf * (cosine * weight);
            }
            const float u1 = rng.NextFloat();
            const float u2 = rng.NextFloat();
            const Vec3 local = SampleCosineHemisphere(u1, u2);
            const Vec3 direction = Frame::FromNormal(normal).ToWorld(local);
            if (!(Dot(direction, geometric) > 0)) break;  // the shading normal pointed it inside
            throughput *= base_color;  // f cos / pdf = (rho / pi) cos / (cos / pi)
            bsdf_pdf = local.z / kPi;
            bounced_at = surface.position;
            specular_bounce = false;
            ray = {OffsetRayOrigin(surface.position, geometric, scale), direction};
        } else if (material.type == MaterialType::kRoughConductor) {
            // Light sampling weighed against the GGX lobe's own sampling, as at diffuse surfaces.
            const Vec3 normal = front_facing ? surface.shading_normal : -surface.shading_normal;
            const Vec3 wo = -ray.direction;
            LightSample light;
            if (inputs.emitters->SampleDirect(surface.position, normal, rng, &light) &&
                !inputs.tracer->Occluded(light.shadow_ray)) {
                const RoughReflection f =
                    EvaluateRoughConductor(material, base_color, normal, wo, light.direction);
                const float weight = light.pdf > 0 ? PowerHeuristic(light.pdf, f.pdf) : 1.0f;
                radiance += throughput * f.value * light.radiance_over_pdf * weight;
            }
            const SpecularBounce bounce = ScatterNonDiffuse(
                material, ray.direction, surface.shading_normal, front_facing, base_color, rng);
            throughput *= bounce.weight;
            bsdf_pdf =
                EvaluateRoughConductor(material, base_color, normal, wo, bounce.direction).pdf;
            bounced_at = surface.position;
            specular_bounce = false;
            ray = {OffsetRayOrigin(
                       surface.position,
                       front_facing ? surface.geometric_normal : -surface.geometric_normal, scale),
                   bounce.direction};
        } else {
            // Specular surfaces, and rough glass, whose light is found by its own sampling alone.
            const SpecularBounce bounce = ScatterNonDiffuse(
                material, ray.direction, surface.shading_normal, front_facing, base_color, rng);
            throughput *= bounce.weight;
            specular_bounce = true;
            const Vec3 side = front_facing == bounce.transmitted ? -surface.geometric_normal
                                                                 : surface.geometric_normal;
            ray = {OffsetRayOrigin(surface.position, side, scale), bounce.direction};
        }
        if (depth >= kPathRouletteDepth) {
            const float survive = std::min(1.0f, MaxComponent(throughput));
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
    if (features.Specular())
        return features.textures ? TracePathFor<true, true>(inputs, ray, rng)
                                 : TracePathFor<true, false>(inputs, ray, rng);
    return features.textures ? TracePathFor<false, true>(inputs, ray, rng)
                             : TracePathFor<false, false>(inputs, ray, rng);
}

}  // namespace pf
