// The sheen of glTF's KHR_materials_sheen: a layer of fibres over the surface, reflecting
// f_sheen = colour D V (Estevez and Kulla 2017's "Charlie" distribution D of alpha = r^2 and its
// visibility V, clamped to 1 as the Khronos sample viewer clamps it; r the sheen roughness,
// taken as at least kMinSheenRoughness). The surface below is scaled by albedo scaling, made
// separable and normalised as the Fresnel mix's base is (core/shared/coat.h): f = f_sheen +
// f_base (1 - P(wo)) (1 - P(wi)) / (1 - P_avg), with P(w) = min(1, max(colour) E(w.z)) the
// probability that the sheen reflects light arriving along w and E the layer's directional
// albedo for colour 1, so a white sheen over a white base reflects all the light wherever E <=
// 1. E and its cosine-weighted mean come from tables integrated numerically
// (tests/core/shared/sheen_test.cpp integrates them again and prints them). One definition for
// the CPU and the Vulkan kernels.
#ifndef PF_CORE_SHARED_SHEEN_H
#define PF_CORE_SHARED_SHEEN_H

#include "core/shared/gpu_prelude.h"

PF_GPU_BEGIN

// Below this the lobe is a line at grazing angles that no sampling would find.
PF_CONST(float) kMinSheenRoughness = 0.07f;

PF_GPU_FN float SheenAlpha(float roughness) {
    const float r = clamp(roughness, kMinSheenRoughness, 1.0f);
    return r * r;
}

// Estevez and Kulla's distribution of fibre normals: (2 + 1/alpha) sin(theta_h)^(1/alpha) / 2pi.
PF_GPU_FN float CharlieDistribution(float cos_h, float alpha) {
    const float sin2 = max(0.0f, 1.0f - cos_h * cos_h);
    return (2.0f + 1.0f / alpha) * pow(sin2, 0.5f / alpha) * (0.5f / 3.14159265358979323846f);
}

// Their fitted shadowing exponent L(x), interpolated in (1 - alpha)^2.
PF_GPU_FN float CharlieL(float x, float alpha) {
    const float t = (1.0f - alpha) * (1.0f - alpha);
    const float a = 21.5473f + (25.3245f - 21.5473f) * t;
    const float b = 3.82987f + (3.32435f - 3.82987f) * t;
    const float c = 0.19823f + (0.16801f - 0.19823f) * t;
    const float d = -1.97760f + (-1.27393f + 1.97760f) * t;
    const float e = -4.32054f + (-4.85967f + 4.32054f) * t;
    return a / (1.0f + b * pow(x, c)) + d * x + e;
}

PF_GPU_FN float CharlieLambda(float cos_theta, float alpha) {
    const float c = abs(cos_theta);
    return c < 0.5f ? exp(CharlieL(c, alpha))
                    : exp(2.0f * CharlieL(0.5f, alpha) - CharlieL(1.0f - c, alpha));
}

// f_sheen for colour 1, wo and wi above the surface (+z); 0 below.
PF_GPU_FN float SheenBrdf(vec3 wo, vec3 wi, float alpha) {
    if (!(wo.z > 0.0f && wi.z > 0.0f)) return 0.0f;
    const vec3 h = normalize(wo + wi);
    const float visibility =
        min(1.0f, 1.0f / ((1.0f + CharlieLambda(wo.z, alpha) + CharlieLambda(wi.z, alpha)) *
                          (4.0f * wo.z * wi.z)));
    return CharlieDistribution(h.z, alpha) * visibility;
}

// The tables' nodes: E at cosine mu = (i / (kSheenCosines - 1))^2 and roughness r =
// kMinSheenRoughness + (1 - kMinSheenRoughness) (j / (kSheenRoughnesses - 1))^2 (dense at
// grazing angles and low roughness, where E changes fastest), row j, column i, row after row;
// then E's mean per roughness.
PF_CONST(int32_t) kSheenCosines = 32;
PF_CONST(int32_t) kSheenRoughnesses = 32;
PF_CONST(int32_t) kSheenAverageBegin = kSheenCosines * kSheenRoughnesses;
PF_CONST(int32_t) kSheenTableSize = kSheenAverageBegin + kSheenRoughnesses;

#ifdef __cplusplus
#include "core/shared/sheen_tables.h"
PF_GPU_FN float SheenTable(int32_t i) { return kSheenTables[i]; }
#else
// The kernels' binding kBindingSheenTables (common.glsl), kSheenTables uploaded.
#define SheenTable(i) sheen_tables[i]
#endif

// Where roughness r falls between the tables' rows: the row below and the fraction past it.
PF_GPU_FN int32_t SheenRow(float roughness, PF_OUT(float) fraction) {
    const float y = sqrt((clamp(roughness, kMinSheenRoughness, 1.0f) - kMinSheenRoughness) /
                         (1.0f - kMinSheenRoughness)) *
                    float(kSheenRoughnesses - 1);
    const int32_t row = int32_t(min(floor(y), float(kSheenRoughnesses - 2)));
    fraction = y - float(row);
    return row;
}

// E(mu): the fraction of light arriving at cosine mu that a white sheen of roughness r
// reflects (above 1 at grazing angles for r below about 0.25: the lobe is not energy
// conserving there).
PF_GPU_FN float SheenAlbedo(float mu, float roughness) {
    float fy;
    const int32_t row = SheenRow(roughness, fy);
    const float x = sqrt(clamp(mu, 0.0f, 1.0f)) * float(kSheenCosines - 1);
    const int32_t column = int32_t(min(floor(x), float(kSheenCosines - 2)));
    const float fx = x - float(column);
    const int32_t i = row * kSheenCosines + column;
    const float below = SheenTable(i) + fx * (SheenTable(i + 1) - SheenTable(i));
    const float above = SheenTable(i + kSheenCosines) +
                        fx * (SheenTable(i + kSheenCosines + 1) - SheenTable(i + kSheenCosines));
    return below + fy * (above - below);
}

// The cosine-weighted mean of E over the hemisphere, 2 integral E(mu) mu dmu.
PF_GPU_FN float SheenAverageAlbedo(float roughness) {
    float fy;
    const int32_t row = SheenRow(roughness, fy);
    const int32_t i = kSheenAverageBegin + row;
    return SheenTable(i) + fy * (SheenTable(i + 1) - SheenTable(i));
}

PF_GPU_END

#endif  // PF_CORE_SHARED_SHEEN_H
