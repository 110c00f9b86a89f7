// The pbrt importer's lights as pbrt-v4 defines them: area lights with an image.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/film/color_space.h"
#include "core/scene/scene_loader.h"
#include "tests/core/scene/pbrt_test_support.h"
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

TEST(PbrtLightsTest, AnImageLightsPowerCountsTheImagesMeanLuminance) {
    // "power" 10 W from a 2 x 2 card (area 4, one side): L = 10 / (pi 4 mean luminance), the
    // mean luminance of texels (1, 1, 2) being sRGB's Y of them.
    absl::StatusOr<Scene> scene = Load(Bundle(ImageLight("\"float power\" 10"),
                                              {{"glow.exr", ExrBytes(2, 1, 1.0f, false)}}));
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
    const SceneBundle written = Bundle(
        "AreaLightSource \"diffuse\" \"string filename\" \"textures/glow.exr\"\n" +
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

}  // namespace
}  // namespace pf
