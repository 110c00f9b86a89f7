#version 460
// One direct-light sample for each point of a batch's slice of the epoch's camera samples
// (direct_points: core/ppm/direct_light.cpp on the CPU, with the same random numbers; none at
// rpm's gather hits): a light sample with its shadow ray and, in a scene with emitting
// triangles or an environment, a cosine-distributed ray that may find one, weighed by the power
// heuristic, under a coat times what it lets through; the result times the hit point's weight.
#include "common.glsl"
#include "trace.glsl"
#include "lights.glsl"
#include "specular.glsl"
#include "core/shared/sobol.h"

layout(local_size_x = kWorkgroupSize) in;

shared uint group_discarded;

void main() {
    if (gl_LocalInvocationIndex == 0) group_discarded = 0;
    barrier();
    const uint index = params.first + gl_GlobalInvocationID.x;
    // rpm's gather hits take no sample: their photons carry direct light.
    const bool gather_hit = index < params.end && kPhotonKinds &&
                            (floatBitsToUint(direct_points[index].weight.w) & kDirectPhoton) != 0u;
    if (gather_hit) direct[index - params.direct_begin] = vec4(0);
    if (index < params.end && !gather_hit) {
        const GpuHitPoint point = direct_points[index];
        Pcg32 rng = Pcg32Seeded(FamilySeed(params.seed_prefix, index));
        const vec3 normal = point.normal.xyz;
        // The numbers as the CPU draws them (core/ppm/direct_light.cpp): with the pass's
        // sequences, the emitter's pick with the point on it and the cosine ray from the slot's
        // camera sample's index in its pixel's sequences, the coat's microfacet from the
        // point's stream; without, all from the stream, in the order used.
        const bool sequenced = params.direct_samples_per_pixel > 0;
        uint64_t sequence = 0;
        uint sample_index = 0;
        float pick = 0;
        vec2 light_u = vec2(0);
        if (sequenced) {
            const uint pixel = floatBitsToUint(point.normal.w);
            // PixelSampler::SequenceOf: 2 pixel + the epoch's parity.
            sequence = FamilyPrefixOf(params.direct_sequences,
                                      2ul * uint64_t(pixel) + uint64_t(params.epoch_parity));
            const uint slots = params.direct_slots_per_sample;
            sample_index = uint(params.direct_first_sample +
                                uint64_t((index - pixel * params.direct_samples_per_pixel * slots) / slots));
            light_u = SequenceSample2D(sequence, sample_index, 0u);
        } else {
            pick = Pcg32NextFloat(rng);
            light_u.x = Pcg32NextFloat(rng);
            light_u.y = Pcg32NextFloat(rng);
        }
        LightSample light;
        vec3 light_part = vec3(0), ray_part = vec3(0);
        vec3 ray_direction = normal;
        RayHit hit;
        if (SampleLightFrom(point.position.xyz, normal, pick, light_u, sequenced, light) &&
            !TraceRay(light.origin, light.direction, light.distance, true, hit)) {
            const float cosine = dot(light.direction, normal);
            const float weight = light.pdf > 0 ? PowerHeuristic(light.pdf, cosine / kPi) : 1.0;
            light_part = light.radiance_over_pdf * (cosine * weight);
        }
        if (kHasTriangleLights || kHasEnvironment) {
            vec2 u;
            if (sequenced) {
                u = SequenceSample2D(sequence, sample_index, 1u);
            } else {
                u.x = Pcg32NextFloat(rng);
                u.y = Pcg32NextFloat(rng);
            }
            ray_direction = FrameFromNormal(normal) * SampleCosineHemisphere(u.x, u.y);
            const vec3 origin = OffsetRayOrigin(point.position.xyz, normal);
            float pdf = 0;
            vec3 radiance = vec3(0);
            if (TraceRay(origin, ray_direction, kInfinity, false, hit)) {
                if (kHasTriangleLights) radiance = HitEmitter(hit, origin, origin + ray_direction * hit.t, pdf);
            } else if (kHasEnvironment) {
                radiance = EscapedRay(origin, ray_direction, pdf);
            }
            // L cos / (cos / pi): the cosine ray's own weight is pi.
            if (pdf > 0) ray_part = radiance * (kPi * PowerHeuristic(dot(ray_direction, normal) / kPi, pdf));
        }
        // Under a coat, what it lets through of each (core/ppm/direct_light.cpp's CoatFactor).
        const uint coat = floatBitsToUint(point.position.w);
        if (kHasCoats && coat != kNoCoat) {
            const Coat layer = CoatOf(materials[coat]);
            float u1 = 0, u2 = 0;
            if (layer.alpha > 0.0) u1 = Pcg32NextFloat(rng), u2 = Pcg32NextFloat(rng);
            const mat3 frame = FrameFromNormal(normal);
            if (MaxComponent(light_part) > 0.0) light_part *= CoatTransmittance(layer, light.direction * frame, u1, u2);
            if (MaxComponent(ray_part) > 0.0) ray_part *= CoatTransmittance(layer, ray_direction * frame, u1, u2);
        }
        const vec3 irradiance = light_part + ray_part;
        vec3 value = point.weight.xyz * irradiance;
        if (!IsFinite(value)) {
            atomicAdd(group_discarded, 1u);
            value = vec3(0);
        }
        direct[index - params.direct_begin] = vec4(value, 0);
    }
    barrier();
    if (gl_LocalInvocationIndex == 0 && group_discarded > 0)
        atomicAdd(counters.nonfinite_discarded, uint64_t(group_discarded));
}
