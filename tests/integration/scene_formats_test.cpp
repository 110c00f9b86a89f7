// The shipped scenes in their two forms, glTF and pbrt-v4 (scenes/pbrt/, written by
// scenes/generate_scenes.py from the same description) render the same image.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

#include "embedded/local_render.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/image_agreement.h"
#include "tests/support/small_render.h"

namespace pf {
namespace {

class SceneFormats : public ::testing::TestWithParam<std::string> {};

TEST_P(SceneFormats, PbrtFormRendersTheGltfFormsImage) {
    const std::string scenes = std::string(PF_SOURCE_DIR) + "/scenes/";
    const Image gltf = testing::RenderSmall(scenes + GetParam() + ".gltf", "cpu", 1);
    const Image gltf_other_stream = testing::RenderSmall(scenes + GetParam() + ".gltf", "cpu", 2);
    const std::string pbrt_path = scenes + "pbrt/" + GetParam() + ".pbrt";
    // pbrt's own spheres (cornell-glass, furnace-glass) are tessellated otherwise than the glTF
    // forms' meshes: their image is another draw of the same estimator. The other scenes hold
    // the same triangles in both forms: with the same random numbers, the same image.
    const bool pbrt_spheres = GetParam() == "cornell-glass" || GetParam() == "furnace-glass";
    if (pbrt_spheres) {
        testing::ExpectSameEstimator(testing::RenderSmall(pbrt_path, "cpu", 3), gltf,
                                     gltf_other_stream);
        return;
    }
    const Image pbrt = testing::RenderSmall(pbrt_path, "cpu", 1);
    ASSERT_EQ(pbrt.pixels.size(), gltf.pixels.size());
    EXPECT_LE(testing::MeanSquaredDifference(pbrt, gltf),
              1e-9 * testing::MeanSquaredDifference(gltf, gltf_other_stream));
}

TEST(FilmExposure, ImageIsLinearInIsoTimesExposureTime) {
    // The same render with pbrt's Film iso 400 and a shutter open for half the time is twice
    // the plain one, bit for bit (a power of two scales floats exactly), and with iso 100 the
    // same.
    const auto scene = [](const std::string& camera, const std::string& film,
                          const std::string& name) {
        return testing::WriteTextFile(
            "LookAt 0 0 4  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 40 " + camera +
                "\nFilm \"rgb\" \"integer xresolution\" 32 \"integer yresolution\" 32 " + film +
                "\nWorldBegin\nLightSource \"point\" \"rgb I\" [2 3 4] \"point3 from\" [0 1 2]\n"
                "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]\n"
                "Shape \"sphere\" \"float radius\" 0.4\n",
            name);
    };
    const Image plain = testing::RenderSmall(scene("", "", "film-plain.pbrt"), "cpu", 1);
    const Image iso = testing::RenderSmall(
        scene("\"float shutterclose\" 0.5", "\"float iso\" 400", "film-iso.pbrt"), "cpu", 1);
    const Image same =
        testing::RenderSmall(scene("", "\"float iso\" 100", "film-iso100.pbrt"), "cpu", 1);
    ASSERT_EQ(plain.pixels.size(), iso.pixels.size());
    ASSERT_EQ(plain.pixels.size(), same.pixels.size());
    double sum = 0;
    for (size_t p = 0; p < plain.pixels.size(); ++p) {
        EXPECT_EQ(iso.pixels[p], plain.pixels[p] * 2.0f) << p;
        EXPECT_EQ(same.pixels[p], plain.pixels[p]) << p;
        sum += plain.pixels[p].y;
    }
    EXPECT_GT(sum, 0);
}

TEST(Cameras, EveryCameraInsideTheFurnaceSeesLeOverOneMinusAlbedo) {
    // The pbrt furnace (albedo 0.5, Le = 1: L = 2 in every direction) seen from inside by a
    // spherical camera of each mapping (every direction, walls, edges and corners alike) and an
    // orthographic one, through the path tracer: each image's mean within 4 sigma of 2 (its
    // pixels are independent), and a 2% error would fail.
    std::ifstream file(std::string(PF_SOURCE_DIR) + "/scenes/pbrt/furnace.pbrt");
    std::string furnace((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    const std::string perspective = "Camera \"perspective\" \"float fov\" 70.0";
    ASSERT_NE(furnace.find(perspective), std::string::npos);
    for (const std::string camera :
         {"Camera \"spherical\"", "Camera \"spherical\" \"string mapping\" \"equirectangular\"",
          "Camera \"orthographic\" \"float screenwindow\" [-0.5 0.5 -0.5 0.5]"}) {
        std::string scene = furnace;
        scene.replace(scene.find(perspective), perspective.size(), camera);
        RenderSettings settings;
        settings.scene_path = testing::WriteTextFile(scene, "furnace-camera.pbrt");
        settings.threads = 2;
        settings.job.integrator = Integrator::kPath;
        settings.job.width = settings.job.height = 32;
        settings.job.samples_per_pixel = 16;
        settings.job.epoch_budget = 8;
        const absl::StatusOr<RenderOutcome> outcome = RenderLocally(settings);
        ASSERT_TRUE(outcome.ok()) << outcome.status();
        double sum = 0, sum_sq = 0;
        for (const Rgb& pixel : outcome->image.pixels) sum += pixel.y, sum_sq += pixel.y * pixel.y;
        const double n = static_cast<double>(outcome->image.pixels.size());
        const double mean = sum / n, sigma = std::sqrt((sum_sq / n - mean * mean) / (n - 1));
        std::printf("%s: mean %.5f, sigma of the mean %.5f\n", camera.c_str(), mean, sigma);
        EXPECT_NEAR(mean, 2.0, 4 * sigma) << camera;
        EXPECT_LT(4 * sigma, 0.02 * 2.0) << camera;
    }
}

INSTANTIATE_TEST_SUITE_P(Shipped, SceneFormats,
                         ::testing::Values("cornell-box", "cornell-glass", "caustic-glass",
                                           "furnace", "furnace-glass"),
                         [](const ::testing::TestParamInfo<std::string>& scene) {
                             std::string name = scene.param;
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

}  // namespace
}  // namespace pf
