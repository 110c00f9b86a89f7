// Random numbers for photon and camera paths: PCG32 (O'Neill 2014) seeded from a hash of the
// job seed and the sample's coordinates, so every photon's stream is a pure function of
// (seed, batch index, photon index) and results do not depend on scheduling.
#pragma once

#include <cstdint>

namespace pf {

// SplitMix64 finaliser (Steele et al. 2014): a bijective 64-bit mix.
constexpr uint64_t Mix64(uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

// The seeds HashSeed(a, b, c, d) for a fixed (a, b, c), with the shared part mixed once: a
// batch seeds each of its photons' streams for one mix instead of four.
class SeedFamily {
public:
    constexpr SeedFamily(uint64_t a, uint64_t b, uint64_t c) : prefix_(Mix64(Mix64(Mix64(a) ^ b) ^ c)) {}
    constexpr uint64_t Seed(uint64_t d) const { return Mix64(prefix_ ^ d); }

private:
    uint64_t prefix_;
};

constexpr uint64_t HashSeed(uint64_t a, uint64_t b, uint64_t c = 0, uint64_t d = 0) {
    return SeedFamily(a, b, c).Seed(d);
}

class Rng {
public:
    constexpr Rng() : Rng(0) {}
    explicit constexpr Rng(uint64_t seed) : state_(0), increment_((Mix64(seed) << 1u) | 1u) {
        NextUint();
        state_ += seed;
        NextUint();
    }

    constexpr uint32_t NextUint() {
        const uint64_t old = state_;
        state_ = old * 6364136223846793005ull + increment_;
        const auto xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
        const auto rotation = static_cast<uint32_t>(old >> 59u);
        return (xorshifted >> rotation) | (xorshifted << ((32u - rotation) & 31u));
    }

    // Uniform in [0, 1): the top 24 bits, so the result is never rounded up to 1.
    constexpr float NextFloat() { return static_cast<float>(NextUint() >> 8) * 0x1p-24f; }

private:
    uint64_t state_;
    uint64_t increment_;
};

}  // namespace pf
