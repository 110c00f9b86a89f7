#version 460
// One direct-light sample for each point of a batch's slice of the epoch's camera samples
// (direct_points: core/ppm/direct_light.cpp on the CPU, with the same random numbers; none at
// rpm's gather hits): a light sample with its shadow ray and, in a scene with emitting
// triangles or an environment, a cosine-distributed ray that may find one, weighed by the power
// heuristic, under a coat times what it lets through; the result times the hit point's weight.
#include "common.glsl"
#include "trace.glsl"
#include "lights.glsl"
#include "bsdf.glsl"
#include "direct.glsl"
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
        vec2 cosine_u = vec2(0);
        if (kLightsFoundByRays) {
            if (sequenced) {
                cosine_u = SequenceSample2D(sequence, sample_index, 1u);
            } else {
                cosine_u.x = Pcg32NextFloat(rng);
                cosine_u.y = Pcg32NextFloat(rng);
            }
        }
        const vec3 irradiance = DirectIrradiance(point.position.xyz, point.normal.xyz, floatBitsToUint(point.position.w),
                                                 pick, light_u, sequenced, cosine_u, rng);
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
