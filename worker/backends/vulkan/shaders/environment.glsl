// The environment light as core/scene/environment.cpp has it on the CPU: radiance from a
// direction (the map's nearest texel, or a uniform colour), directions drawn from the
// piecewise-constant sampling tables, and their density for weighing a ray that escapes the
// scene against light sampling. The maps between image and sphere are the shared ones
// (core/shared/environment_map.h). Its emitter record (gpu_types.h, GpuEmitter) holds the
// map's size, mapping, scale, rotation and where its texels and tables begin. A goniometric
// light's intensity over its sphere of directions is such a map too (Emitters::ImageSampler).
#include "core/shared/environment_map.h"

layout(std430, binding = kBindingLightImageTexels) readonly buffer LightImageTexels {
    vec4 light_image_texels[];
};
layout(std430, binding = kBindingLightImageTables) readonly buffer LightImageTables {
    float light_image_tables[];
};

GpuEmitter EnvironmentEmitter() { return emitters[params.environment_emitter]; }
uint EnvironmentMapping(GpuEmitter e) { return floatBitsToUint(e.edge1.z); }
int EnvironmentWidth(GpuEmitter e) { return int(floatBitsToUint(e.edge1.x)); }
int EnvironmentHeight(GpuEmitter e) { return int(floatBitsToUint(e.edge1.y)); }
uint FirstTexel(GpuEmitter e) { return floatBitsToUint(e.texture.x); }
uint FirstTableEntry(GpuEmitter e) { return floatBitsToUint(e.texture.y); }

vec3 EnvironmentToMap(GpuEmitter e, vec3 w) {
    return normalize(vec3(dot(e.edge2.xyz, w), dot(e.direction.xyz, w), dot(e.cone.xyz, w)));
}
vec3 EnvironmentToWorld(GpuEmitter e, vec3 d) {
    return normalize(e.edge2.xyz * d.x + e.direction.xyz * d.y + e.cone.xyz * d.z);
}

// The radiance arriving from unit world direction `toward` (Environment::Radiance).
vec3 EnvironmentRadiance(GpuEmitter e, vec3 toward) {
    const uint mapping = EnvironmentMapping(e);
    if (mapping == kMappingUniform) return e.radiance.xyz;
    const uint texel = EnvironmentTexel(mapping, EnvironmentWidth(e), EnvironmentHeight(e),
                                        EnvironmentToMap(e, toward));
    return light_image_texels[FirstTexel(e) + texel].xyz * e.radiance.xyz;
}

// Where each table begins in light_image_tables.
uint RowCdfBegin(GpuEmitter e) { return FirstTableEntry(e); }
uint TexelCdfBegin(GpuEmitter e) { return RowCdfBegin(e) + uint(EnvironmentHeight(e)) + 1u; }
uint ProbabilityBegin(GpuEmitter e) {
    return TexelCdfBegin(e) + uint(EnvironmentHeight(e)) * (uint(EnvironmentWidth(e)) + 1u);
}

// The density in solid angle of EnvironmentDraw's direction `toward`
// (EnvironmentSampler::Pdf), the emitter's pick excluded.
float EnvironmentPdf(GpuEmitter e, vec3 toward) {
    const uint mapping = EnvironmentMapping(e);
    if (mapping == kMappingUniform) return 1.0 / (4.0 * kPi);
    const int width = EnvironmentWidth(e), height = EnvironmentHeight(e);
    const uint texel = EnvironmentTexel(mapping, width, height, EnvironmentToMap(e, toward));
    return light_image_tables[ProbabilityBegin(e) + texel] /
           EnvironmentTexelSolidAngle(mapping, width, height, int(texel / uint(width)));
}

// The interval i of the n-entry cumulative table at `begin` (n + 1 values, 0 first and 1
// last) with table[i] <= u < table[i + 1], and u's place in it (FindInterval on the CPU).
uint FindEnvironmentInterval(uint begin, uint n, float u, out float fraction) {
    uint low = 0, high = n;
    while (low < high) {
        const uint middle = (low + high) / 2;
        if (light_image_tables[begin + 1 + middle] > u) high = middle; else low = middle + 1;
    }
    const uint index = min(low, n - 1);
    const float start = light_image_tables[begin + index];
    const float width = light_image_tables[begin + index + 1] - start;
    fraction = width > 0 ? clamp((u - start) / width, 0.0, 0.99999994) : 0.0;
    return index;
}

struct EnvironmentSample {
    vec3 toward;    // unit world direction, toward the environment
    vec3 radiance;  // arriving from it
    float pdf;      // solid angle, the emitter's pick excluded
};

// EnvironmentSampler::Draw, from the tables at `tables` (the map's own, or its portal's).
EnvironmentSample EnvironmentDrawFrom(GpuEmitter e, uint tables, float u1, float u2) {
    EnvironmentSample drawn;
    const uint mapping = EnvironmentMapping(e);
    const int width = EnvironmentWidth(e), height = EnvironmentHeight(e);
    float fx, fy;
    const uint texel_cdf = tables + uint(height) + 1u;
    const uint y = FindEnvironmentInterval(tables, uint(height), u1, fy);
    const uint x = FindEnvironmentInterval(texel_cdf + y * (uint(width) + 1u), uint(width), u2, fx);
    const uint texel = y * uint(width) + x;
    drawn.toward = EnvironmentToWorld(
        e, EnvironmentDirectionInTexel(mapping, width, height, x, y, fx, fy));
    drawn.radiance = light_image_texels[FirstTexel(e) + texel].xyz * e.radiance.xyz;
    const uint probability = texel_cdf + uint(height) * (uint(width) + 1u);
    drawn.pdf = light_image_tables[probability + texel] /
                EnvironmentTexelSolidAngle(mapping, width, height, int(y));
    return drawn;
}

// EnvironmentSampler::Draw over the whole sphere.
EnvironmentSample EnvironmentDraw(GpuEmitter e, float u1, float u2) {
    if (EnvironmentMapping(e) == kMappingUniform) {
        EnvironmentSample drawn;
        drawn.toward = SampleUniformSphere(u1, u2);
        drawn.radiance = e.radiance.xyz;
        drawn.pdf = 1.0 / (4.0 * kPi);
        return drawn;
    }
    return EnvironmentDrawFrom(e, RowCdfBegin(e), u1, u2);
}

// The environment's portal (EnvironmentPortal), where it has one: its normal toward the
// environment, pbrt-v4's p03 x p01.
bool HasPortal(GpuEmitter e) { return e.portal_u.w > 0.0; }
vec3 PortalNormal(GpuEmitter e) { return normalize(cross(e.portal_v.xyz, e.portal_u.xyz)); }
