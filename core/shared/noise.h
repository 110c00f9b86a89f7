// Perlin noise and its sums over octaves, as pbrt-v4 defines them (util/noise.h; Physically
// Based Rendering, 4th edition, section 10.6.2): gradient noise on the integer lattice with Ken
// Perlin's permutation of 0..255 (Perlin 2002, "Improving Noise"), pbrt-v4's choice of twelve
// gradients from the hash's low four bits, and its quintic blend 6t^5 - 15t^4 + 10t^3; FBm and
// Turbulence sum octaves of it, as many as a lookup's footprint resolves. One definition for the
// CPU and the Vulkan kernels (procedural_texture.h evaluates pbrt-v4's noise textures with it).
#ifndef PF_CORE_SHARED_NOISE_H
#define PF_CORE_SHARED_NOISE_H

#include "core/shared/gpu_prelude.h"

PF_GPU_BEGIN

// The permutation's entries, and the vec4 texels the kernels keep it in: the first
// kNoisePermutationTexels of the texels binding, four entries a texel, in scenes with
// procedural textures (kSpecHasProceduralTextures).
PF_CONST(int32_t) kNoisePermutationSize = 256;
PF_CONST(uint32_t) kNoisePermutationTexels = 64;

#ifdef __cplusplus
// Perlin's permutation, as published with his reference implementation of improved noise.
// clang-format off
inline constexpr int32_t kNoisePermutation[kNoisePermutationSize] = {
    151, 160, 137, 91,  90,  15,  131, 13,  201, 95,  96,  53,  194, 233, 7,   225,
    140, 36,  103, 30,  69,  142, 8,   99,  37,  240, 21,  10,  23,  190, 6,   148,
    247, 120, 234, 75,  0,   26,  197, 62,  94,  252, 219, 203, 117, 35,  11,  32,
    57,  177, 33,  88,  237, 149, 56,  87,  174, 20,  125, 136, 171, 168, 68,  175,
    74,  165, 71,  134, 139, 48,  27,  166, 77,  146, 158, 231, 83,  111, 229, 122,
    60,  211, 133, 230, 220, 105, 92,  41,  55,  46,  245, 40,  244, 102, 143, 54,
    65,  25,  63,  161, 1,   216, 80,  73,  209, 76,  132, 187, 208, 89,  18,  169,
    200, 196, 135, 130, 116, 188, 159, 86,  164, 100, 109, 198, 173, 186, 3,   64,
    52,  217, 226, 250, 124, 123, 5,   202, 38,  147, 118, 126, 255, 82,  85,  212,
    207, 206, 59,  227, 47,  16,  58,  17,  182, 189, 28,  42,  223, 183, 170, 213,
    119, 248, 152, 2,   44,  154, 163, 70,  221, 153, 101, 155, 167, 43,  172, 9,
    129, 22,  39,  253, 19,  98,  108, 110, 79,  113, 224, 232, 178, 185, 112, 104,
    218, 246, 97,  228, 251, 34,  242, 193, 238, 210, 144, 12,  191, 179, 162, 241,
    81,  51,  145, 235, 249, 14,  239, 107, 49,  192, 214, 31,  181, 199, 106, 157,
    184, 84,  204, 176, 115, 121, 50,  45,  127, 4,   150, 254, 138, 236, 205, 93,
    222, 114, 67,  29,  24,  72,  243, 141, 128, 195, 78,  66,  215, 61,  156, 180};
// clang-format on
// Entry i of the permutation repeated (pbrt-v4 stores it twice over, for sums up to 511).
PF_GPU_FN int32_t NoisePermutation(int32_t i) { return kNoisePermutation[i & 255]; }
#else
// The kernels' copy, the first texels of the texels binding (common.glsl).
int32_t NoisePermutation(int32_t i) { return int32_t(texels[(i & 255) >> 2][i & 3]); }
#endif

// The gradient of lattice point (x, y, z), each in [0, 256], dotted with the offset (dx, dy, dz)
// from it: twelve directions (1, 1, 0) and the like, the last four repeated, picked by the low
// four bits of the hashed point.
PF_GPU_FN float NoiseGradient(int32_t x, int32_t y, int32_t z, float dx, float dy, float dz) {
    const int32_t h = NoisePermutation(NoisePermutation(NoisePermutation(x) + y) + z) & 15;
    const float u = h < 8 || h == 12 || h == 13 ? dx : dy;
    const float v = h < 4 || h == 12 || h == 13 ? dy : dz;
    return ((h & 1) != 0 ? -u : u) + ((h & 2) != 0 ? -v : v);
}

// The blend between lattice points: 0 and 1 with zero first and second derivatives at 0 and 1.
PF_GPU_FN float NoiseWeight(float t) {
    const float t3 = t * t * t;
    return 6.0f * t3 * t * t - 15.0f * t3 * t + 10.0f * t3;
}

PF_GPU_FN float NoiseLerp(float t, float a, float b) { return (1.0f - t) * a + t * b; }

// x within 2^30 of 0 (C's fmod by 2^30), so that its lattice cell is an int32.
PF_GPU_FN float NoiseCoordinate(float x) {
    const float period = 1073741824.0f;
    if (abs(x) < period) return x;
    if (!(abs(x) <= 3.0e38f)) return 0.0f;  // infinite or NaN: no cell to take an integer of
    const float whole = x < 0.0f ? -floor(-x / period) : floor(x / period);
    return x - period * whole;
}

// Perlin noise at p: 0 at every lattice point, in about [-1, 1], smooth. pbrt-v4 blends its
// cell's eight corners by nested linear interpolation; the same sum is taken here corner by
// corner, one gradient a loop (so that the kernels, which inline every call, hold one copy).
PF_GPU_FN float PerlinNoise(vec3 p) {
    const float x = NoiseCoordinate(p.x), y = NoiseCoordinate(p.y), z = NoiseCoordinate(p.z);
    const float fx = floor(x), fy = floor(y), fz = floor(z);
    const float dx = x - fx, dy = y - fy, dz = z - fz;
    const int32_t ix = int32_t(fx) & 255, iy = int32_t(fy) & 255, iz = int32_t(fz) & 255;
    const float wx = NoiseWeight(dx), wy = NoiseWeight(dy), wz = NoiseWeight(dz);
    float sum = 0.0f;
    for (int32_t corner = 0; corner < 8; ++corner) {
        const int32_t cx = corner & 1, cy = (corner >> 1) & 1, cz = corner >> 2;
        const float weight =
            (cx == 1 ? wx : 1.0f - wx) * (cy == 1 ? wy : 1.0f - wy) * (cz == 1 ? wz : 1.0f - wz);
        sum += weight * NoiseGradient(ix + cx, iy + cy, iz + cz, dx - float(cx), dy - float(cy),
                                      dz - float(cz));
    }
    return sum;
}

// pbrt-v4's SmoothStep: 0 below a, 1 above b, a cubic between.
PF_GPU_FN float NoiseSmoothStep(float x, float a, float b) {
    if (a == b) return x < a ? 0.0f : 1.0f;
    const float t = clamp((x - a) / (b - a), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

// The octaves a lookup resolves: -1 - log2(footprint), footprint the larger of |dp/dx| and
// |dp/dy| (footprint_sq its square) in the noise's space, within [0, max_octaves]; all of them
// for a point (footprint 0).
PF_GPU_FN float NoiseOctaves(float footprint_sq, int32_t max_octaves) {
    if (!(footprint_sq > 0.0f)) return float(max_octaves);
    return clamp(-1.0f - 0.5f * log2(footprint_sq), 0.0f, float(max_octaves));
}

// pbrt-v4's FBm (turbulence false): the sum over octaves i of omega^i noise(1.99^i p), the
// octave the footprint resolves in part faded in by SmoothStep. Its Turbulence (true): the same
// of |noise|, the partial octave blended from 0.2 and each octave not resolved taken as 0.2 (as
// pbrt-v4 counts them: the first at the partial octave's weight again).
PF_GPU_FN float OctaveNoise(vec3 p, float footprint_sq, float omega, int32_t max_octaves,
                            bool turbulence) {
    const float n = NoiseOctaves(footprint_sq, max_octaves);
    const int32_t whole = int32_t(floor(n));
    const float fade = NoiseSmoothStep(n - float(whole), 0.3f, 0.7f);
    float sum = 0.0f, lambda = 1.0f, o = 1.0f;
    for (int32_t i = 0; i <= whole; ++i) {  // i == whole: the partial octave
        const float noise = PerlinNoise(p * lambda);
        if (i < whole) {
            sum += o * (turbulence ? abs(noise) : noise);
            lambda *= 1.99f;
            o *= omega;
        } else {
            sum += o * (turbulence ? NoiseLerp(fade, 0.2f, abs(noise)) : fade * noise);
        }
    }
    if (turbulence)
        for (int32_t i = whole; i < max_octaves; ++i) {
            sum += o * 0.2f;
            o *= omega;
        }
    return sum;
}

PF_GPU_FN float FractalNoise(vec3 p, float footprint_sq, float omega, int32_t max_octaves) {
    return OctaveNoise(p, footprint_sq, omega, max_octaves, false);
}
PF_GPU_FN float Turbulence(vec3 p, float footprint_sq, float omega, int32_t max_octaves) {
    return OctaveNoise(p, footprint_sq, omega, max_octaves, true);
}

PF_GPU_END

#endif  // PF_CORE_SHARED_NOISE_H
