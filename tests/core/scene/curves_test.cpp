// Curves (pbrt-v4's "curve" shape): its parameters read as pbrt-v4 defines them, bad ones refused
// at file:line, instances placing them; the surface a hit on each type is, against points and
// normals worked out by hand; the ray test the Vulkan backend runs (core/shared/curve.h), here
// on the CPU, against distances to the curve measured independently; and their prepared
// form, round trip and hostile.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "core/scene/mesh_builder.h"
#include "core/scene/prepared_scene.h"
#include "core/shared/curve.h"
#include "tests/core/scene_io/pbrt_test_support.h"

namespace pf {
namespace {

using namespace pbrt_test;

void ExpectNear(const Vec3& a, const Vec3& b, float tolerance, const std::string& what) {
    EXPECT_NEAR(a.x, b.x, tolerance) << what;
    EXPECT_NEAR(a.y, b.y, tolerance) << what;
    EXPECT_NEAR(a.z, b.z, tolerance) << what;
}

Vec3 Bezier(const Curve& c, float u) {
    return gpu::BezierPoint(c.control[0], c.control[1], c.control[2], c.control[3], u);
}

TEST(CurvesTest, EachBasisAndDegreeBecomesTheSameCurveInBezierSegments) {
    const Scene scene = *Load(Bundle(
        "Shape \"curve\" \"point3 P\" [0 0 0  1 1 0  2 -1 0  3 0 0  4 1 1  5 0 2  6 0 0] "
        "\"float width0\" 0.2 \"float width1\" 0.1\n"
        "Shape \"curve\" \"point3 P\" [0 0 0  1 2 0  2 0 1] \"integer degree\" 2\n"
        "Shape \"curve\" \"string basis\" \"bspline\" \"point3 P\" [0 0 0  1 2 0  2 0 1  3 3 3  "
        "4 0 0] \"string type\" \"cylinder\"\n"
        "Shape \"curve\" \"string basis\" \"bspline\" \"integer degree\" 2 \"point3 P\" "
        "[0 0 0  1 2 0  2 0 1  3 3 3] \"float width\" 0.5 \"integer splitdepth\" 5\n"));
    ASSERT_EQ(scene.curves.size(), 2u + 1 + 2 + 2);
    EXPECT_TRUE(scene.triangles.empty());
    // Bezier, degree 3: segments share their ends; the width runs linearly along the curve.
    const Curve& first = scene.curves[0];
    ExpectNear(first.control[3], Vec3(3, 0, 0), 0, "end of segment 0");
    ExpectNear(scene.curves[1].control[0], Vec3(3, 0, 0), 0, "start of segment 1");
    ExpectNear(scene.curves[1].control[3], Vec3(6, 0, 0), 0, "end of segment 1");
    EXPECT_FLOAT_EQ(first.width[0], 0.2f);
    EXPECT_FLOAT_EQ(first.width[1], 0.15f);
    EXPECT_FLOAT_EQ(scene.curves[1].width[1], 0.1f);
    EXPECT_EQ(first.type, CurveType::kFlat);
    EXPECT_FLOAT_EQ(scene.curves[2].width[0], 1.0f) << "pbrt-v4's default width";
    // Degree 2 Bezier: the cubic is the quadratic (1-u)^2 p0 + 2u(1-u) p1 + u^2 p2.
    for (float u : {0.0f, 0.25f, 0.6f, 1.0f}) {
        const Vec3 quadratic = Vec3(0, 0, 0) * ((1 - u) * (1 - u)) +
                               Vec3(1, 2, 0) * (2 * u * (1 - u)) + Vec3(2, 0, 1) * (u * u);
        ExpectNear(Bezier(scene.curves[2], u), quadratic, 1e-6f, "quadratic Bezier");
    }
    // Uniform B-splines: segment i at u is sum_k B_k(u) P[i + k], with the cubic basis
    // ((1-u)^3, 3u^3 - 6u^2 + 4, -3u^3 + 3u^2 + 3u + 1, u^3) / 6 and the quadratic
    // ((1-u)^2, -2u^2 + 2u + 1, u^2) / 2.
    const std::vector<Vec3> p = {{0, 0, 0}, {1, 2, 0}, {2, 0, 1}, {3, 3, 3}, {4, 0, 0}};
    for (int s = 0; s < 2; ++s)
        for (float u : {0.0f, 0.3f, 0.8f, 1.0f}) {
            const float b[4] = {(1 - u) * (1 - u) * (1 - u), 3 * u * u * u - 6 * u * u + 4,
                                -3 * u * u * u + 3 * u * u + 3 * u + 1, u * u * u};
            Vec3 cubic(0.0f), quadratic(0.0f);
            for (int k = 0; k < 4; ++k) cubic += p[s + k] * (b[k] / 6);
            const float q[3] = {(1 - u) * (1 - u), -2 * u * u + 2 * u + 1, u * u};
            for (int k = 0; k < 3; ++k) quadratic += p[s + k] * (q[k] / 2);
            ExpectNear(Bezier(scene.curves[3 + s], u), cubic, 1e-5f, "cubic B-spline");
            ExpectNear(Bezier(scene.curves[5 + s], u), quadratic, 1e-5f, "quadratic B-spline");
        }
    EXPECT_EQ(scene.curves[3].type, CurveType::kCylinder);
    EXPECT_FLOAT_EQ(scene.curves[5].width[1], 0.5f);
}

TEST(CurvesTest, TransformsPlaceThePointsAndScaleTheWidthAndRibbonsKeepTheirNormals) {
    std::vector<std::string> warnings;
    const Scene scene = *Load(Bundle("AttributeBegin\nTranslate 1 0 0\nScale 2 2 2\n"
                                     "Shape \"curve\" \"point3 P\" [0 0 0  1 0 0  2 0 0  3 0 0] "
                                     "\"float width\" 0.1 \"string type\" \"ribbon\" "
                                     "\"normal N\" [0 0 3  0 2 0]\nAttributeEnd\n"
                                     "Shape \"curve\" \"point3 P\" [0 0 0  1 0 0  2 0 0  3 0 0] "
                                     "\"normal N\" [0 0 1  0 0 1]\n"),
                              &warnings);
    ASSERT_EQ(scene.curves.size(), 2u);
    const Curve& ribbon = scene.curves[0];
    ExpectNear(ribbon.control[0], Vec3(1, 0, 0), 0, "translated");
    ExpectNear(ribbon.control[3], Vec3(7, 0, 0), 0, "scaled");
    EXPECT_FLOAT_EQ(ribbon.width[0], 0.2f);
    ExpectNear(ribbon.normal[0], Vec3(0, 0, 1), 1e-6f, "a normal, made unit");
    ExpectNear(ribbon.normal[1], Vec3(0, 1, 0), 1e-6f, "the far end's");
    EXPECT_TRUE(Contains(warnings, "scene.pbrt:11:1: warning: Shape \"curve\": \"normal N\""));
}

TEST(CurvesTest, BadCurvesAreRefusedAtTheirLine) {
    const auto refused = [](const std::string& shape, const std::string& fragment) {
        SCOPED_TRACE(shape);
        ExpectError(Load(Bundle("\n" + shape + "\n")),
                    "scenes/scene.pbrt:7:1: Shape \"curve\": " + fragment);
    };
    refused("Shape \"curve\" \"point3 P\" [0 0 0  1 0 0  2 0 0  3 0 0  4 0 0]",
            "\"point3 P\" has 5 points: a degree 3 bezier curve needs 4 + n x 3");
    refused("Shape \"curve\" \"point3 P\" [0 0 0  1 0 0] \"string basis\" \"bspline\"",
            "\"point3 P\" has 2 points: a degree 3 bspline curve needs 4 or more");
    refused("Shape \"curve\" \"point3 P\" [0 0 0  1 0 0  2 0 0  3 0 0] \"string basis\" \"nurbs\"",
            "\"basis\" \"nurbs\" is unknown");
    refused("Shape \"curve\" \"point3 P\" [0 0 0  1 0 0  2 0 0  3 0 0] \"integer degree\" 4",
            "\"degree\" 4 is neither 2 nor 3");
    refused("Shape \"curve\" \"point3 P\" [0 0 0  1 0 0  2 0 0  3 0 0] \"string type\" \"tube\"",
            "\"type\" \"tube\" is unknown");
    refused("Shape \"curve\" \"point3 P\" [0 0 0  1 0 0  2 0 0  3 0 0] \"string type\" \"ribbon\"",
            "a ribbon of 1 segments needs 2 \"normal N\", not 0");
    refused("Shape \"curve\" \"point3 P\" [0 0 0  1 0 0  2 0 0  3 0 0] \"float width\" -1",
            "its widths must be finite and not negative");
    refused(
        "Shape \"curve\" \"point3 P\" [0 0 0  1 0 0  2 0 0  3 0 0] \"string type\" \"ribbon\" "
        "\"normal N\" [0 0 1  0 0 0]",
        "\"normal N\" 1 is zero or not finite");
    refused("Shape \"curve\"", "\"point3 P\" has 0 points");
}

TEST(CurvesTest, AreaLightsOnCurvesAreWarnedAndCurvesAloneMakeAScene) {
    std::vector<std::string> warnings;
    const absl::StatusOr<Scene> scene =
        Load(Bundle("AreaLightSource \"diffuse\" \"rgb L\" [1 1 1]\n"
                    "Shape \"curve\" \"point3 P\" [0 0 0  1 0 0  2 0 0  3 0 0]\n"),
             &warnings);
    ASSERT_TRUE(scene.ok()) << scene.status();
    EXPECT_TRUE(Contains(warnings, "an area light on a curve"));
    ASSERT_EQ(scene->curves.size(), 1u);
    EXPECT_FALSE(scene->materials[scene->curves[0].material].IsEmissive());
    // The bounds hold the band: half a width beyond the points.
    EXPECT_FLOAT_EQ(scene->bounds.lower.y, -0.5f);
    EXPECT_FLOAT_EQ(scene->bounds.upper.x, 3.5f);
}

TEST(CurvesTest, InstancesPlaceTheirObjectsCurves) {
    const Scene scene = *Load(
        Bundle("ObjectBegin \"tuft\"\nShape \"curve\" \"point3 P\" [0 0 0  0 1 0  0 2 0  0 3 0] "
               "\"float width\" 0.1\nObjectEnd\n"
               "AttributeBegin\nTranslate 5 0 0\nObjectInstance \"tuft\"\nAttributeEnd\n"
               "AttributeBegin\nScale 2 2 2\nObjectInstance \"tuft\"\nAttributeEnd\n"));
    ASSERT_EQ(scene.prototypes.size(), 1u);
    EXPECT_EQ(scene.prototypes[0].curve_count, 1u);
    EXPECT_EQ(scene.WorldCurveCount(), 0u);
    ASSERT_EQ(scene.instances.size(), 2u);
    const Curve second = scene.WorldCurve(0, 1);
    ExpectNear(second.control[3], Vec3(0, 6, 0), 1e-6f, "the scaled instance's end");
    EXPECT_FLOAT_EQ(second.width[0], 0.2f);
    const absl::StatusOr<Scene> flat = FlattenInstances(scene, 100, 100);
    ASSERT_TRUE(flat.ok()) << flat.status();
    ASSERT_EQ(flat->curves.size(), 2u);
    ExpectNear(flat->curves[0].control[0], Vec3(5, 0, 0), 0, "the translated instance's start");
    EXPECT_FLOAT_EQ(flat->curves[1].width[1], 0.2f);
    EXPECT_EQ(FlattenInstances(scene, 100, 1).status().code(),
              absl::StatusCode::kResourceExhausted);
    EXPECT_NEAR(scene.bounds.upper.y, 6.1f, 1e-6f) << "the bounds hold the scaled band";
}

// A straight curve along x from (-1, 0, 0) to (1, 0, 0), evenly spaced control points (so x is
// linear in u: x = 2u - 1), width 0.2, of `type`; ribbons' normals (0, 1, 1) / sqrt(2).
Scene StraightCurve(CurveType type) {
    Scene scene;
    scene.materials.push_back(Material{});
    Curve curve;
    curve.control = {Vec3(-1, 0, 0), Vec3(-1.0f / 3, 0, 0), Vec3(1.0f / 3, 0, 0), Vec3(1, 0, 0)};
    curve.width = {0.2f, 0.2f};
    const Vec3 n = Normalize(Vec3(0, 1, 1));
    curve.normal = {n, n};
    curve.type = type;
    scene.curves.push_back(curve);
    return scene;
}

// The ray test of core/shared/curve.h on a scene's curve 0 (t, u, v; t = -1 for a miss).
std::array<float, 3> Intersect(const Scene& scene, const Vec3& origin, const Vec3& direction) {
    const Curve& c = scene.curves[0];
    float t = 0, u = 0, v = 0;
    if (!gpu::IntersectCurve(origin, direction, 1e30f, c.control[0], c.control[1], c.control[2],
                             c.control[3], c.width[0], c.width[1], static_cast<uint32_t>(c.type),
                             c.normal[0], c.normal[1], t, u, v))
        return {-1, 0, 0};
    return {t, u, v};
}

SurfacePoint SurfaceOf(const Scene& scene, const Vec3& origin, const Vec3& direction, float t,
                       float u) {
    RayHit hit;
    hit.triangle = gpu::kCurveBit | 0;
    hit.t = t, hit.b1 = u, hit.origin = origin, hit.direction = direction;
    return scene.Surface(hit);
}

TEST(CurveSurfaceTest, ACylinderMetHeadOnHasARoundTubesNormal) {
    // A ray down +z at (0.3, 0.05): half the radius (0.1) above the axis. By hand: u = 0.65,
    // t = 5 (pbrt-v4 takes the axis's depth), v = 0.5 + 0.05 / 0.2 = 0.75 (toward
    // cross(direction, tangent) = +y); a tube's normal where the offset is half the radius:
    // (0, 1/2, -sqrt(3)/2); the point one width in front of the band.
    const Scene scene = StraightCurve(CurveType::kCylinder);
    const Vec3 origin(0.3f, 0.05f, -5), direction(0, 0, 1);
    const auto [t, u, v] = Intersect(scene, origin, direction);
    EXPECT_NEAR(t, 5.0f, 1e-5f);
    EXPECT_NEAR(u, 0.65f, 1e-5f);
    EXPECT_NEAR(v, 0.75f, 1e-5f);
    const SurfacePoint surface = SurfaceOf(scene, origin, direction, t, u);
    ExpectNear(surface.shading_normal, Vec3(0, 0.5f, -std::sqrt(3.0f) / 2), 1e-5f, "tube normal");
    ExpectNear(surface.geometric_normal, Vec3(0, 0, -1), 1e-6f, "facing the ray");
    ExpectNear(surface.position, Vec3(0.3f, 0.05f, -0.2f), 1e-5f, "in front of the band");
    EXPECT_NEAR(surface.uv.y, 0.75f, 1e-5f) << "v from the hit point (the CPU's way)";
    // Below the axis the normal turns down; at the edge it is across the ray.
    EXPECT_LT(SurfaceOf(scene, Vec3(0.3f, -0.05f, -5), direction, 5, 0.65f).shading_normal.y, 0);
    EXPECT_NEAR(SurfaceOf(scene, Vec3(0.3f, 0.1f, -5), direction, 5, 0.65f).shading_normal.y, 1,
                1e-5f);
}

TEST(CurveSurfaceTest, AFlatCurveFacesTheRayAcrossItsWidth) {
    const Scene scene = StraightCurve(CurveType::kFlat);
    // Met within half its width (0.1) of the axis, missed beyond; seen from either side, it
    // faces the ray.
    EXPECT_GT(Intersect(scene, Vec3(0, 0.099f, -5), Vec3(0, 0, 1))[0], 0);
    EXPECT_LT(Intersect(scene, Vec3(0, 0.101f, -5), Vec3(0, 0, 1))[0], 0);
    EXPECT_LT(Intersect(scene, Vec3(-1.05f, 0, -5), Vec3(0, 0, 1))[0], 0) << "beyond its end";
    for (const Vec3& direction : {Vec3(0, 0, 1), Vec3(0, 0, -1), Normalize(Vec3(0, -1, 1))}) {
        const Vec3 origin = Vec3(0.5f, 0.02f, 0) - direction * 5;
        const auto [t, u, v] = Intersect(scene, origin, direction);
        ASSERT_GT(t, 0);
        const SurfacePoint surface = SurfaceOf(scene, origin, direction, t, u);
        ExpectNear(surface.geometric_normal, direction * -1.0f, 1e-5f, "facing the ray");
        ExpectNear(surface.shading_normal, surface.geometric_normal, 0, "flat");
    }
    // A tapered curve is as wide as its widths say where it is met: 0.3 at u = 0, 0.1 at 1.
    Scene tapered = scene;
    tapered.curves[0].width = {0.3f, 0.1f};
    EXPECT_GT(Intersect(tapered, Vec3(-0.5f, 0.099f, -5), Vec3(0, 0, 1))[0], 0);  // u = 1/4: 0.25
    EXPECT_LT(Intersect(tapered, Vec3(0.5f, 0.099f, -5), Vec3(0, 0, 1))[0], 0);   // u = 3/4: 0.15
    EXPECT_GT(Intersect(tapered, Vec3(0.5f, 0.074f, -5), Vec3(0, 0, 1))[0], 0);
}

TEST(CurveSurfaceTest, ARibbonKeepsItsNormalAndNarrowsSeenObliquely) {
    // Normal (0, 1, 1) / sqrt(2): seen down +z the band (0.2 wide) spans 0.2 cos 45 = 0.141.
    const Scene scene = StraightCurve(CurveType::kRibbon);
    const Vec3 direction(0, 0, 1);
    EXPECT_GT(Intersect(scene, Vec3(0, 0.069f, -5), direction)[0], 0);
    EXPECT_LT(Intersect(scene, Vec3(0, 0.072f, -5), direction)[0], 0);
    // The band's plane through the axis is z = -y: met at (0.2, 0.06, -0.06), which is 0.085
    // across it (along (0, 1, -1) / sqrt(2)): v = 0.5 + 0.085 / 0.2.
    const Vec3 origin(0.2f, 0.06f, -5);
    const SurfacePoint surface = SurfaceOf(scene, origin, direction, 5 - 0.06f, 0.6f);
    const Vec3 n = Normalize(Vec3(0, 1, 1));
    ExpectNear(surface.geometric_normal, n, 1e-6f, "its own normal, whichever side is met");
    ExpectNear(surface.shading_normal, n, 1e-6f, "its own normal");
    EXPECT_NEAR(surface.uv.y, 0.5f + 0.06f * std::sqrt(2.0f) / 0.2f, 1e-5f);
    EXPECT_NEAR(Intersect(scene, origin, direction)[2], surface.uv.y, 1e-5f)
        << "the ray test's v, from the projected distance, is the same";
    // Its normals turn from one end's to the other's, a quarter turn: 45 degrees half way.
    Scene turning = scene;
    turning.curves[0].normal = {Vec3(0, 0, 1), Vec3(0, 1, 0)};
    const SurfacePoint middle = SurfaceOf(turning, Vec3(0, 0, -5), direction, 5, 0.5f);
    ExpectNear(middle.geometric_normal, n, 1e-5f, "half way");
}

// The distance in the xy plane from (x, y) to the curve's centre line, and the u there, by
// sampling it densely (independent of the subdivision the ray test makes).
std::pair<float, float> DistanceToCurve(const Curve& c, float x, float y) {
    float best = 1e30f, best_u = 0;
    for (int i = 0; i <= 4000; ++i) {
        const float u = float(i) / 4000;
        const Vec3 p = Bezier(c, u);
        const float d = std::hypot(p.x - x, p.y - y);
        if (d < best) best = d, best_u = u;
    }
    return {best, best_u};
}

TEST(CurveIntersectTest, RaysMeetABentCurveExactlyWhereItsWidthCovers) {
    // A bent, tapered flat curve in the plane z = 1, rays down +z over a grid: met where the
    // curve's centre line passes within half its width there, missed where not (a margin of
    // 5% of the width either side, for the pieces' chords), never beyond its ends.
    Scene scene = StraightCurve(CurveType::kFlat);
    Curve& c = scene.curves[0];
    c.control = {Vec3(-1, -0.5f, 1), Vec3(-0.3f, 1.2f, 1), Vec3(0.4f, -1.0f, 1), Vec3(1, 0.6f, 1)};
    c.width = {0.12f, 0.04f};
    int met = 0, checked = 0;
    for (int i = 0; i < 80; ++i)
        for (int j = 0; j < 60; ++j) {
            const float x = -0.95f + 1.9f * (i + 0.5f) / 80, y = -0.6f + 1.2f * (j + 0.5f) / 60;
            const auto [distance, u] = DistanceToCurve(c, x, y);
            if (u < 0.01f || u > 0.99f) continue;  // the ends' caps are pbrt-v4's own
            const float half = 0.5f * (c.width[0] + (c.width[1] - c.width[0]) * u);
            if (std::abs(distance - half) < 0.05f * 2 * half) continue;
            const auto [t, hit_u, v] = Intersect(scene, Vec3(x, y, -1), Vec3(0, 0, 1));
            ++checked;
            EXPECT_EQ(t > 0, distance < half) << "at " << x << ", " << y;
            if (t > 0) {
                ++met;
                EXPECT_NEAR(t, 2.0f, 1e-4f);
                EXPECT_NEAR(hit_u, u, 0.01f) << "at " << x << ", " << y;
                EXPECT_NEAR(std::abs(v - 0.5f) * 2 * half, distance, 0.05f * 2 * half);
            }
        }
    EXPECT_GT(met, 200) << "of " << checked << ": the test must exercise hits";
}

TEST(CurvesPreparedTest, CurvesRoundTripAndHostileOnesAreRefused) {
    Scene scene = *Load(Bundle(
        "ObjectBegin \"o\"\nShape \"curve\" \"point3 P\" [0 0 0  0 1 0  0 2 0  0 3 0]\nObjectEnd\n"
        "ObjectInstance \"o\"\n"
        "Shape \"curve\" \"point3 P\" [0 0 0  1 0 0  2 0 0  3 0 0] \"string type\" \"ribbon\" "
        "\"normal N\" [0 0 1  0 1 0] \"float width0\" 0.3 \"float width1\" 0\n" +
        std::string(kQuad)));
    ASSERT_EQ(scene.curves.size(), 2u);
    const absl::StatusOr<Scene> decoded = DecodePreparedScene(EncodePreparedScene(scene), false);
    ASSERT_TRUE(decoded.ok()) << decoded.status();
    ASSERT_EQ(decoded->curves.size(), 2u);
    for (size_t c = 0; c < 2; ++c) {
        EXPECT_EQ(decoded->curves[c].control, scene.curves[c].control);
        EXPECT_EQ(decoded->curves[c].width, scene.curves[c].width);
        EXPECT_EQ(decoded->curves[c].normal, scene.curves[c].normal);
        EXPECT_EQ(decoded->curves[c].type, scene.curves[c].type);
        EXPECT_EQ(decoded->curves[c].material, scene.curves[c].material);
    }
    EXPECT_EQ(decoded->prototypes[0].first_curve, 1u);
    EXPECT_EQ(decoded->prototypes[0].curve_count, 1u);
    const auto refused = [&](const std::string& fragment, auto&& spoil) {
        Scene bad = scene;
        spoil(bad);
        const absl::StatusOr<Scene> result = DecodePreparedScene(EncodePreparedScene(bad), false);
        ASSERT_FALSE(result.ok()) << fragment;
        EXPECT_NE(result.status().message().find(fragment), std::string::npos) << result.status();
    };
    refused("curve 0 uses material 99", [](Scene& s) { s.curves[0].material = 99; });
    refused("curve 1: a point or normal not finite",
            [](Scene& s) { s.curves[1].control[2].y = std::nanf(""); });
    refused("curve 0: widths -1 and 0", [](Scene& s) { s.curves[0].width = {-1, 0}; });
    refused("curve 0: widths 0 and 0", [](Scene& s) { s.curves[0].width = {0, 0}; });
    refused("curve 0: a ribbon normal not of unit length",
            [](Scene& s) { s.curves[0].normal[1] = Vec3(0, 2, 0); });
    refused("curve 1: unknown type 7", [](Scene& s) { s.curves[1].type = CurveType(7); });
    refused("prototype 0: curves out of range", [](Scene& s) { s.prototypes[0].curve_count = 5; });
    refused("curve 0 emits light", [](Scene& s) {
        s.materials.push_back(Material{});
        s.materials.back().emission = Rgb(1.0f);
        s.curves[0].material = static_cast<uint32_t>(s.materials.size() - 1);
    });
}

}  // namespace
}  // namespace pf
