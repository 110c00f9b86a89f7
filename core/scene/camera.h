// A pinhole perspective camera in world space (glTF's camera model).
#pragma once

#include <cmath>

#include "core/geometry/ray.h"
#include "core/math/vec3.h"

namespace pf {

struct Camera {
    Vec3 position;
    Vec3 forward{0, 0, -1}, right{1, 0, 0}, up{0, 1, 0};  // orthonormal, world space
    float y_fov = 0.8f;          // vertical field of view, radians
    float aspect_ratio = 0.0f;   // width / height from the scene; 0 when the scene gives none

    // Ray through film position (x, y) in [0, 1)^2, x right and y down, for a film of the
    // given aspect ratio (width / height).
    Ray GenerateRay(float x, float y, float film_aspect) const {
        const float tan_half = std::tan(0.5f * y_fov);
        const float sx = (2.0f * x - 1.0f) * tan_half * film_aspect;
        const float sy = (1.0f - 2.0f * y) * tan_half;
        return {position, Normalize(forward + right * sx + up * sy)};
    }
    // Solid angle subtended by one pixel at the image centre, as a length per unit distance.
    float PixelAngle(int height) const { return 2.0f * std::tan(0.5f * y_fov) / static_cast<float>(height); }
};

}  // namespace pf
