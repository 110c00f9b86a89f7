#version 460
// One direct-light sample for each hit point of a batch's slice (core/ppm/direct_light.cpp on
// the CPU, with the same random numbers): a light sample, a shadow ray, the weighted result.
#include "common.glsl"
#include "trace.glsl"
#include "lights.glsl"

layout(local_size_x = kWorkgroupSize) in;

shared uint group_discarded;

void main() {
    if (gl_LocalInvocationIndex == 0) group_discarded = 0;
    barrier();
    const uint index = params.first + gl_GlobalInvocationID.x;
    if (index < params.end) {
        const GpuHitPoint point = hit_points[index];
        Pcg32 rng = Pcg32Seeded(FamilySeed(params.seed_prefix, index));
        LightSample light;
        vec3 value = vec3(0);
        RayHit hit;
        if (SampleLight(point.position.xyz, point.normal.xyz, rng, light) &&
            !TraceRay(light.origin, light.direction, light.distance, true, hit))
            value = point.weight.xyz * light.radiance_over_pdf * dot(light.direction, point.normal.xyz);
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
