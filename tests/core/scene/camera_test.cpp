// The cameras: a thin lens's rays meet on the plane in focus and the pinhole is the lens of
// radius zero; orthographic rays leave the screen window in parallel; a screen window crops a
// perspective view; spherical cameras map the film to directions as pbrt-v4 does.
#include "core/scene/camera.h"

#include <gtest/gtest.h>

#include <cmath>

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

Camera LookingDownMinusZ() {
    Camera camera;  // at the origin, forward -z, right +x, up +y
    return camera;
}

TEST(CameraTest, OrthographicRaysAreParallelFromTheScreenWindow) {
    Camera camera = LookingDownMinusZ();
    camera.projection = Projection::kOrthographic;
    camera.window = {-2, 2, -1, 1};
    const Ray corner = camera.GenerateRay(0, 0, 2.0f);  // the film's top left
    EXPECT_EQ(corner.origin, Vec3(-2, 1, 0));
    EXPECT_EQ(corner.direction, Vec3(0, 0, -1));
    const Ray centre = camera.GenerateRay(0.5f, 0.5f, 2.0f);
    EXPECT_EQ(centre.origin, Vec3(0, 0, 0));
    EXPECT_EQ(centre.direction, Vec3(0, 0, -1));
    EXPECT_FALSE(camera.HasLens());
    EXPECT_EQ(camera.Footprint(100).base, 0.02f);  // 2 units over 100 rows
    EXPECT_EQ(camera.Footprint(100).angle, 0.0f);
}

TEST(CameraTest, AScreenWindowCropsThePerspectiveView) {
    Camera camera = LookingDownMinusZ();
    camera.window = {0, 1, 0, 0.5f};  // the upper right part of a 90-degree view, at unit distance
    const Ray corner = camera.GenerateRay(1, 0, 1.0f);  // the film's top right
    EXPECT_NEAR(corner.direction.x, 1 / std::sqrt(2.25f), 1e-6f);
    EXPECT_NEAR(corner.direction.y, 0.5f / std::sqrt(2.25f), 1e-6f);
    EXPECT_NEAR(camera.Footprint(50).angle, 0.01f, 1e-7f);
}

TEST(CameraTest, SphericalCamerasSeeEveryDirectionAsPbrtMapsThem) {
    Camera camera = LookingDownMinusZ();
    camera.projection = Projection::kSpherical;
    camera.equal_area = 0;  // equirectangular: theta = pi y from up, phi = 2 pi x from right
    auto near = [](const Vec3& a, const Vec3& b) { return Length(a - b) < 1e-5f; };
    EXPECT_TRUE(near(camera.GenerateRay(0.3f, 0.0f, 1).direction, Vec3(0, 1, 0)));    // up
    EXPECT_TRUE(near(camera.GenerateRay(0.0f, 0.5f, 1).direction, Vec3(1, 0, 0)));    // right
    EXPECT_TRUE(near(camera.GenerateRay(0.25f, 0.5f, 1).direction, Vec3(0, 0, -1)));  // forward
    EXPECT_TRUE(near(camera.GenerateRay(0.5f, 1.0f, 1).direction, Vec3(0, -1, 0)));   // down
    camera.equal_area = 1;  // the octahedral square: its centre is up, its corners down
    EXPECT_TRUE(near(camera.GenerateRay(0.5f, 0.5f, 1).direction, Vec3(0, 1, 0)));
    EXPECT_TRUE(near(camera.GenerateRay(0.0f, 0.0f, 1).direction, Vec3(0, -1, 0)));
    EXPECT_EQ(camera.GenerateRay(0.7f, 0.2f, 1).origin, Vec3(0, 0, 0));
    // A pixel filter's samples reach past the film's border: folded back as pbrt's
    // WrapEqualAreaSquare folds them, where the sphere continues across the square's edge.
    EXPECT_TRUE(near(camera.GenerateRay(-0.05f, 0.3f, 1).direction,
                     camera.GenerateRay(0.05f, 0.7f, 1).direction));
    EXPECT_TRUE(near(camera.GenerateRay(0.2f, 1.04f, 1).direction,
                     camera.GenerateRay(0.8f, 0.96f, 1).direction));
    EXPECT_TRUE(near(camera.GenerateRay(-0.01f, 0.5f, 1).direction,
                     camera.GenerateRay(0.01f, 0.5f, 1).direction))
        << "the square's edge is a seam of the sphere";
}

}  // namespace
}  // namespace pf
