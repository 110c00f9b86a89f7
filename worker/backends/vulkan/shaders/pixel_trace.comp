#version 460
// The integrators that render pixels, a thread a pixel (the megakernel design: one kernel
// follows each of its camera samples' whole path): the path tracer (core/render/path_tracer.cpp on the
// CPU: next-event estimation weighed against BSDF sampling by the power heuristic at diffuse
// and rough-metal vertices, coats walked as TraceCoatedBase does) or, specialised with
// kPhotonMapping, classic photon mapping's rendering pass (core/pm/photon_mapping.cpp: direct
// light, the caustic map, and the global map read there or where final-gather rays land,
// photon_map.glsl). Camera rays come from the host (core/camera/pixel_sample.h), one a sample;
// each sample draws from its own stream, as on the CPU (core/render/pixel_pass.h), in the CPU's
// order; its radiance times its filter weight is written in sample order (into `direct`), w set where it came
// out NaN or Inf, and the host sums each pixel's in order. Textures are looked up at a point
// (the CPU averages the first diffuse hit's over the sample's cone: the pixel's samples
// integrate them either way).
#include "common.glsl"
#include "trace.glsl"
#include "lights.glsl"
#include "specular.glsl"
#include "direct.glsl"
#include "photon_map.glsl"

layout(local_size_x = kWorkgroupSize) in;

layout(constant_id = kSpecPhotonMapping) const bool kPhotonMapping = false;

layout(std430, binding = kBindingCameraRays) readonly buffer CameraRays { GpuCameraRay camera_rays[]; };

// Whether a diffuse material lets light through to its other side (Material::IsTranslucent).
bool Translucent(GpuMaterial material) {
    return kHasTranslucency && MaxComponent(material.transmittance.xyz) > 0.0;
}

bool Coated(GpuMaterial material) { return kHasCoats && material.coat.x > 0.0; }

// Where a path meets a coated diffuse surface (ArriveAtCoat): it reaches the base, taking
// `weight`, or the coat reflects it as `reflected`. Uncoated: the base, weight 1.
bool ArriveAtCoat(GpuMaterial material, Surface surface, vec3 d, bool front_facing, inout Pcg32 rng,
                  out float weight, out SpecularBounce reflected) {
    weight = 1.0;
    reflected = SpecularBounce(d, vec3(0.0), false);
    if (!Coated(material)) return true;
    const mat3 frame = FrameFromNormal(front_facing ? surface.shading_normal : -surface.shading_normal);
    const float u_branch = Pcg32NextFloat(rng), u1 = Pcg32NextFloat(rng), u2 = Pcg32NextFloat(rng);
    vec3 wi;
    const vec3 entered = EnterCoat(CoatOf(material), -d * frame, u_branch, u1, u2, wi);
    if (wi.z < 0.0) {
        weight = entered.x;  // grey on the way in
        return true;
    }
    reflected = SpecularBounce(frame * wi, entered, false);
    return false;
}

// ChooseDiffuseSide: whether the path goes through (a translucent surface's other side), and the
// albedo it then carries.
bool ChooseDiffuseSide(GpuMaterial material, vec3 base_color, inout Pcg32 rng, out vec3 albedo, out float through) {
    through = 0.0;
    albedo = base_color;
    if (!Translucent(material)) return false;
    through = TransmitProbability(base_color, material.transmittance.xyz);
    if (Pcg32NextFloat(rng) < through) {
        albedo = material.transmittance.xyz / through;
        return true;
    }
    albedo = base_color / (1.0 - through);
    return false;
}

// A light sample from p, normal n, its numbers from rng (Emitters::SampleDirect), and whether it
// is unoccluded.
bool SampleVisibleLight(vec3 p, vec3 n, inout Pcg32 rng, out LightSample light) {
    const float pick = Pcg32NextFloat(rng), u1 = Pcg32NextFloat(rng), u2 = Pcg32NextFloat(rng);
    RayHit unused;
    return SampleLightFrom(p, n, pick, vec2(u1, u2), false, light) &&
           !TraceRay(light.origin, light.direction, light.distance, true, unused);
}

// ---- The path tracer ----

// The light leaving a coated diffuse base toward a path that entered the coat carrying
// `entered` (TraceCoatedBase): light sampling through the coat at each visit, then a cosine
// bounce inside that the coat lets out or turns back. Sets the path leaving the coat; false
// where it ends inside.
bool TraceCoatedBase(Surface surface, bool front_facing, GpuMaterial material, vec3 entered, inout Pcg32 rng,
                     inout vec3 radiance, out vec3 throughput, out vec3 origin, out vec3 direction) {
    const Coat coat = CoatOf(material);
    vec3 inside = entered * CoatInside(coat);  // a layer's radiance inside is ior^2 times larger
    const vec3 normal = front_facing ? surface.shading_normal : -surface.shading_normal;
    const vec3 geometric = front_facing ? surface.geometric_normal : -surface.geometric_normal;
    const mat3 frame = FrameFromNormal(normal);
    const vec3 base_color = surface.base_color;
    throughput = vec3(0);
    origin = surface.position;
    direction = normal;
    for (int returns = 0; returns <= kMaxCoatReturns; ++returns) {
        LightSample light;
        if (SampleVisibleLight(surface.position, normal, rng, light)) {
            const float u1 = Pcg32NextFloat(rng), u2 = Pcg32NextFloat(rng);
            const float through = CoatTransmittance(coat, light.direction * frame, u1, u2);
            radiance += inside * base_color / kPi * light.radiance_over_pdf * (dot(light.direction, normal) * through);
        }
        const float survive = min(1.0, MaxComponent(base_color));
        if (!(Pcg32NextFloat(rng) < survive)) return false;
        inside *= base_color / survive;
        const float u1 = Pcg32NextFloat(rng), u2 = Pcg32NextFloat(rng);
        const vec3 up = SampleCosineHemisphere(u1, u2);
        const float u_branch = Pcg32NextFloat(rng), v1 = Pcg32NextFloat(rng), v2 = Pcg32NextFloat(rng);
        vec3 wi;
        inside *= LeaveCoat(coat, up, u_branch, v1, v2, wi);
        if (!(MaxComponent(inside) > 0.0)) return false;
        if (wi.z > 0.0) {
            direction = frame * wi;
            if (!(dot(direction, geometric) > 0)) return false;
            throughput = inside / CoatInside(coat);
            origin = OffsetRayOrigin(surface.position, geometric);
            return true;
        }
    }
    return false;
}

vec3 TracePath(vec3 origin, vec3 direction, inout Pcg32 rng) {
    vec3 radiance = vec3(0), throughput = vec3(1);
    // Emission found by a specular bounce (or seen directly) counts in full; after a diffuse or
    // rough bounce it is weighed against light sampling, which finds it too.
    bool specular_bounce = true;
    bool coat_exit = false;  // the last bounce left a coated base: light sampling found its light
    float bsdf_pdf = 0;      // of the last diffuse or rough bounce, solid angle
    vec3 bounced_at = origin;
    for (uint depth = 0; depth <= pixel_job.max_depth; ++depth) {
        RayHit hit;
        if (!TraceRay(origin, direction, kInfinity, false, hit)) {
            if (kHasEnvironment) {
                float pdf;
                const vec3 escaped = EscapedRay(origin, direction, pdf);
                const float weight = specular_bounce ? 1.0 : coat_exit ? (pdf > 0 ? 0.0 : 1.0) : PowerHeuristic(bsdf_pdf, pdf);
                if (MaxComponent(escaped) > 0.0) radiance += throughput * escaped * weight;
            }
            break;
        }
        const Surface surface = SurfaceAt(hit);
        const GpuMaterial material = ShadingMaterial(surface);
        const bool front_facing = dot(direction, surface.geometric_normal) < 0;
        if (kHasAbsorption && !front_facing) throughput *= BeerLambert(material.absorption.xyz, hit.t);
        if (kHasTriangleLights) {
            float light_pdf;
            const vec3 emitted = HitEmitter(hit, specular_bounce ? origin : bounced_at, surface.position, light_pdf);
            if (MaxComponent(emitted) > 0.0) {
                float weight = 1.0;
                if (!specular_bounce)
                    weight = coat_exit ? (light_pdf > 0 ? 0.0 : 1.0) : PowerHeuristic(bsdf_pdf, light_pdf);
                radiance += throughput * emitted * weight;
            }
        }
        if (depth >= pixel_job.max_depth) break;
        const vec3 base_color = surface.base_color;
        float arrival_weight;
        SpecularBounce reflected;
        const bool at_base = material.type != kMaterialDiffuse ||
                             ArriveAtCoat(material, surface, direction, front_facing, rng, arrival_weight, reflected);
        if (material.type == kMaterialDiffuse && !Coated(material)) {
            // Light sampled on the path's side and, through a translucent surface, on the other;
            // the bounce on one of them, chosen with its probability, against whose density
            // each side's light sample is weighed.
            const float through = Translucent(material) ? TransmitProbability(base_color, material.transmittance.xyz) : 0.0;
            for (int other = 0; other < 2; ++other) {
                if (other == 1 && !(through > 0)) break;
                const vec3 facing = front_facing != (other == 1) ? surface.shading_normal : -surface.shading_normal;
                const vec3 albedo = other == 1 ? material.transmittance.xyz : base_color;
                const float chosen = other == 1 ? through : 1.0 - through;
                LightSample light;
                if (SampleVisibleLight(surface.position, facing, rng, light)) {
                    const float cosine = dot(light.direction, facing);
                    const float weight = light.pdf > 0 ? PowerHeuristic(light.pdf, chosen * cosine / kPi) : 1.0;
                    radiance += throughput * (albedo / kPi) * light.radiance_over_pdf * (cosine * weight);
                }
            }
            vec3 albedo;
            float unused;
            const bool side_through = ChooseDiffuseSide(material, base_color, rng, albedo, unused);
            const bool toward = front_facing != side_through;
            const vec3 normal = toward ? surface.shading_normal : -surface.shading_normal;
            const vec3 geometric = toward ? surface.geometric_normal : -surface.geometric_normal;
            const float u1 = Pcg32NextFloat(rng), u2 = Pcg32NextFloat(rng);
            const vec3 local = SampleCosineHemisphere(u1, u2);
            direction = FrameFromNormal(normal) * local;
            if (!(dot(direction, geometric) > 0)) break;  // the shading normal pointed it inside
            throughput *= albedo;
            bsdf_pdf = (side_through ? through : 1.0 - through) * local.z / kPi;
            bounced_at = surface.position;
            specular_bounce = false;
            coat_exit = false;
            origin = OffsetRayOrigin(surface.position, geometric);
        } else if (material.type == kMaterialDiffuse && at_base) {
            if (!TraceCoatedBase(surface, front_facing, material, throughput * arrival_weight, rng, radiance, throughput,
                                 origin, direction))
                break;
            bounced_at = surface.position;
            specular_bounce = false;
            coat_exit = true;
        } else if (material.type == kMaterialDiffuse) {
            // The coat's reflection, found by its own sampling alone, as specular bounces are.
            throughput *= reflected.weight;
            specular_bounce = true;
            coat_exit = false;
            origin = OffsetRayOrigin(surface.position, front_facing ? surface.geometric_normal : -surface.geometric_normal);
            direction = reflected.direction;
        } else if (kHasRoughConductor && material.type == kMaterialRoughConductor && !Coated(material)) {
            // Light sampling weighed against the GGX lobe's own sampling.
            const vec3 normal = front_facing ? surface.shading_normal : -surface.shading_normal;
            const vec3 wo = -direction;
            LightSample light;
            if (SampleVisibleLight(surface.position, normal, rng, light)) {
                vec3 value;
                const float pdf = EvaluateRoughConductor(material, base_color, normal, wo, light.direction, value);
                const float weight = light.pdf > 0 ? PowerHeuristic(light.pdf, pdf) : 1.0;
                radiance += throughput * value * light.radiance_over_pdf * weight;
            }
            const SpecularBounce bounce = ScatterNonDiffuse(material, surface, direction, front_facing, rng);
            throughput *= bounce.weight;
            vec3 unused;
            bsdf_pdf = EvaluateRoughConductor(material, base_color, normal, wo, bounce.direction, unused);
            bounced_at = surface.position;
            specular_bounce = false;
            coat_exit = false;
            origin = OffsetRayOrigin(surface.position, front_facing ? surface.geometric_normal : -surface.geometric_normal);
            direction = bounce.direction;
        } else {
            // Specular surfaces, and rough glass, whose light is found by its own sampling alone.
            const SpecularBounce bounce = ScatterNonDiffuse(material, surface, direction, front_facing, rng);
            throughput *= bounce.weight;
            specular_bounce = true;
            coat_exit = false;
            origin = OffsetRayOrigin(surface.position, front_facing == bounce.transmitted ? -surface.geometric_normal
                                                                                          : surface.geometric_normal);
            direction = bounce.direction;
        }
        if (depth >= pixel_job.roulette_depth) {
            const float survive = min(1.0, MaxComponent(throughput));
            if (!(Pcg32NextFloat(rng) < survive)) break;
            throughput /= survive;
        }
        if (all(equal(throughput, vec3(0)))) break;
    }
    return radiance;
}

// ---- Classic photon mapping ----

// The global map's estimate where a gather ray from `origin` lands on a diffuse surface after
// specular and rough bounces (FollowToDiffuse), times the weight of the way there.
vec3 GatherRay(vec3 origin, vec3 direction, inout Pcg32 rng) {
    vec3 weight = vec3(1);
    for (uint depth = 0; depth < pixel_job.gather_depth; ++depth) {
        RayHit hit;
        if (!TraceRay(origin, direction, kInfinity, false, hit)) return vec3(0);
        const Surface surface = SurfaceAt(hit);
        const GpuMaterial material = ShadingMaterial(surface);
        const bool front_facing = dot(direction, surface.geometric_normal) < 0;
        if (kHasAbsorption && !front_facing) weight *= BeerLambert(material.absorption.xyz, hit.t);
        float arrival_weight;
        SpecularBounce reflected;
        const bool at_base = material.type != kMaterialDiffuse ||
                             ArriveAtCoat(material, surface, direction, front_facing, rng, arrival_weight, reflected);
        if (material.type == kMaterialDiffuse && at_base) {
            vec3 albedo;
            float unused;
            const bool through = ChooseDiffuseSide(material, surface.base_color, rng, albedo, unused);
            const vec3 normal = front_facing != through ? surface.shading_normal : -surface.shading_normal;
            if (Coated(material)) weight *= arrival_weight * CoatInside(CoatOf(material));
            return weight * EstimateDiffuseRadiance(pixel_job.global_map, surface.position, normal, albedo);
        }
        const SpecularBounce bounce = material.type == kMaterialDiffuse
                                          ? reflected
                                          : ScatterNonDiffuse(material, surface, direction, front_facing, rng);
        weight *= bounce.weight;
        if (all(equal(weight, vec3(0)))) return vec3(0);
        origin = OffsetRayOrigin(surface.position, front_facing == bounce.transmitted ? -surface.geometric_normal
                                                                                      : surface.geometric_normal);
        direction = bounce.direction;
    }
    return vec3(0);
}

// The light leaving diffuse point p (normal toward the path, albedo) under the coat of material
// `coat` (or kNoCoat), as DiffuseRadiance in core/pm/photon_mapping.cpp: under a coat with final
// gathering the global map alone (it holds every landing); otherwise direct light, the caustic
// map, and the global map read here or where gather rays land.
vec3 DiffuseRadiance(vec3 p, vec3 normal, vec3 geometric, vec3 albedo, uint coat, inout Pcg32 rng) {
    if (pixel_job.final_gather > 0 && coat != kNoCoat)
        return EstimateDiffuseRadiance(pixel_job.global_map, p, normal, albedo);
    const float pick = Pcg32NextFloat(rng);
    vec2 light_u, cosine_u = vec2(0);
    light_u.x = Pcg32NextFloat(rng);
    light_u.y = Pcg32NextFloat(rng);
    if (kLightsFoundByRays) {
        cosine_u.x = Pcg32NextFloat(rng);
        cosine_u.y = Pcg32NextFloat(rng);
    }
    vec3 radiance = albedo / kPi * DirectIrradiance(p, normal, coat, pick, light_u, false, cosine_u, rng);
    radiance += EstimateDiffuseRadiance(pixel_job.caustic_map, p, normal, albedo);
    if (pixel_job.final_gather == 0 || coat != kNoCoat)
        return radiance + EstimateDiffuseRadiance(pixel_job.global_map, p, normal, albedo);
    // Final gathering: cosine-weighted rays, each carrying albedo (f cos / pdf = rho).
    const mat3 frame = FrameFromNormal(normal);
    const vec3 origin = OffsetRayOrigin(p, geometric);
    vec3 gathered = vec3(0);
    for (uint i = 0; i < pixel_job.final_gather; ++i) {
        const float u1 = Pcg32NextFloat(rng), u2 = Pcg32NextFloat(rng);
        const vec3 direction = frame * SampleCosineHemisphere(u1, u2);
        if (!(dot(direction, geometric) > 0)) continue;
        gathered += GatherRay(origin, direction, rng);
    }
    return radiance + albedo * gathered / float(pixel_job.final_gather);
}

vec3 PhotonMappingRadiance(vec3 origin, vec3 direction, inout Pcg32 rng) {
    vec3 radiance = vec3(0), throughput = vec3(1);
    for (uint depth = 0; depth < pixel_job.max_depth; ++depth) {
        RayHit hit;
        if (!TraceRay(origin, direction, kInfinity, false, hit)) {
            // The environment, seen directly or through specular and rough bounces.
            if (kHasEnvironment) {
                float unused;
                radiance += throughput * EscapedRay(origin, direction, unused);
            }
            break;
        }
        const Surface surface = SurfaceAt(hit);
        const GpuMaterial material = ShadingMaterial(surface);
        const bool front_facing = dot(direction, surface.geometric_normal) < 0;
        if (kHasAbsorption && !front_facing) throughput *= BeerLambert(material.absorption.xyz, hit.t);
        // Emission seen directly or through specular and rough bounces (no light map holds it).
        if (kHasTriangleLights) {
            float unused;
            radiance += throughput * HitEmitter(hit, origin, surface.position, unused);
        }
        float arrival_weight;
        SpecularBounce reflected;
        const bool at_base = material.type != kMaterialDiffuse ||
                             ArriveAtCoat(material, surface, direction, front_facing, rng, arrival_weight, reflected);
        if (material.type == kMaterialDiffuse && at_base) {
            const uint coat = Coated(material) ? surface.material : kNoCoat;
            // The light reflected on the path's side and, through a translucent surface, the
            // light let through from the other.
            vec3 diffuse = DiffuseRadiance(surface.position, front_facing ? surface.shading_normal : -surface.shading_normal,
                                           front_facing ? surface.geometric_normal : -surface.geometric_normal,
                                           surface.base_color, coat, rng);
            if (Translucent(material))
                diffuse += DiffuseRadiance(surface.position, front_facing ? -surface.shading_normal : surface.shading_normal,
                                           front_facing ? -surface.geometric_normal : surface.geometric_normal,
                                           material.transmittance.xyz, coat, rng);
            const float factor = Coated(material) ? arrival_weight * CoatInside(CoatOf(material)) : 1.0;
            return radiance + throughput * factor * diffuse;
        }
        const SpecularBounce bounce = material.type == kMaterialDiffuse
                                          ? reflected
                                          : ScatterNonDiffuse(material, surface, direction, front_facing, rng);
        throughput *= bounce.weight;
        if (depth >= pixel_job.roulette_depth) {
            const float survive = min(1.0, MaxComponent(throughput));
            if (!(Pcg32NextFloat(rng) < survive)) break;
            throughput /= survive;
        }
        if (all(equal(throughput, vec3(0)))) break;
        origin = OffsetRayOrigin(surface.position, front_facing == bounce.transmitted ? -surface.geometric_normal
                                                                                      : surface.geometric_normal);
        direction = bounce.direction;
    }
    return radiance;
}

void main() {
    const uint pixel = params.first + gl_GlobalInvocationID.x;  // of the batch
    if (pixel >= params.end) return;
    // The pixel's samples one after another from its stream (RunPixelBatches), summed in order,
    // those that come out NaN or Inf counted and left out.
    const uint spp = pixel_job.samples_per_pixel;
    Pcg32 rng = Pcg32Seeded(FamilySeed(params.seed_prefix, uint64_t(params.direct_begin + pixel)));
    vec3 sum = vec3(0);
    uint discarded = 0;
    for (uint s = 0; s < spp; ++s) {
        const GpuCameraRay ray = camera_rays[pixel * spp + s];
        const vec3 radiance = kPhotonMapping ? PhotonMappingRadiance(ray.origin.xyz, ray.direction.xyz, rng)
                                             : TracePath(ray.origin.xyz, ray.direction.xyz, rng);
        const vec3 value = radiance * ray.origin.w;
        if (IsFinite(value)) sum += value;
        else ++discarded;
    }
    direct[pixel] = vec4(sum * (1.0 / float(spp)), float(discarded));
}
