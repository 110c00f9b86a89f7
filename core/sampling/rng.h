// Random numbers for photon and camera paths: PCG32 (O'Neill 2014) seeded from a hash of the
// job seed and the sample's coordinates, so every photon's stream is a pure function of
// (seed, batch index, photon index) and results do not depend on scheduling. The generator
// itself is defined once for C++ and the Vulkan shaders, in core/shared/rng.h.
#pragma once

#include <cstdint>

#include "core/shared/rng.h"

namespace pf {

using gpu::Mix64;

// The seeds HashSeed(a, b, c, d) for a fixed (a, b, c), with the shared part mixed once: a
// batch seeds each of its photons' streams for one mix instead of four.
class SeedFamily {
public:
    constexpr SeedFamily(uint64_t a, uint64_t b, uint64_t c)
        : prefix_(gpu::FamilyPrefix(a, b, c)) {}
    constexpr uint64_t Seed(uint64_t d) const { return gpu::FamilySeed(prefix_, d); }
    // The shared part, which the Vulkan shaders take to derive the same seeds.
    constexpr uint64_t Prefix() const { return prefix_; }

private:
    uint64_t prefix_;
};

constexpr uint64_t HashSeed(uint64_t a, uint64_t b, uint64_t c = 0, uint64_t d = 0) {
    return SeedFamily(a, b, c).Seed(d);
}

class Rng {
public:
    constexpr Rng() : Rng(0) {}
    explicit constexpr Rng(uint64_t seed) : state_(gpu::Pcg32Seeded(seed)) {}

    constexpr uint32_t NextUint() { return gpu::Pcg32Next(state_); }
    // Uniform in [0, 1): the top 24 bits, so the result is never rounded up to 1.
    constexpr float NextFloat() { return gpu::Pcg32NextFloat(state_); }
    // The generator itself, for the walks both languages share (core/shared/coat.h).
    constexpr gpu::Pcg32& State() { return state_; }

private:
    gpu::Pcg32 state_;
};

}  // namespace pf
