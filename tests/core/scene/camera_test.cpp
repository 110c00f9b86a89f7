// The thin-lens camera: rays from anywhere on the lens meet on the plane in focus, and the
// pinhole is the lens of radius zero.
#include "core/scene/camera.h"

#include <gtest/gtest.h>

namespace pf {
namespace {

Camera LensCamera() {
    Camera camera;
    camera.position = Vec3(1, 2, 3);
    camera.forward = Vec3(0, 0, -1);
    camera.right = Vec3(1, 0, 0);
    camera.up = Vec3(0, 1, 0);
    camera.lens_radius = 0.1f;
    camera.focal_distance = 4.0f;
    return camera;
}

TEST(CameraTest, LensRaysMeetOnThePlaneInFocus) {
    const Camera camera = LensCamera();
    for (const Point2& film : {Point2{0.5f, 0.5f}, Point2{0.1f, 0.8f}, Point2{0.95f, 0.05f}}) {
        const Ray pinhole = camera.GenerateRay(film.x, film.y, 1.5f);
        // The pinhole ray's point at depth focal_distance along forward.
        const Vec3 focus = pinhole.origin + pinhole.direction * (4.0f / -pinhole.direction.z);
        for (const Point2& lens :
             {Point2{0, 0}, Point2{1, 0}, Point2{-0.6f, 0.8f}, Point2{0.3f, -0.2f}}) {
            const Ray ray = camera.GenerateRay(film.x, film.y, 1.5f, lens);
            EXPECT_NEAR(Length(ray.direction), 1.0f, 1e-6f);
            // It leaves from the lens disk around the camera position...
            EXPECT_NEAR(ray.origin.x, 1 + 0.1f * lens.x, 1e-6f);
            EXPECT_NEAR(ray.origin.y, 2 + 0.1f * lens.y, 1e-6f);
            EXPECT_NEAR(ray.origin.z, 3.0f, 1e-6f);
            // ...and passes through the pinhole ray's point in focus.
            const float t = (focus.z - ray.origin.z) / ray.direction.z;
            const Vec3 at = ray.origin + ray.direction * t;
            EXPECT_NEAR(Length(at - focus), 0.0f, 1e-5f);
        }
    }
}

TEST(CameraTest, WithoutALensEveryRayIsThePinholes) {
    Camera camera = LensCamera();
    camera.lens_radius = 0;
    EXPECT_FALSE(camera.HasLens());
    const Ray pinhole = camera.GenerateRay(0.3f, 0.6f, 1.0f);
    const Ray lens = camera.GenerateRay(0.3f, 0.6f, 1.0f, Point2{0.9f, 0.1f});
    EXPECT_EQ(lens.origin, pinhole.origin);
    EXPECT_EQ(lens.direction, pinhole.direction);
}

}  // namespace
}  // namespace pf
