// The random numbers of photon and light paths, one definition for the CPU (core/sampling/
// rng.h wraps it) and the Vulkan shaders: PCG32 (O'Neill 2014) seeded through the SplitMix64
// finaliser, so a photon's stream is a pure function of (job seed, batch, photon index) on
// either backend.
#ifndef PF_CORE_SHARED_RNG_H
#define PF_CORE_SHARED_RNG_H

#include "core/shared/gpu_prelude.h"

PF_GPU_BEGIN

// SplitMix64 finaliser (Steele et al. 2014): a bijective 64-bit mix.
PF_GPU_CONSTEXPR_FN uint64_t Mix64(uint64_t x) {
    x += 0x9e3779b97f4a7c15ul;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ul;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebul;
    return x ^ (x >> 31);
}

// The seed of member d of the family whose (a, b, c) mixed once gave `prefix`
// (FamilyPrefix): a batch mixes its shared part once, each photon once more.
// FamilyPrefix in two steps, for families that differ in c alone (a pixel's sequences, one
// per pixel): the part of (a, b), then each c's prefix from it.
PF_GPU_CONSTEXPR_FN uint64_t FamilyPartial(uint64_t a, uint64_t b) { return Mix64(Mix64(a) ^ b); }
PF_GPU_CONSTEXPR_FN uint64_t FamilyPrefixOf(uint64_t partial, uint64_t c) {
    return Mix64(partial ^ c);
}
PF_GPU_CONSTEXPR_FN uint64_t FamilyPrefix(uint64_t a, uint64_t b, uint64_t c) {
    return FamilyPrefixOf(FamilyPartial(a, b), c);
}
PF_GPU_CONSTEXPR_FN uint64_t FamilySeed(uint64_t prefix, uint64_t d) { return Mix64(prefix ^ d); }

struct Pcg32 {
    uint64_t state;
    uint64_t increment;  // odd: selects the stream
#ifdef __cplusplus
    // For GLSL's constructor syntax, Pcg32(state, increment): clang before 16 lacks C++20's
    // parenthesised aggregate initialisation.
    Pcg32() = default;
    constexpr Pcg32(uint64_t state_in, uint64_t increment_in)
        : state(state_in), increment(increment_in) {}
#endif
};

PF_GPU_CONSTEXPR_FN uint32_t Pcg32Next(PF_INOUT(Pcg32) rng) {
    const uint64_t old = rng.state;
    rng.state = old * 6364136223846793005ul + rng.increment;
    const uint32_t xorshifted = uint32_t(((old >> 18) ^ old) >> 27);
    const uint32_t rotation = uint32_t(old >> 59);
    return (xorshifted >> rotation) | (xorshifted << ((32u - rotation) & 31u));
}

PF_GPU_CONSTEXPR_FN Pcg32 Pcg32Seeded(uint64_t seed) {
    Pcg32 rng = Pcg32(0ul, (Mix64(seed) << 1) | 1ul);
    Pcg32Next(rng);
    rng.state += seed;
    Pcg32Next(rng);
    return rng;
}

// Uniform in [0, 1): the top 24 bits, so the result is never rounded up to 1.
PF_GPU_CONSTEXPR_FN float Pcg32NextFloat(PF_INOUT(Pcg32) rng) {
    return float(Pcg32Next(rng) >> 8) * 5.9604644775390625e-8f;
}

PF_GPU_END

#endif  // PF_CORE_SHARED_RNG_H
