// A hit point: where a camera path first reached a diffuse surface (Hachisuka et al. 2008,
// section 4.1). Created once by the camera pass and fixed for the whole render.
#pragma once

#include <cstdint>

#include "core/math/vec3.h"

namespace pf {

// A hit point on a diffuse surface under no coat.
inline constexpr uint32_t kNoCoat = 0xffffffffu;

struct HitPoint {
    Vec3 position;   // world space
    Vec3 normal;     // unit shading normal, turned toward the camera path's side
    Rgb weight;      // camera-path throughput x diffuse BSDF (albedo / pi), 1/sr
    uint32_t pixel;  // y * width + x
    // The material whose coat covers the surface (light reaching the hit point crosses it:
    // core/shared/coat.h), or kNoCoat.
    uint32_t coat = kNoCoat;
};

}  // namespace pf
