// The pbrt importer's lights as pbrt-v4 defines them: spot, distant and point lights, infinite
// lights uniform and from an image, and area lights with an image.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/film/color_space.h"
#include "core/film/exr_io.h"
#include "core/scene_io/scene_loader.h"
#include "core/shared/environment_map.h"
#include "tests/core/scene_io/pbrt_test_support.h"
#include "tests/support/test_env.h"

namespace pf {
namespace {

using namespace pbrt_test;

// The first emitting triangle's material.
const Material* EmittingMaterial(const Scene& scene) {
    for (const Triangle& triangle : scene.triangles)
        if (scene.materials[triangle.material].IsEmissive())
            return &scene.materials[triangle.material];
    return nullptr;
}

std::string ImageLight(const std::string& parameters) {
    return "AttributeBegin\nAreaLightSource \"diffuse\" \"string filename\" \"glow.exr\" " +
           parameters + "\n" + kQuad + "AttributeEnd\n";
}

TEST(PbrtLightsTest, AnAreaLightsImageIsItsEmissionTexture) {
    // L is the image times scale, over the shape's (u, v) with v up: a bilinear patch without
    // "uv" spans the unit square, p00 at the image's bottom left.
    absl::StatusOr<Scene> scene =
        Load(Bundle(ImageLight("\"float scale\" 2"), {{"glow.exr", ExrBytes(2, 1, 1.0f)}}));
    ASSERT_TRUE(scene.ok()) << scene.status();
    const Material* light = EmittingMaterial(*scene);
    ASSERT_NE(light, nullptr);
    EXPECT_EQ(light->emission, Rgb(2.0f));
    ASSERT_NE(light->emission_texture, kNoTexture);
    const Texture& image = *scene->textures[light->emission_texture];
    EXPECT_EQ(image.width, 2);
    EXPECT_EQ(image.texels[1], Rgb(1.0f, 1.0f, 2.0f));
    for (size_t v = 0; v < scene->positions.size(); ++v) {
        const Vec3& p = scene->positions[v];
        // (x, y) in [-1, 1]^2 -> (u, v) = ((x + 1) / 2, (y + 1) / 2), then v flipped.
        EXPECT_NEAR(scene->uvs[v].x, (p.x + 1) / 2, 1e-6f);
        EXPECT_NEAR(scene->uvs[v].y, 1 - (p.y + 1) / 2, 1e-6f);
    }
    // The emission at the card's points is the texel there (here the right texel's centre).
    SurfacePoint surface;
    surface.material = static_cast<uint32_t>(light - scene->materials.data());
    surface.uv = {0.75f, 0.5f};
    EXPECT_EQ(scene->Emission(surface), Rgb(2.0f, 2.0f, 4.0f));
}

TEST(PbrtLightsTest, TrianglesWithoutUvReadImagesAtPbrtsDefaultCoordinates) {
    // pbrt-v4 gives each triangle of a mesh without "uv" (0, 0), (1, 0), (1, 1) at its corners;
    // a mesh no texture reads keeps its shared vertices.
    const std::string mesh =
        "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 1 1 0 0 1 0] \"integer indices\" "
        "[0 1 2 0 2 3]\n";
    absl::StatusOr<Scene> scene = Load(
        Bundle("AttributeBegin\nAreaLightSource \"diffuse\" \"string filename\" \"glow.exr\"\n" +
                   mesh + "AttributeEnd\n",
               {{"glow.exr", ExrBytes(2, 1, 1.0f)}}));
    ASSERT_TRUE(scene.ok()) << scene.status();
    std::vector<Point2> corners;
    for (const Triangle& triangle : scene->triangles)
        if (scene->materials[triangle.material].IsEmissive())
            for (const uint32_t vertex : triangle.vertex) corners.push_back(scene->uvs[vertex]);
    ASSERT_EQ(corners.size(), 6u);
    // (u, v) then v flipped for the image: (0, 1), (1, 1), (1, 0) at each triangle's corners.
    for (size_t c = 0; c < corners.size(); ++c) {
        EXPECT_EQ(corners[c].x, c % 3 == 0 ? 0.0f : 1.0f) << c;
        EXPECT_EQ(corners[c].y, c % 3 == 2 ? 0.0f : 1.0f) << c;
    }
    absl::StatusOr<Scene> plain = Load(Bundle(mesh));
    ASSERT_TRUE(plain.ok()) << plain.status();
    EXPECT_EQ(plain->positions.size(), 4u);  // shared
}

TEST(PbrtLightsTest, AnImageLightsPowerCountsTheImagesMeanLuminance) {
    // "power" 10 W from a 2 x 2 card (area 4, one side): L = 10 / (pi 4 mean luminance), the
    // mean luminance of texels (1, 1, 2) being sRGB's Y of them.
    absl::StatusOr<Scene> scene =
        Load(Bundle(ImageLight("\"float power\" 10"), {{"glow.exr", ExrBytes(2, 1, 1.0f, false)}}));
    ASSERT_TRUE(scene.ok()) << scene.status();
    const Material* light = EmittingMaterial(*scene);
    ASSERT_NE(light, nullptr);
    const double luminance = SrgbLuminance({1, 1, 2});
    EXPECT_NEAR(light->emission.x, 10 / (kPiD * 4 * luminance), 1e-5);
}

TEST(PbrtLightsTest, ImageLightRefusalsNameTheirPlace) {
    ExpectError(Load(Bundle(ImageLight("\"rgb L\" [1 1 1]"), {{"glow.exr", ExrBytes(2, 1, 1)}})),
                "scenes/scene.pbrt:7:1: AreaLightSource: give \"L\" or \"filename\", not both");
    ExpectError(Load(Bundle(ImageLight(""))), "glow.exr");
    ExpectError(Load(Bundle(ImageLight(""), {{"glow.exr", "not an image"}})),
                "scenes/scene.pbrt:7:1: AreaLightSource: glow.exr");
}

TEST(PbrtLightsTest, PackingGathersAreaLightImages) {
    const std::filesystem::path folder = testing::ProcessTempDir() / "image-light-scene";
    std::filesystem::create_directories(folder / "textures");
    const SceneBundle written =
        Bundle("AreaLightSource \"diffuse\" \"string filename\" \"textures/glow.exr\"\n" +
               std::string(kQuad));
    std::ofstream(folder / "scene.pbrt") << written.files.at("scene.pbrt");
    std::ofstream(folder / "textures" / "glow.exr", std::ios::binary) << ExrBytes(2, 2, 1.0f);
    const absl::StatusOr<SceneBundle> bundle = PackSceneBundle((folder / "scene.pbrt").string());
    ASSERT_TRUE(bundle.ok()) << bundle.status();
    EXPECT_TRUE(bundle->files.contains("textures/glow.exr"));
    const absl::StatusOr<Scene> scene = LoadScene(*bundle, "scene.pbrt");
    ASSERT_TRUE(scene.ok()) << scene.status();
    ASSERT_NE(EmittingMaterial(*scene), nullptr);
    EXPECT_NE(EmittingMaterial(*scene)->emission_texture, kNoTexture);
}

// A w x h EXR whose texel i is (values[i], values[i], values[i]).
std::string GreyExr(int width, int height, const std::vector<float>& values) {
    Image image(width, height);
    for (size_t i = 0; i < values.size(); ++i) image.pixels[i] = Rgb(values[i]);
    const std::string path = testing::TempPath("pbrt-light-image.exr");
    EXPECT_TRUE(WriteExr(path, image).ok());
    absl::StatusOr<std::string> bytes = ReadWholeFile(path);
    return bytes.ok() ? *bytes : std::string();
}

TEST(PbrtLightsTest, GoniometricLightsAsPbrtV4DefinesThem) {
    // A 3 x 3 map, its centre texel 9 and the rest 1, under pbrt-v4's swap of y and z: the
    // light's +y is the square's centre, its -y the corners. "power" P: I = P / (4 pi mean).
    const std::string map = GreyExr(3, 3, {1, 1, 1, 1, 9, 1, 1, 1, 1});
    absl::StatusOr<Scene> scene =
        Load(Bundle("AttributeBegin\nTranslate 1 2 3\nLightSource \"goniometric\" \"string "
                    "filename\" \"g.exr\" \"rgb I\" [2 2 2]\nAttributeEnd\n" +
                        std::string(kQuad),
                    {{"g.exr", map}}));
    ASSERT_TRUE(scene.ok()) << scene.status();
    ASSERT_EQ(scene->lights.size(), 2u);  // the bundle's point light, then this
    const PunctualLight& light = scene->lights[1];
    EXPECT_EQ(light.type, LightType::kGoniometric);
    EXPECT_EQ(light.position, Vec3(1, 2, 3));
    EXPECT_NEAR(light.intensity.x, 2.0f, 5e-3f);
    EXPECT_EQ(light.ImageFactor({0, 1, 0}), Rgb(9.0f));
    EXPECT_EQ(light.ImageFactor({0, -1, 0}), Rgb(1.0f));
    absl::StatusOr<Scene> powered = Load(
        Bundle("LightSource \"goniometric\" \"string filename\" \"g.exr\" \"float power\" 100\n" +
                   std::string(kQuad),
               {{"g.exr", map}}));
    ASSERT_TRUE(powered.ok()) << powered.status();
    EXPECT_NEAR(powered->lights[1].intensity.x, 100 / (4 * kPiD * 17.0 / 9), 1e-3);
    ExpectError(Load(Bundle("LightSource \"goniometric\"\n" + std::string(kQuad))),
                "scenes/scene.pbrt:6:1: LightSource \"goniometric\" needs \"string filename\"");
    ExpectError(Load(Bundle("LightSource \"goniometric\" \"string filename\" \"g.exr\"\n" +
                                std::string(kQuad),
                            {{"g.exr", GreyExr(2, 1, {1, 1})}})),
                "is 2x1; pbrt-v4's goniometric images are equal-area squares");
}

TEST(PbrtLightsTest, ProjectionLightsAsPbrtV4DefinesThem) {
    // A 1 x 2 image (top 5, bottom 7) through a 60 degree frustum along +z: the top row
    // toward the light's +y (pbrt-v4's flip), nothing outside tan(30 degrees).
    absl::StatusOr<Scene> scene =
        Load(Bundle("LightSource \"projection\" \"string filename\" \"p.exr\" \"float fov\" 60 "
                    "\"float scale\" 2\n" +
                        std::string(kQuad),
                    {{"p.exr", GreyExr(1, 2, {5, 7})}}));
    ASSERT_TRUE(scene.ok()) << scene.status();
    const PunctualLight& light = scene->lights[1];
    EXPECT_EQ(light.type, LightType::kProjection);
    EXPECT_EQ(light.intensity, Rgb(2.0f));
    EXPECT_NEAR(light.tan_half_fov, std::tan(kPiD / 6), 1e-6);
    EXPECT_EQ(light.ImageFactor(Normalize(Vec3(0, 0.5f, 1))), Rgb(5.0f));
    EXPECT_EQ(light.ImageFactor(Normalize(Vec3(0, -0.5f, 1))), Rgb(7.0f));
    EXPECT_EQ(light.ImageFactor(Normalize(Vec3(0.6f, 0, 1))), Rgb(0.0f));  // x / z > tan 30
    ExpectError(Load(Bundle("LightSource \"projection\" \"string filename\" \"p.exr\" \"float "
                            "fov\" 180\n" +
                                std::string(kQuad),
                            {{"p.exr", GreyExr(1, 2, {5, 7})}})),
                "fov in (0, 180)");
}

TEST(PbrtLightsTest, AnInfiniteLightsPortalIsAWorldSpaceRectangle) {
    // pbrt-v4 takes the corners in world space (the light's transform turns its map, not its
    // portal) and faces the portal p03 x p01, toward the environment.
    const absl::StatusOr<Scene> scene =
        Load(Bundle("AttributeBegin\nRotate 90 1 0 0\nLightSource \"infinite\" \"rgb L\" [1 1 1] "
                    "\"point3 portal\" [0 0 2  0 1 2  1 1 2  1 0 2]\nAttributeEnd\n" +
                    std::string(kQuad)));
    ASSERT_TRUE(scene.ok()) << scene.status();
    ASSERT_TRUE(scene->environment && scene->environment->portal);
    const EnvironmentPortal& portal = *scene->environment->portal;
    EXPECT_EQ(portal.corner, Vec3(0, 0, 2));
    EXPECT_EQ(portal.edge_u, Vec3(0, 1, 0));
    EXPECT_EQ(portal.edge_v, Vec3(1, 0, 0));
    EXPECT_NEAR(portal.normal.z, 1, 1e-6f);  // x cross y
    ExpectError(Load(Bundle("LightSource \"infinite\" \"point3 portal\" [0 0 2  0 1 2  1 1 2]\n" +
                            std::string(kQuad))),
                "scenes/scene.pbrt:6:1: LightSource \"infinite\": \"portal\" takes the 4 corners "
                "of a rectangle, not 3");
    ExpectError(
        Load(Bundle("LightSource \"infinite\" \"point3 portal\" [0 0 2  0 1 2  1 1 3  1 0 2]\n" +
                    std::string(kQuad))),
        "\"portal\": its corners are not a rectangle");
}

TEST(PbrtLoaderTest, LightsTakePbrtsParameters) {
    SceneBundle bundle = Bundle(kQuad);
    bundle.files["scene.pbrt"] +=
        "LightSource \"spot\" \"point3 from\" [0 0 1] \"point3 to\" [0 0 0] \"float coneangle\" 30 "
        "\"float conedeltaangle\" 10 "
        "\"blackbody I\" 6500\n"
        "AttributeBegin\nRotate 90 1 0 0\nLightSource \"distant\" \"point3 from\" [0 0 0] \"point3 "
        "to\" [0 0 1] \"rgb L\" [3 3 3]\nAttributeEnd\n"
        "LightSource \"point\" \"rgb I\" [1 1 1] \"float power\" 100\n";
    const absl::StatusOr<Scene> scene = Load(bundle);
    ASSERT_TRUE(scene.ok()) << scene.status();
    ASSERT_EQ(scene->lights.size(), 4u);
    const PunctualLight& spot = scene->lights[1];
    EXPECT_EQ(spot.type, LightType::kSpot);
    EXPECT_NEAR(spot.direction.z, -1.0f, 1e-6f);
    EXPECT_NEAR(spot.cos_outer, std::cos(30 * kPiD / 180), 1e-6);
    EXPECT_NEAR(spot.cos_inner, std::cos(20 * kPiD / 180), 1e-6);
    EXPECT_TRUE(spot.smooth_falloff);
    // pbrt's smoothstep in the cosine between the cones: t^2 (3 - 2t).
    const double t = (std::cos(25 * kPiD / 180) - std::cos(30 * kPiD / 180)) /
                     (std::cos(20 * kPiD / 180) - std::cos(30 * kPiD / 180));
    EXPECT_NEAR(spot.SpotFalloff(std::cos(25 * kPiD / 180)), t * t * (3 - 2 * t), 1e-5);
    // 6500 K is close to D65 white, with luminance 1.
    EXPECT_NEAR(
        0.2126f * spot.intensity.x + 0.7152f * spot.intensity.y + 0.0722f * spot.intensity.z, 1.0f,
        1e-3f);
    EXPECT_NEAR(spot.intensity.x / spot.intensity.z, 1.0f, 0.05f);
    const PunctualLight& distant = scene->lights[2];
    EXPECT_EQ(distant.type, LightType::kDirectional);
    EXPECT_NEAR(distant.direction.y, -1.0f, 1e-6f);  // +z turned 90 degrees about x travels -y
    EXPECT_NEAR(distant.intensity.x, 3.0f, 1e-6f);
    // "power" 100 W from a point light: I = 100 / (4 pi) W/sr.
    EXPECT_NEAR(scene->lights[3].intensity.x, 100 / (4 * kPiD), 1e-4);
}

TEST(PbrtLoaderTest, InfiniteLightsAsPbrtV4DefinesThem) {
    // Uniform: L x scale, and the colour space's illuminant (white) when L is absent;
    // "illuminance" E scales a uniform light to L = E / pi.
    absl::StatusOr<Scene> uniform = Load(
        Bundle(std::string("LightSource \"infinite\" \"rgb L\" [0.2 0.4 0.6] \"float scale\" 2\n") +
               kQuad));
    ASSERT_TRUE(uniform.ok()) << uniform.status();
    ASSERT_TRUE(uniform->environment.has_value());
    EXPECT_EQ(uniform->environment->mapping, EnvironmentMapping::kUniform);
    EXPECT_NEAR(uniform->environment->scale.z, 1.2f, 1e-6f);
    absl::StatusOr<Scene> lux =
        Load(Bundle(std::string("LightSource \"infinite\" \"float illuminance\" 10\n") + kQuad));
    ASSERT_TRUE(lux.ok()) << lux.status();
    EXPECT_NEAR(lux->environment->scale.x, 10 / kPi, 1e-5f);
    // Two uniform lights add up.
    absl::StatusOr<Scene> two = Load(
        Bundle(std::string("LightSource \"infinite\" \"rgb L\" [1 1 1]\nLightSource \"infinite\" "
                           "\"rgb L\" [0 1 0]\n") +
               kQuad));
    ASSERT_TRUE(two.ok()) << two.status();
    EXPECT_EQ(two->environment->scale, Rgb(1, 2, 1));

    // An image: an equal-area square in the light's frame, which the transform turns.
    absl::StatusOr<Scene> map = Load(
        Bundle(std::string("AttributeBegin\nRotate -90 1 0 0\nLightSource \"infinite\" \"string "
                           "filename\" \"sky.exr\" \"float scale\" 0.5\nAttributeEnd\n") +
                   kQuad,
               {{"sky.exr", ExrBytes(4, 4, 1.0f)}}));
    ASSERT_TRUE(map.ok()) << map.status();
    const Environment& environment = *map->environment;
    EXPECT_EQ(environment.mapping, EnvironmentMapping::kEqualArea);
    EXPECT_EQ(environment.image.width, 4);
    // Rotate -90 about x takes the light's +z to world +y (pbrt's usual "z up" map made "y up").
    const Vec3 up = environment.ToWorld(Vec3(0, 0, 1));
    EXPECT_NEAR(up.y, 1.0f, 1e-5f);
    for (const Vec3& world : {Vec3(0, 1, 0), Vec3(0.3f, -0.5f, 0.81f), Vec3(-1, 0, 0)}) {
        const Vec3 d = Normalize(world);
        const Point2 uv = EqualAreaSphereToSquare(Vec3(d.x, -d.z, d.y));  // world -> light frame
        const int texel = std::min(3, int(uv.y * 4)) * 4 + std::min(3, int(uv.x * 4));
        EXPECT_EQ(environment.Radiance(d), Rgb(float(texel), 1, 2) * 0.5f) << texel;
    }
    // "illuminance" with an image: scaled by E over the map's upper-hemisphere illuminance as
    // pbrt-v4 sums it (lights.cpp), with 2 pi / texels of solid angle a texel where a texel
    // spans 4 pi / texels: a flat map of radiance L sums to pi L / 2, so E asks for L = 2 E / pi
    // (twice the plain reading; pbrt-v4's pictures are what a scene's author saw).
    absl::StatusOr<Scene> lit =
        Load(Bundle(std::string("LightSource \"infinite\" \"string filename\" \"sky.exr\" \"float "
                                "illuminance\" 3.14159265\n") +
                        kQuad,
                    {{"sky.exr", ExrBytes(64, 64, 1.0f, false)}}));
    ASSERT_TRUE(lit.ok()) << lit.status();
    const float luminance = 0.2126f + 0.7152f + 0.0722f * 2;
    EXPECT_NEAR(lit->environment->scale.x * luminance, 2.0f, 0.02f);

    // What pbrt-v4 refuses, refused with the place.
    ExpectError(Load(Bundle(std::string("LightSource \"infinite\" \"string filename\" "
                                        "\"sky.exr\"\n") +
                                kQuad,
                            {{"sky.exr", ExrBytes(8, 4, 1.0f)}})),
                "scenes/scene.pbrt:6:1: LightSource \"infinite\": sky.exr is 8x4");
    ExpectError(Load(Bundle(std::string("LightSource \"infinite\" \"rgb L\" [1 1 1] \"string "
                                        "filename\" \"sky.exr\"\n") +
                                kQuad,
                            {{"sky.exr", ExrBytes(4, 4, 1.0f)}})),
                "not both");
    ExpectError(Load(Bundle(std::string("LightSource \"infinite\" \"float power\" 3\n") + kQuad)),
                "no \"power\"");
    ExpectError(Load(Bundle(std::string("Scale 1 2 1\nLightSource \"infinite\"\n") + kQuad)),
                "must be a rotation");
    ExpectError(Load(Bundle(std::string("LightSource \"infinite\" \"string filename\" "
                                        "\"absent.exr\"\n") +
                            kQuad)),
                "absent.exr");
}

}  // namespace
}  // namespace pf
