// Morton (Z-order) codes: nearby points get nearby codes, so sorting by them lays data out
// with spatial locality.
#pragma once

#include <algorithm>
#include <cstdint>

#include "core/math/vec3.h"

namespace pf {

// Spreads the low 21 bits of v to every third bit.
constexpr uint64_t SpreadBits3(uint64_t v) {
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffull;
    v = (v | v << 16) & 0x1f0000ff0000ffull;
    v = (v | v << 8) & 0x100f00f00f00f00full;
    v = (v | v << 4) & 0x10c30c30c30c30c3ull;
    v = (v | v << 2) & 0x1249249249249249ull;
    return v;
}

// The 63-bit Morton code of p within the box [lower, lower + extent] (clamped to it).
inline uint64_t MortonCode(const Vec3& p, const Vec3& lower, const Vec3& extent) {
    uint64_t code = 0;
    for (int axis = 0; axis < 3; ++axis) {
        const float unit = std::clamp((p[axis] - lower[axis]) / extent[axis], 0.0f, 1.0f);
        code |= SpreadBits3(static_cast<uint64_t>(unit * float((1 << 21) - 1))) << axis;
    }
    return code;
}

}  // namespace pf
