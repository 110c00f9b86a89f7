// The pbrt importer, continued: what a scene asks of its render (Integrator, Sampler,
// cameras), spectra as pbrt-v4 names, samples and files them, and includes read as one token
// stream with their parent.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/scene_io/scene_loader.h"
#include "tests/core/scene_io/pbrt_test_support.h"
#include "tests/support/test_env.h"

namespace pf {
namespace {

using namespace pbrt_test;

TEST(PbrtRenderSettingsTest, IntegratorAndSamplerAreReadAsPbrtDefinesThem) {
    auto settings = [](const std::string& directives) {
        SceneBundle bundle = Bundle(kQuad);
        bundle.files["scene.pbrt"] = directives + "\n" + bundle.files["scene.pbrt"];
        std::vector<std::string> warnings;
        const absl::StatusOr<Scene> scene = Load(bundle, &warnings);
        EXPECT_TRUE(scene.ok()) << scene.status();
        return std::make_pair(scene.ok() ? scene->render_settings : SceneRenderSettings{},
                              warnings);
    };
    const auto [volpath, volpath_notes] = settings(
        "Integrator \"volpath\" \"integer maxdepth\" 100\nSampler \"zsobol\" "
        "\"integer pixelsamples\" 1024");
    EXPECT_EQ(volpath.integrator, "path");
    EXPECT_EQ(volpath.max_depth, 100);
    EXPECT_EQ(volpath.pixel_samples, 1024);
    EXPECT_EQ(volpath.sampler_source, "scenes/scene.pbrt:2:1: Sampler \"zsobol\"");
    const auto [bdpt, bdpt_notes] = settings("Integrator \"bdpt\"\nSampler \"halton\"");
    EXPECT_EQ(bdpt.integrator, "path");
    EXPECT_EQ(bdpt.max_depth, 5);
    EXPECT_EQ(bdpt.pixel_samples, 16);
    EXPECT_TRUE(Contains(bdpt_notes, "renders as photonfarm's path tracer"));
    const auto [ao, ao_notes] = settings("Integrator \"ambientocclusion\"");
    EXPECT_TRUE(ao.integrator.empty());
    EXPECT_TRUE(Contains(ao_notes, "is not a light transport photonfarm renders"));
    const auto [none, none_notes] = settings("");
    EXPECT_TRUE(none.integrator.empty());
    EXPECT_EQ(none.max_depth, 0);
    EXPECT_EQ(none.pixel_samples, 0);

    SceneBundle bad = Bundle(kQuad);
    bad.files["scene.pbrt"] =
        "Integrator \"path\" \"integer maxdepth\" 0\n" + bad.files["scene.pbrt"];
    const absl::StatusOr<Scene> refused = Load(bad);
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.status().message(),
              "scenes/scene.pbrt:1:1: Integrator \"path\": \"maxdepth\" must be at least 1");
}

TEST(PbrtRenderSettingsTest, TheFilmsFilenameIsReadWithoutAWarning) {
    // Every pbrt scene names its output; photonfarm writes where --out says. That changes
    // nothing in the image: an info line, not a warning (corpus run 1 saw it on all 57).
    SceneBundle bundle = Bundle(kQuad);
    std::string& text = bundle.files["scene.pbrt"];
    const std::string film = "Film \"rgb\" ";
    ASSERT_NE(text.find(film), std::string::npos);
    text.replace(text.find(film), film.size(), film + "\"string filename\" \"out.exr\" ");
    std::vector<std::string> warnings;
    const absl::StatusOr<Scene> scene = Load(bundle, &warnings);
    ASSERT_TRUE(scene.ok()) << scene.status();
    EXPECT_EQ(scene->hints.width, 200);
    EXPECT_TRUE(warnings.empty()) << warnings.front();
}

TEST(PbrtRenderSettingsTest, AClampOfSamplesIsWarnedAsLeftOut) {
    // pbrt-v4 clips samples brighter than maxcomponentvalue; photonfarm does not, which reads
    // brighter on a scene of fireflies: a warning naming it (and none for pbrt-v4's default).
    SceneBundle bundle = Bundle(kQuad);
    std::string& text = bundle.files["scene.pbrt"];
    const std::string film = "Film \"rgb\" ";
    ASSERT_NE(text.find(film), std::string::npos);
    text.replace(text.find(film), film.size(), film + "\"float maxcomponentvalue\" 10 ");
    std::vector<std::string> warnings;
    ASSERT_TRUE(Load(bundle, &warnings).ok());
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("\"maxcomponentvalue\" 10 is left out"), std::string::npos)
        << warnings[0];
}

TEST(PbrtRenderSettingsTest, OrthographicAndSphericalCamerasAndScreenWindows) {
    auto load = [](const std::string& camera) {
        SceneBundle bundle = Bundle(kQuad);
        std::string& main = bundle.files["scene.pbrt"];
        const std::string perspective = "Camera \"perspective\" \"float fov\" 40";
        main.replace(main.find(perspective), perspective.size(), camera);
        return Load(bundle);
    };
    // The film is 200 x 100: an orthographic camera's default window is [-2, 2] x [-1, 1].
    const absl::StatusOr<Scene> orthographic = load("Scale 3 3 1\nCamera \"orthographic\"");
    ASSERT_TRUE(orthographic.ok()) << orthographic.status();
    EXPECT_EQ(orthographic->camera.projection, Projection::kOrthographic);
    // The transform is camera from world: a Scale of 3 before the Camera makes a camera-space
    // unit a third of the world's.
    EXPECT_NEAR(orthographic->camera.window.x_max, 2.0f / 3, 1e-5f);
    EXPECT_NEAR(orthographic->camera.window.y_min, -1.0f / 3, 1e-5f);
    const absl::StatusOr<Scene> cropped =
        load("Camera \"perspective\" \"float fov\" 90 \"float screenwindow\" [0 1 0 0.5]");
    ASSERT_TRUE(cropped.ok()) << cropped.status();
    EXPECT_NEAR(cropped->camera.window.x_max, 1.0f, 1e-6f);  // times tan(45 degrees)
    EXPECT_NEAR(cropped->camera.window.y_max, 0.5f, 1e-6f);
    const absl::StatusOr<Scene> spherical =
        load("Camera \"spherical\" \"string mapping\" \"equirectangular\"");
    ASSERT_TRUE(spherical.ok()) << spherical.status();
    EXPECT_EQ(spherical->camera.projection, Projection::kSpherical);
    EXPECT_EQ(spherical->camera.equal_area, 0u);

    ExpectError(load("Camera \"realistic\""),
                "Camera \"realistic\" is not supported (\"perspective\", \"orthographic\" and "
                "\"spherical\" are)");
    ExpectError(load("Camera \"orthographic\" \"float screenwindow\" [1 0 0 1]"),
                "\"screenwindow\" needs 4 values, x_min < x_max and y_min < y_max");
    ExpectError(load("Camera \"spherical\" \"string mapping\" \"cubemap\""),
                "\"mapping\" \"cubemap\" is not");
}

TEST(PbrtRenderSettingsTest, AnIncludeIsPartOfItsParentsTokenStream) {
    // As pbrt reads it: the parameter list of the Shape goes on in the included file and back
    // in the parent after it (pbrt-v4-scenes' smoke-plume writes its grid's values so).
    const absl::StatusOr<Scene> scene =
        Load(Bundle("Shape \"trianglemesh\" Include \"points.pbrt\" \"integer indices\" [0 1 2]\n",
                    {{"points.pbrt", "\"point3 P\" [0 0 0\n 1 0 0\n Include \"last.pbrt\"]"},
                     {"last.pbrt", "0 1 0"}}));
    ASSERT_TRUE(scene.ok()) << scene.status();
    ASSERT_EQ(scene->positions.size(), 3u);
    EXPECT_EQ(scene->positions[2].y, 1.0f);
    EXPECT_EQ(scene->triangles.size(), 1u);
}

TEST(PbrtRenderSettingsTest, SpectraAreNamedSampledOrInFiles) {
    SceneBundle bundle = Bundle(
        "AttributeBegin\nAreaLightSource \"diffuse\" \"spectrum L\" \"stdillum-D65\" "
        "\"float scale\" 2\n" +
            std::string(kQuad) +
            "AttributeEnd\n"
            "Material \"diffuse\" \"spectrum reflectance\" \"spectra/half.spd\"\n" +
            kQuad + "Material \"diffuse\" \"spectrum reflectance\" [300 0.25 900 0.25]\n" + kQuad,
        {{"spectra/half.spd", "# a flat 50% reflectance\n380 0.5\n 780 0.5 # the end\n"}});
    const absl::StatusOr<Scene> scene = Load(bundle);
    ASSERT_TRUE(scene.ok()) << scene.status();
    ASSERT_EQ(scene->materials.size(), 3u);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(scene->materials[0].emission[c], 2.0f, 5e-3f);  // D65 is sRGB's white
        EXPECT_NEAR(scene->materials[1].base_color[c], 0.5f, 1e-3f);
        EXPECT_NEAR(scene->materials[2].base_color[c], 0.25f, 1e-3f);
    }

    auto error = [](const std::string& world, std::map<std::string, std::string> files = {}) {
        const absl::StatusOr<Scene> loaded = Load(Bundle(world, std::move(files)));
        return loaded.ok() ? std::string("loaded") : std::string(loaded.status().message());
    };
    EXPECT_EQ(
        error(std::string("Material \"diffuse\" \"spectrum reflectance\" \"nope.spd\"\n") + kQuad),
        "scenes/scene.pbrt:6:20: parameter \"spectrum reflectance\": 'nope.spd' is neither a "
        "spectrum pbrt-v4 names nor a file of the scene ('nope.spd' is not in the scene "
        "bundle)");
    EXPECT_EQ(
        error(std::string("Material \"diffuse\" \"spectrum reflectance\" \"bad.spd\"\n") + kQuad,
              {{"bad.spd", "400 0.5\n500 x\n"}}),
        "scenes/bad.spd:2: 'x' is not a finite number");
    EXPECT_EQ(
        error(std::string("Material \"diffuse\" \"spectrum reflectance\" [700 0.5 400 0.5]\n") +
              kQuad),
        "scenes/scene.pbrt:6:20: parameter \"spectrum reflectance\" wavelengths must "
        "ascend: 400 follows 700");
}

TEST(PbrtRenderSettingsTest, PackingGathersSpectrumFiles) {
    const std::filesystem::path folder = testing::ProcessTempDir() / "spd-scene";
    std::filesystem::create_directories(folder / "spectra");
    const SceneBundle written =
        Bundle("Material \"diffuse\" \"spectrum reflectance\" \"spectra/half.spd\"\n" +
               std::string(kQuad));
    std::ofstream(folder / "scene.pbrt") << written.files.at("scene.pbrt");
    std::ofstream(folder / "spectra" / "half.spd") << "380 0.5 780 0.5\n";
    const absl::StatusOr<SceneBundle> bundle = PackSceneBundle((folder / "scene.pbrt").string());
    ASSERT_TRUE(bundle.ok()) << bundle.status();
    EXPECT_TRUE(bundle->files.contains("spectra/half.spd"));
    EXPECT_TRUE(LoadScene(*bundle, "scene.pbrt").ok());
}

TEST(PbrtRenderSettingsTest, InterfacesLeaveTheirShapesOut) {
    // A medium's boundary is no surface: "interface", and as pbrt-v4 reads them "" and "none".
    for (const char* type : {"interface", "", "none"}) {
        const absl::StatusOr<Scene> scene =
            Load(Bundle(std::string(kQuad) + "Material \"" + type +
                        "\"\nShape \"sphere\" \"float radius\" 0.5\n"));
        ASSERT_TRUE(scene.ok()) << scene.status();
        EXPECT_EQ(scene->triangles.size(), 2u) << "Material \"" << type << "\"";  // the quad alone
    }
}

}  // namespace
}  // namespace pf
