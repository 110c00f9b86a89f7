// The pbrt-v4 importer's textures: the planar, spherical and cylindrical mappings against
// pbrt-v4's formulas at the vertices, and the scale, mix and directionmix textures against
// their values texel by texel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "tests/core/scene/pbrt_test_support.h"

namespace pf {
namespace {

using namespace pbrt_test;

// The texture coordinates of `scene`'s vertex where triangle t's corner c is.
Point2 CornerUv(const Scene& scene, uint32_t t, int c) {
    return scene.uvs[scene.triangles[t].vertex[c]];
}

TEST(PbrtTexturesTest, PlanarMappingProjectsRenderSpacePositions) {
    // pbrt-v4 takes the point in its render space, "cameraworld": the camera (at z = -5 in
    // Bundle's scene) is its origin. s = udelta + p . v1, t = vdelta + p . v2; photonfarm's v
    // is 1 - t.
    const std::string world =
        std::string(
            "Texture \"grid\" \"spectrum\" \"imagemap\" \"string filename\" \"g.png\" "
            "\"string mapping\" \"planar\" \"vector3 v1\" [0.5 0 0] \"vector3 v2\" "
            "[0 0 0.25] \"float udelta\" 0.1 \"float vdelta\" 0.2\n"
            "Material \"diffuse\" \"texture reflectance\" \"grid\"\n") +
        "Translate 0 0 3\n" + kQuad;
    const std::string png = TwoTexelPng({10, 20, 30, 40, 50, 60}, "photonfarm-grid.png");
    const absl::StatusOr<Scene> scene = Load(Bundle(world, {{"g.png", png}}));
    ASSERT_TRUE(scene.ok()) << scene.status();
    ASSERT_EQ(scene->uvs.size(), scene->positions.size());
    for (size_t v = 0; v < scene->positions.size(); ++v) {
        const Vec3 p = scene->positions[v] - Vec3(0, 0, -5);
        EXPECT_NEAR(scene->uvs[v].x, 0.1f + 0.5f * p.x, 1e-5f);
        EXPECT_NEAR(scene->uvs[v].y, 1 - (0.2f + 0.25f * p.z), 1e-5f);
    }
}

TEST(PbrtTexturesTest, SphericalAndCylindricalMappingsFollowPbrt) {
    // Spheres of radius 2 about (1, 0, 0) and (1, 0, 10), the textures' frames at (1, 0, 0)
    // (the transform current at the Texture directive); each triangle's corners are its own,
    // the angle about the axis unwrapped across the seam.
    const std::string png = TwoTexelPng({10, 20, 30, 40, 50, 60}, "photonfarm-globe.png");
    const std::string world =
        std::string("AttributeBegin\nTranslate 1 0 0\n") +
        "Texture \"globe\" \"spectrum\" \"imagemap\" \"string filename\" \"g.png\" "
        "\"string mapping\" \"spherical\"\n"
        "Texture \"can\" \"spectrum\" \"imagemap\" \"string filename\" \"g.png\" "
        "\"string mapping\" \"cylindrical\"\n"
        "Material \"diffuse\" \"texture reflectance\" \"globe\"\n"
        "Shape \"sphere\" \"float radius\" 2\n"
        "Material \"diffuse\" \"texture reflectance\" \"can\"\n"
        "Translate 0 0 10\nShape \"sphere\" \"float radius\" 2\nAttributeEnd\n";
    const absl::StatusOr<Scene> scene = Load(Bundle(world, {{"g.png", png}}));
    ASSERT_TRUE(scene.ok()) << scene.status();
    const uint32_t globe = scene->triangles[0].material;
    size_t seams = 0, checked = 0;
    for (uint32_t t = 0; t < scene->triangles.size(); ++t) {
        const bool spherical = scene->triangles[t].material == globe;
        const Vec3d centre(1, 0, 0);  // both textures' frames, whichever sphere
        for (int c = 0; c < 3; ++c) {
            const Vec3d d =
                Normalize(Vec3d(scene->positions[scene->triangles[t].vertex[c]]) - centre);
            const double phi = std::atan2(d.y, d.x);
            const Point2 uv = CornerUv(*scene, t, c);
            // s and t as pbrt-v4 (the angle about z up to whole turns), v = 1 - t.
            const double turn = spherical ? (phi < 0 ? phi + 2 * kPiD : phi) / (2 * kPiD)
                                          : (kPiD + phi) / (2 * kPiD);
            const double other = spherical ? std::acos(std::clamp(d.z, -1.0, 1.0)) / kPiD : 1 - d.z;
            EXPECT_NEAR(spherical ? uv.x : uv.y, other, 1e-4) << t << " " << c;
            if (d.x * d.x + d.y * d.y < 1e-10) continue;  // a pole: no angle about the axis
            const double got_turn = spherical ? 1 - uv.y : uv.x;
            const double whole = got_turn - turn;
            EXPECT_NEAR(whole, std::round(whole), 1e-4) << t << " " << c;
            seams += std::round(whole) != 0;
            ++checked;
        }
        // No triangle spans more than a small part of a turn (the pole's fans: the mean).
        const float a = spherical ? CornerUv(*scene, t, 0).y : CornerUv(*scene, t, 0).x;
        for (int c = 1; c < 3; ++c)
            EXPECT_LT(
                std::abs((spherical ? CornerUv(*scene, t, c).y : CornerUv(*scene, t, c).x) - a),
                0.1f)
                << t;
    }
    EXPECT_GT(checked, 1000u);
    EXPECT_GT(seams, 0u) << "some corner was unwrapped across the seam";
    ExpectError(Load(Bundle(std::string("Texture \"t\" \"spectrum\" \"imagemap\" \"string "
                                        "filename\" \"g.png\" \"string mapping\" \"conic\"\n") +
                                kQuad,
                            {{"g.png", png}})),
                "mapping \"conic\" is unknown");
}

TEST(PbrtTexturesTest, ScaleAndMixCombineTheirOperands) {
    // Two 2x1 images (sRGB 0/255 and 255/0 red; grey 128/255) and constants.
    const std::string red = TwoTexelPng({0, 0, 0, 255, 0, 0}, "photonfarm-red.png");
    const std::string grey = TwoTexelPng({128, 128, 128, 255, 255, 255}, "photonfarm-grey.png");
    const std::string world =
        std::string(
            "Texture \"red\" \"spectrum\" \"imagemap\" \"string filename\" \"red.png\"\n"
            "Texture \"grey\" \"float\" \"imagemap\" \"string filename\" \"grey.png\"\n"
            "Texture \"c\" \"spectrum\" \"constant\" \"rgb value\" [0.2 0.4 0.6]\n"
            // A constant: 0.5 x 0.2 + 0.5 x 0.6 (mix of constants).
            "Texture \"m0\" \"spectrum\" \"mix\" \"texture tex1\" \"c\" \"rgb tex2\" "
            "[0.6 0.6 0.6]\n"
            // An image scaled by a constant, either way round.
            "Texture \"s1\" \"spectrum\" \"scale\" \"texture tex\" \"red\" \"float scale\" 0.5\n"
            "Texture \"s2\" \"spectrum\" \"scale\" \"rgb tex\" [1 0.5 0.25] \"texture scale\" "
            "\"grey\"\n"
            // Baked: an image amount between two constants, and two images.
            "Texture \"m1\" \"spectrum\" \"mix\" \"rgb tex1\" [1 0 0] \"rgb tex2\" [0 0 1] "
            "\"texture amount\" \"grey\"\n"
            "Texture \"s3\" \"spectrum\" \"scale\" \"texture tex\" \"red\" \"texture scale\" "
            "\"grey\"\n"
            "Texture \"d\" \"spectrum\" \"directionmix\" \"texture tex1\" \"c\" \"rgb tex2\" "
            "[1 1 1] \"vector3 dir\" [0 0 1]\n") +
        "Material \"diffuse\" \"texture reflectance\" \"m0\"\n" + kQuad +
        "Material \"diffuse\" \"texture reflectance\" \"s1\"\n" + kQuad +
        "Material \"diffuse\" \"texture reflectance\" \"s2\"\n" + kQuad +
        "Material \"diffuse\" \"texture reflectance\" \"m1\"\n" + kQuad +
        "Material \"diffuse\" \"texture reflectance\" \"s3\"\n" + kQuad +
        "Material \"diffuse\" \"texture reflectance\" \"d\"\n" + kQuad;
    std::vector<std::string> warnings;
    const absl::StatusOr<Scene> scene =
        Load(Bundle(world, {{"red.png", red}, {"grey.png", grey}}), &warnings);
    ASSERT_TRUE(scene.ok()) << scene.status();
    const auto material = [&](int shape) {
        return scene->materials[scene->triangles[2 * shape].material];
    };
    // Each shape's colour at the left and right texel centres.
    const auto at = [&](int shape, float u) {
        const Material& m = material(shape);
        if (m.base_color_texture == kNoTexture) return m.base_color;
        return scene->textures[m.base_color_texture]->Sample(u, 0.5f) * m.base_color;
    };
    const float g = SrgbToLinear(128 / 255.0f);
    const auto near = [](const Rgb& got, const Rgb& expected) {
        return std::abs(got.x - expected.x) < 1e-5f && std::abs(got.y - expected.y) < 1e-5f &&
               std::abs(got.z - expected.z) < 1e-5f;
    };
    EXPECT_EQ(material(0).base_color_texture, kNoTexture);
    EXPECT_TRUE(near(at(0, 0.25f), Rgb(0.4f, 0.5f, 0.6f)));
    EXPECT_TRUE(near(at(1, 0.75f), Rgb(0.5f, 0.0f, 0.0f)));
    EXPECT_TRUE(near(at(1, 0.25f), Rgb(0.0f)));
    EXPECT_TRUE(near(at(2, 0.25f), Rgb(1.0f, 0.5f, 0.25f) * g));
    EXPECT_TRUE(near(at(3, 0.25f), Rgb(1 - g, 0.0f, g)));
    EXPECT_TRUE(near(at(3, 0.75f), Rgb(0.0f, 0.0f, 1.0f)));
    EXPECT_TRUE(near(at(4, 0.25f), Rgb(0.0f)));
    EXPECT_TRUE(near(at(4, 0.75f), Rgb(1.0f, 0.0f, 0.0f)));
    // directionmix: half of each, noted.
    EXPECT_TRUE(near(at(5, 0.5f), Rgb(0.6f, 0.7f, 0.8f)));
    EXPECT_TRUE(Contains(warnings, "taken as its mean over all directions"));
}

TEST(PbrtTexturesTest, TexturesNotEvaluatedAreNotedWithTheirStandIn) {
    // A texture class photonfarm does not evaluate (ptex), alone and as an operand of scale and
    // mix, in a reflectance and a roughness: each use is noted with the texture's name, class
    // and place, and the material's default stands in, never 1.
    const std::string world =
        "Texture \"p\" \"float\" \"ptex\" \"string filename\" \"p.ptx\"\n"  // line 6
        "Texture \"s\" \"spectrum\" \"scale\" \"rgb tex\" [0.9 0.9 0.9] "
        "\"texture scale\" \"p\"\n"                                                      // line 7
        "Texture \"m\" \"float\" \"mix\" \"float tex1\" 0.1 \"texture amount\" \"p\"\n"  // line 8
        "Material \"diffuse\" \"texture reflectance\" \"s\"\n" +
        std::string(kQuad) + "Material \"conductor\" \"texture roughness\" \"m\"\n" + kQuad;
    std::vector<std::string> warnings;
    const absl::StatusOr<Scene> scene = Load(Bundle(world), &warnings);
    ASSERT_TRUE(scene.ok()) << scene.status();
    const Material& diffuse = scene->materials[scene->triangles[0].material];
    EXPECT_EQ(diffuse.base_color_texture, kNoTexture);
    EXPECT_EQ(diffuse.base_color, Rgb(0.5f));  // pbrt-v4's diffuse default, not 1
    const Material& conductor = scene->materials[scene->triangles[2].material];
    EXPECT_EQ(conductor.roughness_texture, kNoTexture);
    EXPECT_EQ(conductor.roughness, 0.0f);  // the default roughness 0: a smooth conductor
    EXPECT_TRUE(Contains(warnings,
                         "Texture \"s\" (scale) at scenes/scene.pbrt:7:1 is not evaluated by "
                         "photonfarm: scale of Texture \"p\" (ptex) at scenes/scene.pbrt:6:1; "
                         "the material's default 0.5 stands in"))
        << ::testing::PrintToString(warnings);
    EXPECT_TRUE(Contains(warnings,
                         "Texture \"m\" (mix) at scenes/scene.pbrt:8:1 is not evaluated by "
                         "photonfarm: mix of Texture \"p\" (ptex) at scenes/scene.pbrt:6:1; its "
                         "default 0 stands in"))
        << ::testing::PrintToString(warnings);
}

}  // namespace
}  // namespace pf
