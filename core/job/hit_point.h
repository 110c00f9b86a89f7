// A hit point: where a camera path first reached a diffuse surface (Hachisuka et al. 2008,
// section 4.1). Created once by the camera pass and fixed for the whole render.
#pragma once

#include <cstdint>

#include "core/math/vec3.h"

namespace pf {

struct HitPoint {
    Vec3 position;   // world space
    Vec3 normal;     // unit shading normal, turned toward the camera path's side
    Rgb weight;      // camera-path throughput x diffuse BSDF (albedo / pi), 1/sr
    uint32_t pixel;  // y * width + x
};

}  // namespace pf
