// The shipped scenes in their two forms, glTF and pbrt-v4 (scenes/pbrt/, written by
// scenes/generate_scenes.py from the same description) render the same image.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/film/exr_io.h"
#include "core/job/integrator.h"
#include "embedded/local_render.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/image_agreement.h"
#include "tests/support/small_render.h"
#include "tests/support/test_env.h"

namespace pf {
namespace {

// A render of `path` on 2 threads with `spp` camera samples a pixel, stopping after `epochs`
// epochs (0: no such budget) or, for ppm and sppm, `photons` photons; an empty image (and a
// failure) where it does not render.
Image RenderWith(const std::string& path, Integrator integrator, uint64_t seed, int spp,
                 uint64_t epochs, uint64_t photons) {
    RenderSettings settings;
    settings.scene_path = path;
    settings.threads = 2;
    settings.job.integrator = integrator;
    settings.job.seed = seed;
    settings.job.samples_per_pixel = spp;
    settings.job.epoch_budget = epochs;
    if (integrator == Integrator::kPpm || integrator == Integrator::kSppm)
        settings.job.photon_budget = photons;
    const absl::StatusOr<RenderOutcome> outcome = RenderLocally(settings);
    EXPECT_TRUE(outcome.ok()) << outcome.status();
    return outcome.ok() ? outcome->image : Image();
}

class SceneFormats : public ::testing::TestWithParam<std::string> {};

TEST_P(SceneFormats, PbrtFormRendersTheGltfFormsImage) {
    const std::string scenes = std::string(PF_SOURCE_DIR) + "/scenes/";
    // One R0 for all hit points (2% of the Cornell box's width): each hit point's own comes
    // from a pilot photon map, whose paths a last-bit vertex difference sends elsewhere after
    // a few bounces (through caustic-glass's sphere above all), so the two forms' radii would
    // differ by the pilot's noise.
    constexpr uint64_t kPhotons = 1'000'000;
    constexpr double kRadius = 0.011;
    const Image gltf =
        testing::RenderSmall(scenes + GetParam() + ".gltf", "cpu", 1, kPhotons, kRadius);
    const Image gltf_other_stream =
        testing::RenderSmall(scenes + GetParam() + ".gltf", "cpu", 2, kPhotons, kRadius);
    const std::string pbrt_path = scenes + "pbrt/" + GetParam() + ".pbrt";
    // pbrt's own spheres (cornell-glass, furnace-glass) are tessellated otherwise than the glTF
    // forms' meshes: their image is another draw of the same estimator. The other scenes hold
    // the same triangles in both forms: with the same random numbers, the same image, but for
    // the few camera samples that a last-bit difference of a vertex moves across an edge (of
    // caustic-glass's light of 4000, sampled afresh every epoch): 1e-5 of another stream's
    // difference.
    const bool pbrt_spheres = GetParam() == "cornell-glass" || GetParam() == "furnace-glass";
    if (pbrt_spheres) {
        testing::ExpectSameEstimator(testing::RenderSmall(pbrt_path, "cpu", 3, kPhotons, kRadius),
                                     gltf, gltf_other_stream);
        return;
    }
    const Image pbrt = testing::RenderSmall(pbrt_path, "cpu", 1, kPhotons, kRadius);
    ASSERT_EQ(pbrt.pixels.size(), gltf.pixels.size());
    EXPECT_LE(testing::MeanSquaredDifference(pbrt, gltf),
              1e-5 * testing::MeanSquaredDifference(gltf, gltf_other_stream));
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

TEST(TwoSidedLights, ATwoSidedLightIsItsTwoFacesSummed) {
    // A floor under a small square light (albedo 0 itself), open to the sky: light transport is
    // linear in the emission, so the image with a two-sided light is the image with the light
    // emitting from one face plus the image with it emitting from the other
    // (ReverseOrientation), in the path tracer's light samples and MIS alike and in ppm's
    // photons. Means over the image within 5.5 sigma of their noise (from four renders of
    // each with independent seeds); a 2% error would fail.
    const auto scene = [](const std::string& light, const std::string& name) {
        return testing::WriteTextFile(
            "LookAt 0 0.5 3  0 0 0.4  0 1 0\nCamera \"perspective\" \"float fov\" 50\n"
            "Film \"rgb\" \"integer xresolution\" 48 \"integer yresolution\" 48\nWorldBegin\n"
            "Material \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]\n"
            "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]\n"
            "AttributeBegin\n" +
                light +
                "Material \"diffuse\" \"rgb reflectance\" [0 0 0]\n"
                "Translate 0 0 0.6\nRotate 50 1 0 0\n"
                "Shape \"bilinearmesh\" \"point3 P\" [-0.3 -0.3 0  0.3 -0.3 0  -0.3 0.3 0  0.3 0.3 "
                "0]\n"
                "AttributeEnd\n",
            name);
    };
    const std::string light = "AreaLightSource \"diffuse\" \"rgb L\" [4 4 4]";
    const std::string two_sided = scene(light + " \"bool twosided\" true\n", "two-sided.pbrt");
    const std::string front = scene(light + "\n", "front-face.pbrt");
    const std::string back = scene("ReverseOrientation\n" + light + "\n", "back-face.pbrt");
    for (const Integrator integrator : {Integrator::kPath, Integrator::kPpm}) {
        struct Mean {
            double mean = 0, variance = 0;  // of the image's mean
        };
        const auto render = [&](const std::string& path, uint64_t stream) {
            const Image image = RenderWith(path, integrator, stream, 16,
                                           integrator == Integrator::kPath ? 16 : 0, 4'000'000);
            double sum = 0;
            for (const Rgb& pixel : image.pixels) sum += pixel.y;
            return sum / static_cast<double>(std::max<size_t>(1, image.pixels.size()));
        };
        // The noise of an image's mean from 4 renders with independent seeds: their sample
        // variance over 4 estimates the variance of their average (3 degrees of freedom each,
        // 9 for the three scenes: 5.5 sigma is then t's 0.04% tail).
        const auto measure = [&](const std::string& path) {
            double sum = 0, sum_sq = 0;
            for (uint64_t seed = 1; seed <= 4; ++seed) {
                const double m = render(path, seed);
                sum += m, sum_sq += m * m;
            }
            const double mean = sum / 4;
            return Mean{mean, std::max(0.0, (sum_sq - 4 * mean * mean) / 3) / 4};
        };
        const Mean both = measure(two_sided), one = measure(front), other = measure(back);
        const double sigma = std::sqrt(both.variance + one.variance + other.variance);
        std::printf("%s: two-sided %.5f, front + back %.5f + %.5f, sigma %.5f\n",
                    std::string(IntegratorName(integrator)).c_str(), both.mean, one.mean,
                    other.mean, sigma);
        EXPECT_GT(std::min(one.mean, other.mean), 0.0);
        EXPECT_NEAR(both.mean, one.mean + other.mean, 5.5 * sigma);
        EXPECT_LT(5.5 * sigma, 0.02 * both.mean);
    }
}

TEST(TexturedLights, ASingleTexelImageLightRendersAsItsColour) {
    // A card lit by a two-sided area light whose image is one texel (0.5, 0.25, 1) at scale 8,
    // against the same light with L = (4, 2, 8): the same radiance everywhere, so with the same
    // random numbers every integrator renders the same image (seen directly, by light samples and
    // MIS hits, and by photons), to float rounding.
    const std::string folder = testing::TempPath("single-texel-light");
    std::filesystem::create_directories(folder);
    Image texel(1, 1);
    texel.pixels[0] = Rgb(0.5f, 0.25f, 1.0f);
    ASSERT_TRUE(WriteExr(folder + "/texel.exr", texel).ok());
    const auto scene = [&](const std::string& light, const std::string& name) {
        const std::string path = folder + "/" + name;
        std::ofstream(path)
            << "LookAt 0 0.5 3  0 0 0.4  0 1 0\nCamera \"perspective\" \"float fov\" 50\n"
               "Film \"rgb\" \"integer xresolution\" 32 \"integer yresolution\" 32\nWorldBegin\n"
               "Material \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]\n"
               "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]\n"
               "AttributeBegin\n"
            << light
            << "\nTranslate 0 0 0.6\nRotate 160 1 0 0\n"
               "Shape \"bilinearmesh\" \"point3 P\" [-0.3 -0.3 0  0.3 -0.3 0  -0.3 0.3 0  0.3 0.3 "
               "0]\nAttributeEnd\n";
        return path;
    };
    const std::string textured = scene(
        "AreaLightSource \"diffuse\" \"string filename\" \"texel.exr\" \"float scale\" 8 "
        "\"bool twosided\" true",
        "textured.pbrt");
    const std::string plain =
        scene("AreaLightSource \"diffuse\" \"rgb L\" [4 2 8] \"bool twosided\" true", "plain.pbrt");
    for (const Integrator integrator :
         {Integrator::kPath, Integrator::kPpm, Integrator::kSppm, Integrator::kPm}) {
        const auto render = [&](const std::string& path, uint64_t seed) {
            return RenderWith(path, integrator, seed, 4, 2, 200'000);
        };
        const Image a = render(textured, 1), b = render(plain, 1), other = render(plain, 2);
        ASSERT_EQ(a.pixels.size(), b.pixels.size());
        const std::string name(IntegratorName(integrator));
        EXPECT_GT(testing::MeanSquaredDifference(b, other), 0.0) << name;
        EXPECT_LE(testing::MeanSquaredDifference(a, b),
                  1e-9 * testing::MeanSquaredDifference(b, other))
            << name;
    }
}

INSTANTIATE_TEST_SUITE_P(Shipped, SceneFormats,
                         ::testing::Values("cornell-box", "cornell-glass", "caustic-glass",
                                           "furnace", "furnace-glass", "cornell-stained",
                                           "cornell-bumpy"),
                         [](const ::testing::TestParamInfo<std::string>& scene) {
                             std::string name = scene.param;
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

}  // namespace
}  // namespace pf
