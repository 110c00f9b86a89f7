// The pbrt-v4 importer's textures: the planar, spherical and cylindrical mappings against
// pbrt-v4's formulas at the vertices, the scale, mix and directionmix textures against their
// values texel by texel, the procedural ones (noise, dots, 3D checkerboard) at points against
// pbrt-v4's formulas in the texture's space, and what photonfarm does not evaluate noted.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/shared/noise.h"
#include "core/shared/procedural_texture.h"
#include "tests/core/scene_io/pbrt_test_support.h"

namespace pf {
namespace {

using namespace pbrt_test;

bool Near(const Rgb& a, const Rgb& b, float tolerance = 1e-5f) {
    return std::abs(a.x - b.x) <= tolerance && std::abs(a.y - b.y) <= tolerance &&
           std::abs(a.z - b.z) <= tolerance;
}

// The texture coordinates of `scene`'s vertex where triangle t's corner c is.
Point2 CornerUv(const Scene& scene, uint32_t t, int c) {
    return scene.uvs[scene.triangles[t].vertex[c]];
}

TEST(PbrtTexturesTest, PlanarMappingProjectsPointsInTheTexturesSpace) {
    // pbrt-v4 takes the point through its textureFromRender, the inverse of the transform
    // current at the Texture directive (here a move by (1, 0, 0)): s = udelta + q . v1,
    // t = vdelta + q . v2; photonfarm's v is 1 - t. The camera's place (its render space's
    // origin) cancels; the shape's own transform does not enter.
    const std::string world =
        std::string(
            "AttributeBegin\nTranslate 1 0 0\n"
            "Texture \"grid\" \"spectrum\" \"imagemap\" \"string filename\" \"g.png\" "
            "\"string mapping\" \"planar\" \"vector3 v1\" [0.5 0 0] \"vector3 v2\" "
            "[0 0 0.25] \"float udelta\" 0.1 \"float vdelta\" 0.2\nAttributeEnd\n"
            "Material \"diffuse\" \"texture reflectance\" \"grid\"\n") +
        "Translate 0 0 3\n" + kQuad;
    const std::string png = TwoTexelPng({10, 20, 30, 40, 50, 60}, "photonfarm-grid.png");
    const absl::StatusOr<Scene> scene = Load(Bundle(world, {{"g.png", png}}));
    ASSERT_TRUE(scene.ok()) << scene.status();
    ASSERT_EQ(scene->uvs.size(), scene->positions.size());
    for (size_t v = 0; v < scene->positions.size(); ++v) {
        const Vec3 q = scene->positions[v] - Vec3(1, 0, 0);
        EXPECT_NEAR(scene->uvs[v].x, 0.1f + 0.5f * q.x, 1e-5f);
        EXPECT_NEAR(scene->uvs[v].y, 1 - (0.2f + 0.25f * q.z), 1e-5f);
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
            "[1 1 1] \"vector3 dir\" [0 0 1]\n"
            // directionmix of an image: its texture word is numbered once the images are.
            "Texture \"d2\" \"spectrum\" \"directionmix\" \"texture tex1\" \"red\" \"rgb tex2\" "
            "[0 0 1] \"vector3 dir\" [0 0 1]\n") +
        "Material \"diffuse\" \"texture reflectance\" \"m0\"\n" + kQuad +
        "Material \"diffuse\" \"texture reflectance\" \"s1\"\n" + kQuad +
        "Material \"diffuse\" \"texture reflectance\" \"s2\"\n" + kQuad +
        "Material \"diffuse\" \"texture reflectance\" \"m1\"\n" + kQuad +
        "Material \"diffuse\" \"texture reflectance\" \"s3\"\n" + kQuad +
        "Material \"diffuse\" \"texture reflectance\" \"d\"\n" + kQuad +
        "Material \"diffuse\" \"texture reflectance\" \"d2\"\n" + kQuad;
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
    // directionmix: |n . dir| of tex1, the rest of tex2; the quad faces z: all of tex1.
    ASSERT_TRUE(scene->textures[material(5).base_color_texture]->IsProcedural());
    SurfacePoint point;
    point.geometric_normal = Vec3(0, 0, -1);
    EXPECT_TRUE(
        near(scene->TextureValue(material(5).base_color_texture, point), Rgb(0.2f, 0.4f, 0.6f)));
    point.geometric_normal = Normalize(Vec3(0, 1, 1));
    EXPECT_TRUE(near(scene->TextureValue(material(5).base_color_texture, point),
                     Rgb(0.2f, 0.4f, 0.6f) * std::sqrt(0.5f) + Rgb(1 - std::sqrt(0.5f))));
    const int32_t d2 = material(6).base_color_texture;
    ASSERT_TRUE(scene->textures[d2]->IsProcedural());
    point.uv = {0.75f, 0.5f};
    point.geometric_normal = Vec3(0, 0, 1);
    EXPECT_TRUE(near(scene->TextureValue(d2, point), Rgb(1.0f, 0.0f, 0.0f)));
    point.geometric_normal = Normalize(Vec3(0, 1, 1));
    EXPECT_TRUE(
        near(scene->TextureValue(d2, point), Rgb(std::sqrt(0.5f), 0.0f, 1 - std::sqrt(0.5f))));
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

// A point of `scene`'s triangle t at barycentrics (b1, b2), as Scene::Surface makes it.
SurfacePoint PointOn(const Scene& scene, uint32_t t, float b1, float b2) {
    RayHit hit;
    hit.triangle = t, hit.b1 = b1, hit.b2 = b2, hit.instance = Instance::kNone;
    return scene.Surface(hit);
}

TEST(PbrtTexturesTest, NoiseTexturesAreEvaluatedInTheirOwnSpace) {
    // Noise textures defined under a transform (x2, then moved by 0.5 in x), read by shapes
    // placed under another: pbrt-v4 takes the world point through the inverse of the
    // texture's transform, not the shape's.
    const std::string world =
        std::string(
            "AttributeBegin\nTranslate 0.5 0 0\nScale 2 2 2\n"
            "Texture \"w\" \"float\" \"wrinkled\" \"float roughness\" 0.3 \"integer octaves\" 5\n"
            "Texture \"f\" \"float\" \"fbm\"\n"
            "Texture \"wind\" \"float\" \"windy\"\n"
            "Texture \"m\" \"spectrum\" \"marble\" \"float scale\" 3 \"float variation\" 0.5\n"
            "AttributeEnd\n"
            "Texture \"s\" \"spectrum\" \"scale\" \"rgb tex\" [0.9 0.6 0.3] \"texture scale\" "
            "\"w\"\n"
            "Material \"diffuse\" \"texture reflectance\" \"s\"\n"
            "AttributeBegin\nTranslate 0 0 3\nRotate 30 0 0 1\n") +
        kQuad +
        "Material \"conductor\" \"texture roughness\" \"f\"\n"
        "Translate 0 0 1\n" +
        kQuad +
        "Texture \"sw\" \"spectrum\" \"scale\" \"texture scale\" \"wind\"\n"
        "Material \"diffuse\" \"texture reflectance\" \"sw\"\n"
        "Translate 0 0 1\n" +
        kQuad +
        "Material \"diffuse\" \"texture reflectance\" \"m\"\n"
        "Translate 0 0 1\n" +
        kQuad + "AttributeEnd\n";
    std::vector<std::string> warnings;
    const absl::StatusOr<Scene> scene = Load(Bundle(world), &warnings);
    ASSERT_TRUE(scene.ok()) << scene.status();
    EXPECT_TRUE(warnings.empty()) << ::testing::PrintToString(warnings);
    const auto in_texture_space = [](const Vec3& p) { return (p - Vec3(0.5f, 0, 0)) * 0.5f; };
    int checked = 0;
    for (const auto& [b1, b2] : {std::pair{0.1f, 0.2f}, std::pair{0.6f, 0.3f},
                                 std::pair{0.33f, 0.33f}, std::pair{0.05f, 0.9f}}) {
        // Each quad's first triangle.
        const SurfacePoint wrinkled = PointOn(*scene, 0, b1, b2);
        const Vec3 q = in_texture_space(wrinkled.position);
        const float turbulence = gpu::Turbulence(q, 0.0f, 0.3f, 5);
        EXPECT_TRUE(
            Near(scene->BaseColor(wrinkled), Min(Rgb(0.9f, 0.6f, 0.3f) * turbulence, Rgb(1.0f))))
            << q.x << " " << q.y << " " << q.z;
        // A roughness texture's values map to GGX alpha as pbrt-v4's RoughnessToAlpha, sqrt.
        const SurfacePoint rough = PointOn(*scene, 2, b1, b2);
        std::optional<Material> scratch;
        const Material& shading = scene->ShadingMaterial(rough, scratch);
        const float fbm = gpu::FractalNoise(in_texture_space(rough.position), 0.0f, 0.5f, 8);
        EXPECT_NEAR(shading.roughness, std::clamp(std::sqrt(std::max(fbm, 0.0f)), 1e-3f, 1.0f),
                    1e-5f);
        const SurfacePoint windy = PointOn(*scene, 4, b1, b2);
        EXPECT_NEAR(scene->BaseColor(windy).x,
                    std::clamp(gpu::WindyNoise(in_texture_space(windy.position), 0.0f), 0.0f, 1.0f),
                    1e-6f);
        // Marble: its scale multiplies the point in the texture's space.
        const SurfacePoint marble = PointOn(*scene, 6, b1, b2);
        EXPECT_TRUE(Near(
            scene->BaseColor(marble),
            Min(gpu::MarbleColourAt(in_texture_space(marble.position) * 3.0f, 0.0f, 0.5f, 8, 0.5f),
                Rgb(1.0f))));
        ++checked;
    }
    EXPECT_EQ(checked, 4);
    // The quads moved: the noise differs from quad to quad, as the points do.
    EXPECT_NE(scene->BaseColor(PointOn(*scene, 0, 0.2f, 0.2f)).x,
              scene->BaseColor(PointOn(*scene, 4, 0.2f, 0.2f)).x);
    ExpectError(Load(Bundle("Texture \"w\" \"float\" \"wrinkled\" \"float roughness\" 1e39\n")),
                "Texture \"w\" (wrinkled): its parameters must be finite");
}

TEST(PbrtTexturesTest, DotsAndCheckerboardsAreEvaluatedAtEachPoint) {
    // dots over (s, t) = (8u, 8v): pbrt-v4 shows "outside" in its dots and "inside" between
    // them (DotsTexture::Create hands them over in that order); a 3D checkerboard in x, y, z;
    // a 2D checkerboard of textures; scale of a procedural texture.
    const std::string world =
        std::string(
            "Texture \"d\" \"spectrum\" \"dots\" \"rgb inside\" [1 0 0] \"rgb outside\" [0 0 1] "
            "\"float uscale\" 8 \"float vscale\" 8\n"
            "Texture \"c3\" \"spectrum\" \"checkerboard\" \"integer dimension\" 3 "
            "\"rgb tex1\" [0.8 0.8 0.8] \"rgb tex2\" [0.1 0.2 0.3]\n"
            "Texture \"f\" \"spectrum\" \"scale\" \"texture tex\" \"d\" \"float scale\" 0.5\n"
            "Texture \"c2\" \"spectrum\" \"checkerboard\" \"texture tex1\" \"f\" "
            "\"rgb tex2\" [0 1 0]\n"
            "Material \"diffuse\" \"texture reflectance\" \"d\"\n") +
        kQuad + "Material \"diffuse\" \"texture reflectance\" \"c3\"\n" + kQuad +
        "Material \"diffuse\" \"texture reflectance\" \"c2\"\n" + kQuad;
    std::vector<std::string> warnings;
    const absl::StatusOr<Scene> scene = Load(Bundle(world), &warnings);
    ASSERT_TRUE(scene.ok()) << scene.status();
    EXPECT_TRUE(warnings.empty()) << ::testing::PrintToString(warnings);
    // The dots' mapping is the material's: the mesh's coordinates are its (s, t).
    const Scene& s = *scene;
    const uint32_t dots = s.materials[s.triangles[0].material].base_color_texture;
    ASSERT_NE(dots, kNoTexture);
    int inside = 0, outside = 0;
    for (int cell_s = 1; cell_s < 7; ++cell_s)
        for (int cell_t = 1; cell_t < 7; ++cell_t) {
            SurfacePoint point = PointOn(s, 0, 0.1f, 0.1f);
            const auto noise = [](float x, float y) { return gpu::PerlinNoise(Vec3(x, y, 0.5f)); };
            point.uv = {cell_s + 0.15f * noise(cell_s + 1.5f, cell_t + 2.8f),
                        cell_t + 0.15f * noise(cell_s + 4.5f, cell_t + 9.8f)};
            const bool dot = noise(cell_s + 0.5f, cell_t + 0.5f) > 0;
            EXPECT_EQ(s.TextureValue(dots, point), dot ? Rgb(0, 0, 1) : Rgb(1, 0, 0));
            (dot ? inside : outside) += 1;
        }
    EXPECT_GT(inside, 3);
    EXPECT_GT(outside, 3);
    const auto corner_uv = [&](uint32_t t, int c) { return s.uvs[s.triangles[t].vertex[c]]; };
    for (int c = 0; c < 3; ++c) {
        const Vec3 p = s.positions[s.triangles[0].vertex[c]];
        // bilinearmesh's (u, v) is (0, 0) to (1, 1) over the quad from (-1, -1) to (1, 1).
        EXPECT_NEAR(corner_uv(0, c).x, 8 * (p.x + 1) / 2, 1e-5f);
        EXPECT_NEAR(corner_uv(0, c).y, 8 * (p.y + 1) / 2, 1e-5f);
    }
    // The 3D checkerboard: tex1 where floor(x) + floor(y) + floor(z) is even.
    const uint32_t solid = s.materials[s.triangles[2].material].base_color_texture;
    for (const Vec3& p : {Vec3(0.5f, 0.5f, 0), Vec3(-0.5f, 0.5f, 0), Vec3(-0.5f, -0.5f, 0)}) {
        SurfacePoint point;
        point.position = p;
        const int sum = int(std::floor(p.x)) + int(std::floor(p.y)) + int(std::floor(p.z));
        EXPECT_EQ(s.TextureValue(solid, point), sum % 2 == 0 ? Rgb(0.8f) : Rgb(0.1f, 0.2f, 0.3f));
    }
    // A checkerboard of the scaled dots, in its own (s, t) = (u, v) while the dots read
    // (8u, 8v): the material's coordinates are the dots' (their mapping comes first).
    const uint32_t checks = s.materials[s.triangles[4].material].base_color_texture;
    for (const auto& [u, v] : {std::pair{0.3f, 0.6f}, std::pair{1.4f, 0.2f}}) {
        SurfacePoint point;
        point.uv = {8 * u, 8 * v};
        SurfacePoint dots_point = point;
        const Rgb expected = (int(std::floor(u)) + int(std::floor(v))) % 2 == 0
                                 ? s.TextureValue(dots, dots_point) * 0.5f
                                 : Rgb(0, 1, 0);
        EXPECT_EQ(s.TextureValue(checks, point), expected) << u << " " << v;
    }
}

TEST(PbrtTexturesTest, ProceduralCutOutsAreNoted) {
    // Cut-outs are tested during traversal, where the kernels read images: a procedural texture
    // there is noted, its default standing in.
    const std::string world = std::string(
        "Texture \"d\" \"float\" \"dots\"\n"
        "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0] "
        "\"texture alpha\" \"d\"\n");
    std::vector<std::string> warnings;
    const absl::StatusOr<Scene> scene = Load(Bundle(world), &warnings);
    ASSERT_TRUE(scene.ok()) << scene.status();
    const Material& material = scene->materials[scene->triangles[0].material];
    EXPECT_EQ(material.alpha_texture, kNoTexture);
    EXPECT_EQ(material.alpha, 1.0f);
    EXPECT_TRUE(Contains(warnings,
                         "Shape: \"alpha\": Texture \"d\" (dots) at "
                         "scenes/scene.pbrt:6:1 is evaluated at each point, and "
                         "cut-outs read images; its default 1 stands in"))
        << ::testing::PrintToString(warnings);
}

TEST(PbrtTexturesTest, ProceduralBumpMapsTiltTheNormalAsTheMovedSurfaceDoes) {
    // A plane z = 0 displaced along its normal n = (0, 0, s) by d(x, y) (fbm x 0.05) is
    // (x, y, s d): its normal is (-dd/dx, -dd/dy, s) normalised, whatever (u, v) it carries
    // (three octaves: smooth enough for the differences of both to agree closely).
    const std::string world =
        "Texture \"f\" \"float\" \"fbm\" \"integer octaves\" 3\n"
        "Texture \"d\" \"float\" \"scale\" \"texture tex\" \"f\" \"float scale\" 0.05\n"
        "Material \"diffuse\" \"texture displacement\" \"d\"\n" +
        std::string(kQuad);
    std::vector<std::string> warnings;
    const absl::StatusOr<Scene> scene = Load(Bundle(world), &warnings);
    ASSERT_TRUE(scene.ok()) << scene.status();
    EXPECT_TRUE(warnings.empty()) << ::testing::PrintToString(warnings);
    const Material& material = scene->materials[scene->triangles[0].material];
    ASSERT_NE(material.bump_texture, kNoTexture);
    const auto displacement = [&](const Vec3& p) {
        SurfacePoint at;
        at.position = p;
        return scene->TextureValue(material.bump_texture, at).x;
    };
    int tilted = 0;
    for (const auto& [b1, b2] :
         {std::pair{0.2f, 0.3f}, std::pair{0.6f, 0.1f}, std::pair{0.3f, 0.5f}}) {
        const SurfacePoint surface = PointOn(*scene, 0, b1, b2);
        const float s = surface.geometric_normal.z;
        ASSERT_NEAR(std::abs(s), 1.0f, 1e-6f);
        const float h = 1e-3f;
        const Vec3 p = surface.position;
        const float dx =
            (displacement(p + Vec3(h, 0, 0)) - displacement(p - Vec3(h, 0, 0))) / (2 * h);
        const float dy =
            (displacement(p + Vec3(0, h, 0)) - displacement(p - Vec3(0, h, 0))) / (2 * h);
        const Vec3 expected = Normalize(Vec3(-dx, -dy, s));
        EXPECT_NEAR(surface.shading_normal.x, expected.x, 2e-3f) << b1 << " " << b2;
        EXPECT_NEAR(surface.shading_normal.y, expected.y, 2e-3f) << b1 << " " << b2;
        tilted += std::abs(expected.x) + std::abs(expected.y) > 0.01f;
    }
    EXPECT_GT(tilted, 0) << "the bump tilts the normal somewhere";
    // fbm swings both ways, and pbrt-v4's BumpMap reads a displacement as it is: no clamp at 0.
    float lowest = 0, highest = 0;
    for (int i = 0; i < 400; ++i) {
        const float d = displacement(Vec3(0.37f * float(i % 20), 0.29f * float(i / 20), 0));
        lowest = std::min(lowest, d), highest = std::max(highest, d);
    }
    EXPECT_LT(lowest, -0.005f);
    EXPECT_GT(highest, 0.005f);
}

}  // namespace
}  // namespace pf
