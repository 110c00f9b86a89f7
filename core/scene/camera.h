// A perspective camera in world space: a pinhole (glTF's camera model), or a thin lens
// focused at a distance (pbrt's lensradius and focaldistance).
#pragma once

#include <cmath>

#include "core/geometry/ray.h"
#include "core/math/point2.h"
#include "core/math/vec3.h"

namespace pf {

struct Camera {
    Vec3 position;
    Vec3 forward{0, 0, -1}, right{1, 0, 0}, up{0, 1, 0};  // orthonormal, world space
    float y_fov = 0.8f;                                   // vertical field of view, radians
    float aspect_ratio = 0.0f;    // width / height from the scene; 0 when the scene gives none
    float lens_radius = 0.0f;     // world units; 0: a pinhole
    float focal_distance = 1e6f;  // along forward, world units: where the lens is in focus

    bool HasLens() const { return lens_radius > 0; }

    // Ray through film position (x, y) in [0, 1)^2, x right and y down, for a film of the
    // given aspect ratio (width / height).
    Ray GenerateRay(float x, float y, float film_aspect) const {
        const float tan_half = std::tan(0.5f * y_fov);
        const float sx = (2.0f * x - 1.0f) * tan_half * film_aspect;
        const float sy = (1.0f - 2.0f * y) * tan_half;
        return {position, Normalize(forward + right * sx + up * sy)};
    }
    // The same through the point `lens` of the unit disk scaled to the lens: rays from the
    // lens meet at the pinhole ray's point `focal_distance` ahead (the plane in focus).
    Ray GenerateRay(float x, float y, float film_aspect, Point2 lens) const {
        const Ray pinhole = GenerateRay(x, y, film_aspect);
        if (!HasLens()) return pinhole;
        const Vec3 focus =
            position + pinhole.direction * (focal_distance / Dot(pinhole.direction, forward));
        const Vec3 origin = position + (right * lens.x + up * lens.y) * lens_radius;
        return {origin, Normalize(focus - origin)};
    }
    // Solid angle subtended by one pixel at the image centre, as a length per unit distance.
    float PixelAngle(int height) const {
        return 2.0f * std::tan(0.5f * y_fov) / static_cast<float>(height);
    }
};

}  // namespace pf
