// Unit vectors packed in 32 bits by the octahedral map (Meyer et al. 2010; Cigolle et al. 2014,
// "A Survey of Efficient Representations for Independent Unit Vectors"): 16 bits an axis,
// angular error below 0.01 degrees.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/math/vec3.h"

namespace pf {

inline uint32_t EncodeOctahedral(const Vec3& n) {
    const float scale = 1.0f / (std::abs(n.x) + std::abs(n.y) + std::abs(n.z));
    float u = n.x * scale, v = n.y * scale;
    if (n.z < 0) {
        const float fu = (1.0f - std::abs(v)) * std::copysign(1.0f, u);
        const float fv = (1.0f - std::abs(u)) * std::copysign(1.0f, v);
        u = fu, v = fv;
    }
    const auto quantise = [](float x) {
        return static_cast<uint32_t>(
            static_cast<uint16_t>(static_cast<int16_t>(std::lround(x * 32767.0f))));
    };
    return quantise(u) | quantise(v) << 16;
}

// The decoded direction, not normalised (its length lies in [1/sqrt(3), 1]): enough for
// sign tests, normalise for anything else. Branch-free (Stubbe's form of the fold): the
// lower hemisphere's unfolding is a subtraction of max(-z, 0), so the photon gather does not
// mispredict on half of its normals.
inline Vec3 DecodeOctahedral(uint32_t packed) {
    const float u = static_cast<int16_t>(packed & 0xffff) * (1.0f / 32767.0f);
    const float v = static_cast<int16_t>(packed >> 16) * (1.0f / 32767.0f);
    const float z = 1.0f - std::abs(u) - std::abs(v);
    const float fold = std::max(-z, 0.0f);
    return {u + std::copysign(fold, -u), v + std::copysign(fold, -v), z};
}

}  // namespace pf
