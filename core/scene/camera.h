// The camera in world space: a perspective one (glTF's pinhole, or pbrt's thin lens focused at
// a distance), pbrt's orthographic one, or pbrt's spherical one that sees every direction.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/geometry/ray.h"
#include "core/math/point2.h"
#include "core/math/vec3.h"
#include "core/shared/environment_map.h"

namespace pf {

enum class Projection : uint32_t {
    kPerspective,
    kOrthographic,  // parallel rays along `forward` from the screen window's points
    kSpherical,     // every direction, equirectangular or equal-area over the film (pbrt-v4's)
};

// The part of the image plane the film covers, x right and y up: for a perspective camera at
// unit distance (pbrt's screen window times tan(fov / 2)), for an orthographic one in world
// units.
struct ScreenWindow {
    float x_min = 0, x_max = 0, y_min = 0, y_max = 0;
    bool Given() const { return x_min < x_max && y_min < y_max; }
};

// How a pixel weighs the film around it (pbrt-v4's PixelFilter): a separable f(x) f(y) over
// [-radius, radius] pixels from the pixel's centre. Each camera sample is placed by sampling the
// filter (filter importance sampling, as pbrt-v4 does), so a pixel is the mean of its samples:
// box, triangle and Gaussian give every sample weight 1; Mitchell's and the windowed sinc's
// negative lobes give theirs a sign (core/scene/pixel_filter.h).
enum class FilterKind : uint32_t { kBox, kTriangle, kGaussian, kMitchell, kSinc };

struct PixelFilter {
    FilterKind kind = FilterKind::kBox;
    float radius_x = 0.5f, radius_y = 0.5f;  // pixels
    float sigma = 0.5f;                      // Gaussian: standard deviation, pixels
    float b = 1.0f / 3, c = 1.0f / 3;        // Mitchell-Netravali's B and C
    float tau = 3.0f;                        // windowed sinc: lobes of the Lanczos window
};

// How wide a pixel is where a camera path meets a surface `length` along it: base + length x
// angle (world units).
struct PixelFootprint {
    float base = 0, angle = 0;
};

struct Camera {
    Vec3 position;
    Vec3 forward{0, 0, -1}, right{1, 0, 0}, up{0, 1, 0};  // orthonormal, world space
    float y_fov = 0.8f;                                   // vertical field of view, radians
    float aspect_ratio = 0.0f;    // width / height from the scene; 0 when the scene gives none
    float lens_radius = 0.0f;     // world units; 0: a pinhole
    float focal_distance = 1e6f;  // along forward, world units: where the lens is in focus
    Projection projection = Projection::kPerspective;
    // Perspective and orthographic: the window the film covers; not given, a perspective
    // camera's is y_fov's tall and the film's aspect wide.
    ScreenWindow window;
    // Spherical: pbrt's "equalarea" mapping (1), else "equirectangular" (0). Not a bool: the
    // camera is written byte for byte into prepared scenes, and must have no padding.
    uint32_t equal_area = 1;
    // Each pixel's filter: pbrt's PixelFilter (its Gaussian where a pbrt file names none), a
    // box of one pixel for glTF.
    PixelFilter filter;

    bool HasLens() const { return lens_radius > 0 && projection == Projection::kPerspective; }

    // Ray through film position (x, y) in [0, 1)^2, x right and y down, for a film of the
    // given aspect ratio (width / height).
    Ray GenerateRay(float x, float y, float film_aspect) const {
        if (projection == Projection::kSpherical) return {position, SphericalDirection(x, y)};
        float sx, sy;
        if (window.Given()) {
            sx = window.x_min + (window.x_max - window.x_min) * x;
            sy = window.y_max - (window.y_max - window.y_min) * y;
        } else {
            const float tan_half = std::tan(0.5f * y_fov);
            sx = (2.0f * x - 1.0f) * tan_half * film_aspect;
            sy = (1.0f - 2.0f * y) * tan_half;
        }
        if (projection == Projection::kOrthographic)
            return {position + right * sx + up * sy, forward};
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
    // A pixel's width at distance `length` along a camera ray, for a film `height` pixels
    // tall: what textures and search radii are sized by.
    PixelFootprint Footprint(int height) const {
        const float rows = static_cast<float>(height);
        switch (projection) {
            case Projection::kOrthographic:
                return {(window.y_max - window.y_min) / rows, 0.0f};
            case Projection::kSpherical:
                return {0.0f, 3.14159265f / rows};
            case Projection::kPerspective:
                break;
        }
        const float tall =
            window.Given() ? window.y_max - window.y_min : 2.0f * std::tan(0.5f * y_fov);
        return {0.0f, tall / rows};
    }

private:
    // pbrt-v4's SphericalCamera: film (x, y) to a direction, camera +y up at the top row.
    Vec3 SphericalDirection(float x, float y) const {
        Vec3 d;  // camera space, pbrt's before its y-z swap
        if (equal_area) {
            // A filter's samples reach past the film's border: folded back into the square as
            // pbrt's WrapEqualAreaSquare does, where the sphere continues.
            if (x < 0) {
                x = -x, y = 1 - y;
            } else if (x > 1) {
                x = 2 - x, y = 1 - y;
            }
            if (y < 0) {
                x = 1 - x, y = -y;
            } else if (y > 1) {
                x = 1 - x, y = 2 - y;
            }
            d = gpu::EqualAreaSquareToSphere(Point2{x, y});
        } else {
            const float theta = 3.14159265f * y, phi = 2.0f * 3.14159265f * x;
            d = Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                     std::cos(theta));
        }
        return Normalize(right * d.x + up * d.z + forward * d.y);
    }
};

}  // namespace pf
