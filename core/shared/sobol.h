// Low-discrepancy samples, one definition for the CPU and the Vulkan shaders: the first two
// dimensions of Sobol's sequence, a (0,2)-sequence in base 2, Owen-scrambled by a hash
// (Burley 2020, "Practical hash-based Owen scrambling", with the better hash of Vegdahl 2021
// that pbrt-v4's FastOwenScrambler uses), their order shuffled by a scramble of the index.
// Any aligned run of 2^m indices, [j 2^m, (j + 1) 2^m), is then a (0,m,2)-net: every
// elementary interval of area 2^-m (2^-a wide, 2^-(m-a) tall) holds one point. A pixel's
// samples drawn at consecutive indices over a whole run stay stratified however many epochs
// they are spread over. Each pair of dimensions takes its own scrambles and shuffle (a padded
// sequence, as pbrt-v4's PaddedSobolSampler), so pairs are independent of each other.
#ifndef PF_CORE_SHARED_SOBOL_H
#define PF_CORE_SHARED_SOBOL_H

#include "core/shared/gpu_prelude.h"
#include "core/shared/rng.h"

PF_GPU_BEGIN

PF_GPU_CONSTEXPR_FN uint32_t ReverseBits32(uint32_t x) {
    x = (x << 16) | (x >> 16);
    x = ((x & 0x00ff00ffu) << 8) | ((x & 0xff00ff00u) >> 8);
    x = ((x & 0x0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0u) >> 4);
    x = ((x & 0x33333333u) << 2) | ((x & 0xccccccccu) >> 2);
    return ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
}

// Base-2 Owen scrambling of x read as the binary fraction 0.x31 x30 ... x0: each bit flipped
// or not by a hash of `seed` and the bits above it. On an index it permutes aligned runs of
// 2^m indices among themselves, whole.
PF_GPU_CONSTEXPR_FN uint32_t OwenScramble(uint32_t x, uint32_t seed) {
    x = ReverseBits32(x);
    x ^= x * 0x3d20adeau;
    x += seed;
    x *= (seed >> 16) | 1u;
    x ^= x * 0x05526c56u;
    x ^= x * 0x53a22864u;
    return ReverseBits32(x);
}

// Sobol's second dimension (its generator matrix is Pascal's triangle mod 2): direction
// number i is 2^31 XOR-shifted i times; the first dimension is ReverseBits32(index).
// Branch-free over the index's bits: a branch on each bit, taken at random, mispredicts half
// the time (the loop was a sixth of a direct-light sample's CPU time).
PF_GPU_CONSTEXPR_FN uint32_t SobolSecondDimension(uint32_t index) {
    uint32_t result = 0u;
    uint32_t direction = 0x80000000u;
    while (index != 0u) {
        result ^= direction & (0u - (index & 1u));
        index >>= 1u;
        direction ^= direction >> 1u;
    }
    return result;
}

// Point `index` of the (0,2)-sequence scrambled by seeds.x (x), seeds.y (y) and shuffled by
// seeds.z, in [0, 1)^2 (the top 24 bits of each, so never rounded up to 1).
PF_GPU_CONSTEXPR_FN vec2 ScrambledSobol2D(uint32_t index, uint32_t seed_x, uint32_t seed_y,
                                          uint32_t seed_shuffle) {
    const uint32_t shuffled = OwenScramble(index, seed_shuffle);
    const uint32_t x = OwenScramble(ReverseBits32(shuffled), seed_x);
    const uint32_t y = OwenScramble(SobolSecondDimension(shuffled), seed_y);
    return vec2(float(x >> 8u) * 5.9604644775390625e-8f, float(y >> 8u) * 5.9604644775390625e-8f);
}

// Pair `pair` of point `index` of the sequence whose seeds' family prefix is
// `sequence_prefix` (FamilyPrefix of (seed, stream, sequence): a pixel's, PixelSampler).
PF_GPU_CONSTEXPR_FN vec2 SequenceSample2D(uint64_t sequence_prefix, uint32_t index, uint32_t pair) {
    const uint64_t hash = FamilySeed(sequence_prefix, uint64_t(pair));
    return ScrambledSobol2D(index, uint32_t(hash), uint32_t(hash >> 32u), uint32_t(Mix64(hash)));
}

PF_GPU_END

#endif  // PF_CORE_SHARED_SOBOL_H
