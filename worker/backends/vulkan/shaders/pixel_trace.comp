#version 460
// The integrators that render pixels, a thread a pixel (the megakernel design: one kernel
// follows each of its camera samples' whole path): the path tracer (path_vertex.glsl's vertices
// one after another; path_wavefront.comp runs the same vertices as a wavefront) or,
// specialised with kPhotonMapping, classic photon mapping's rendering pass
// (core/pm/photon_mapping.cpp: direct light, the caustic map, and the global map read there or
// where final-gather rays land, photon_map.glsl). Camera rays come from the host
// (core/camera/pixel_sample.h), one a sample; a pixel's samples draw from its stream in order,
// as on the CPU (core/render/pixel_pass.h); their radiance times their filter weight is summed
// in order and the pixel's mean written (into `direct`), w counting the samples that came out
// NaN or Inf and were left out. Textures are looked up at a point (the CPU averages the first
// diffuse hit's over the sample's cone: the pixel's samples integrate them either way).
#include "common.glsl"
#include "trace.glsl"
#include "lights.glsl"
#include "bsdf.glsl"
#include "direct.glsl"
#include "photon_map.glsl"
#include "path_vertex.glsl"

layout(local_size_x = kWorkgroupSize) in;

layout(constant_id = kSpecPhotonMapping) const bool kPhotonMapping = false;

layout(std430, binding = kBindingCameraRays) readonly buffer CameraRays { GpuCameraRay camera_rays[]; };

// The path tracer: its vertices (path_vertex.glsl) one after another.
vec3 TracePath(vec3 origin, vec3 direction, inout Pcg32 rng) {
    PathState path = BeginPath(origin, direction);
    for (;;) {
        RayHit hit;
        const bool found = TraceRay(path.origin, path.direction, kInfinity, false, hit);
        if (!PathVertex(path, found, hit, rng)) return path.radiance;
    }
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
        const Bsdf bsdf = BsdfOf(material);
        const bool front_facing = dot(direction, surface.geometric_normal) < 0;
        if (kHasAbsorption)
            weight *= SegmentTransmittance(material.absorption.xyz, material.outside_absorption.xyz, front_facing, hit.t);
        const CoatArrival arrival = material.type == kMaterialDiffuse
                                        ? ArriveAtCoat(bsdf, direction, surface.shading_normal, front_facing, rng)
                                        : CoatArrival(false, 0.0, SpecularBounce(direction, vec3(0.0), false));
        if (arrival.at_base) {
            const DiffuseSide side = ChooseDiffuseSide(bsdf, surface.base_color, rng);
            const vec3 normal = front_facing != side.through ? surface.shading_normal : -surface.shading_normal;
            if (IsCoated(bsdf)) weight *= arrival.weight * CoatInside(bsdf.coat);
            return weight * EstimateDiffuseRadiance(pixel_job.global_map, surface.position, normal, side.albedo);
        }
        const SpecularBounce bounce =
            material.type == kMaterialDiffuse
                ? arrival.reflected
                : ScatterNonDiffuse(bsdf, direction, surface.shading_normal, front_facing, surface.base_color, rng,
                                    kCarriesRadiance);
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
    const Frame frame = FrameFromNormal(normal);
    const vec3 origin = OffsetRayOrigin(p, geometric);
    vec3 gathered = vec3(0);
    for (uint i = 0; i < pixel_job.final_gather; ++i) {
        const float u1 = Pcg32NextFloat(rng), u2 = Pcg32NextFloat(rng);
        const vec3 direction = ToWorld(frame, SampleCosineHemisphere(u1, u2));
        if (!(dot(direction, geometric) > 0)) continue;
        gathered += GatherRay(origin, direction, rng);
    }
    return radiance + albedo * gathered / float(pixel_job.final_gather);
}

vec3 PhotonMappingRadiance(vec3 origin, vec3 direction, inout Pcg32 rng) {
    vec3 radiance = vec3(0), throughput = vec3(1);
    float refraction = 1.0;  // the refractions' scales in throughput, out of Russian roulette
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
        const Bsdf bsdf = BsdfOf(material);
        const bool front_facing = dot(direction, surface.geometric_normal) < 0;
        if (kHasAbsorption)
            throughput *= SegmentTransmittance(material.absorption.xyz, material.outside_absorption.xyz, front_facing, hit.t);
        // Emission seen directly or through specular and rough bounces (no light map holds it).
        if (kHasTriangleLights) {
            float unused;
            radiance += throughput * HitEmitter(hit, origin, surface.position, unused);
        }
        // Punctual lights on a glossy surface, which no path finds.
        if (GlossyToPunctualLights(bsdf))
            radiance += throughput * PunctualLightOnGloss(bsdf, surface, front_facing, -direction, rng);
        const CoatArrival arrival = material.type == kMaterialDiffuse
                                        ? ArriveAtCoat(bsdf, direction, surface.shading_normal, front_facing, rng)
                                        : CoatArrival(false, 0.0, SpecularBounce(direction, vec3(0.0), false));
        if (arrival.at_base) {
            const uint coat = IsCoated(bsdf) ? surface.material : kNoCoat;
            // The light reflected on the path's side and, through a translucent surface, the
            // light let through from the other.
            vec3 diffuse = DiffuseRadiance(surface.position, front_facing ? surface.shading_normal : -surface.shading_normal,
                                           front_facing ? surface.geometric_normal : -surface.geometric_normal,
                                           surface.base_color, coat, rng);
            if (IsTranslucent(bsdf))
                diffuse += DiffuseRadiance(surface.position, front_facing ? -surface.shading_normal : surface.shading_normal,
                                           front_facing ? -surface.geometric_normal : surface.geometric_normal,
                                           material.transmittance.xyz, coat, rng);
            const float factor = IsCoated(bsdf) ? arrival.weight * CoatInside(bsdf.coat) : 1.0;
            return radiance + throughput * factor * diffuse;
        }
        const SpecularBounce bounce =
            material.type == kMaterialDiffuse
                ? arrival.reflected
                : ScatterNonDiffuse(bsdf, direction, surface.shading_normal, front_facing, surface.base_color, rng,
                                    kCarriesRadiance);
        throughput *= bounce.weight;
        if (bounce.transmitted) refraction *= RefractionOf(bsdf, front_facing);
        if (depth >= pixel_job.roulette_depth) {
            const float survive = min(1.0, MaxComponent(throughput) / refraction);
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
