// Alpha cut-outs (core/shared/alpha.h) through the CPU tracer and every integrator: rays pass
// where alpha says and nowhere else, a shape of alpha 0 changes nothing in an image, and a
// half-covering plane under a uniform sky shows exactly the mix of itself and the sky.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "absl/strings/str_format.h"
#include "core/job/integrator.h"
#include "core/scene/scene_features.h"
#include "core/scene_io/scene_loader.h"
#include "embedded/local_render.h"
#include "embree/embree_tracer.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/test_env.h"

namespace pf {
namespace {

// A 2x1 grey PNG: 0 on the left, 1 on the right.
constexpr unsigned char kHalfPng[] = {
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48,
    0x44, 0x52, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x01, 0x08, 0x00, 0x00, 0x00,
    0x00, 0xd1, 0x49, 0x20, 0x56, 0x00, 0x00, 0x00, 0x0b, 0x49, 0x44, 0x41, 0x54, 0x78,
    0x9c, 0x63, 0x60, 0xf8, 0x0f, 0x00, 0x01, 0x02, 0x01, 0x00, 0x42, 0xbe, 0xbc, 0x68,
    0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};

// Two unit quads facing +z, the front one at z = 1 with `alpha` (a Shape parameter), the back
// one at z = 0, under a sky.
std::string TwoQuads(const std::string& alpha) {
    return "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 30\nWorldBegin\n"
           "LightSource \"infinite\" \"rgb L\" [1 1 1]\n"
           "Texture \"half\" \"float\" \"imagemap\" \"string filename\" \"half.png\"\n"
           "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]\n"
           "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 1  1 -1 1  -1 1 1  1 1 1] " +
           alpha + "\n";
}

Scene LoadWithPng(const std::string& text, const std::string& name) {
    const std::filesystem::path folder = testing::FreshTempDir(name);
    std::ofstream(folder / "half.png", std::ios::binary)
        .write(reinterpret_cast<const char*>(kHalfPng), sizeof(kHalfPng));
    std::ofstream(folder / "scene.pbrt") << text;
    absl::StatusOr<Scene> scene = LoadScene((folder / "scene.pbrt").string());
    EXPECT_TRUE(scene.ok()) << scene.status();
    return scene.ok() ? *scene : Scene();
}

// Rays straight down -z at (x, y) from z = 3: where each first meets a quad (its z), and
// whether a shadow ray over the same segment is blocked.
struct Cast {
    float z = -1;
    bool occluded = false;
};
Cast CastDown(const embree::EmbreeTracer& tracer, float x, float y, float t_max = 10) {
    Ray ray{{x, y, 3}, {0, 0, -1}};
    ray.t_max = t_max;
    Cast cast;
    RayHit hit;
    if (tracer.Intersect(ray, &hit)) cast.z = 3 - hit.t;
    cast.occluded = tracer.Occluded(ray);
    return cast;
}

TEST(CutOutsTest, RaysPassWhereAlphaSays) {
    // Alpha 0: the front quad is not there for any ray, closest-hit or shadow.
    const Scene absent = LoadWithPng(TwoQuads("\"float alpha\" 0"), "alpha-0");
    EXPECT_TRUE(AnalyseFeatures(absent, Emitters(absent)).cut_outs);
    auto tracer = embree::EmbreeTracer::Create(absent);
    ASSERT_TRUE(tracer.ok()) << tracer.status();
    for (float x : {-0.9f, 0.0f, 0.7f}) {
        EXPECT_NEAR(CastDown(**tracer, x, 0.1f).z, 0.0f, 1e-5f);
        EXPECT_FALSE(CastDown(**tracer, x, 0.1f, 2.5f).occluded) << "alpha 0 casts no shadow";
    }
    // A texture: cut out on the left half (texel 0), solid on the right.
    const Scene half = LoadWithPng(TwoQuads("\"texture alpha\" \"half\""), "alpha-texture");
    tracer = embree::EmbreeTracer::Create(half);
    ASSERT_TRUE(tracer.ok()) << tracer.status();
    // (At the texels' centres: between them the bilinear lookup gives fractions, which the
    // stochastic test passes in part.)
    EXPECT_NEAR(CastDown(**tracer, -0.5f, 0.3f).z, 0.0f, 1e-5f);
    EXPECT_NEAR(CastDown(**tracer, 0.5f, 0.3f).z, 1.0f, 1e-5f);
    EXPECT_TRUE(CastDown(**tracer, 0.5f, 0.3f, 2.5f).occluded);
    EXPECT_FALSE(CastDown(**tracer, -0.5f, 0.3f, 2.5f).occluded);
    // Alpha 0.3: three rays in ten meet it, the same ones whether closest-hit or shadow.
    const Scene part = LoadWithPng(TwoQuads("\"float alpha\" 0.3"), "alpha-part");
    tracer = embree::EmbreeTracer::Create(part);
    ASSERT_TRUE(tracer.ok()) << tracer.status();
    constexpr int kRays = 20000;
    int met = 0;
    for (int i = 0; i < kRays; ++i) {
        const float x = -0.95f + 1.9f * float(i % 200) / 200,
                    y = -0.95f + 1.9f * float(i / 200) / 100;
        const Cast front = CastDown(**tracer, x, y, 2.5f);
        const Cast full = CastDown(**tracer, x, y);
        met += full.z > 0.5f;
        EXPECT_EQ(front.occluded, full.z > 0.5f) << "shadow and closest-hit rays disagree";
        EXPECT_EQ(CastDown(**tracer, x, y).z, full.z) << "the same ray decides the same way";
    }
    const double sigma = std::sqrt(0.3 * 0.7 / kRays);
    EXPECT_NEAR(double(met) / kRays, 0.3, 5 * sigma);
}

// Where a ray from `origin` along `direction` first meets a surface (its z), -100 where it meets
// none; and whether a shadow ray over the same 10 units is blocked.
Cast CastAlong(const embree::EmbreeTracer& tracer, Vec3 origin, Vec3 direction) {
    Ray ray{origin, direction};
    ray.t_max = 10;
    Cast cast{-100, false};
    RayHit hit;
    if (tracer.Intersect(ray, &hit)) cast.z = origin.z + direction.z * hit.t;
    cast.occluded = tracer.Occluded(ray);
    return cast;
}

TEST(CutOutsTest, SingleSidedGltfSurfacesLetRaysThroughTheirBackFaces) {
    // The lit quad (single-sided, open), used by a second node turned half a turn about y and
    // lowered to z = -2, so that it faces -z there: the mesh is a prototype placed twice, and
    // Embree's filter sees the ray in the prototype's space.
    testing::TestScene built = testing::LitQuadScene();
    built.extra_nodes = {R"({"mesh":0,"translation":[0,0,-2],"rotation":[0,1,0,0]})"};
    const absl::StatusOr<Scene> scene = LoadScene(testing::WriteGltf(built, "single-sided.gltf"));
    ASSERT_TRUE(scene.ok()) << scene.status();
    ASSERT_EQ(scene->instances.size(), 2u);
    auto tracer = embree::EmbreeTracer::Create(*scene);
    ASSERT_TRUE(tracer.ok()) << tracer.status();
    const Vec3 up(0, 0, 1), down(0, 0, -1);
    // Front faces stop rays, closest-hit and shadow alike.
    EXPECT_NEAR(CastAlong(**tracer, {0.5f, 0.5f, 3}, down).z, 0.0f, 1e-5f);
    EXPECT_TRUE(CastAlong(**tracer, {0.5f, 0.5f, 3}, down).occluded);
    EXPECT_NEAR(CastAlong(**tracer, {0.5f, 0.5f, -5}, up).z, -2.0f, 1e-5f);
    // Back faces let them through: between the two, looking at either, nothing is met.
    for (const Vec3& direction : {up, down}) {
        const Cast between = CastAlong(**tracer, {0.5f, 0.5f, -1}, direction);
        EXPECT_EQ(between.z, -100.0f) << direction.z;
        EXPECT_FALSE(between.occluded) << direction.z;
    }
    // The light above (single-sided too, facing down) stops a ray from below.
    EXPECT_NEAR(CastAlong(**tracer, {0.1f, 0.1f, -1}, up).z, 1.0f, 1e-5f);
}

// A render of the scene at `path` by `integrator`, 48x48.
Image Render(const std::string& path, Integrator integrator) {
    RenderSettings settings;
    settings.scene_path = path;
    settings.threads = 2;
    settings.job.integrator = integrator;
    settings.job.width = settings.job.height = 48;
    settings.job.seed = 4;
    settings.job.layout = {1u << 14, 2};
    settings.job.epoch_budget = 24;
    settings.job.photon_map.global_photons = settings.job.photon_map.caustic_photons = 1u << 16;
    const absl::StatusOr<RenderOutcome> outcome = RenderLocally(settings);
    EXPECT_TRUE(outcome.ok()) << outcome.status();
    return outcome.ok() ? outcome->image : Image();
}

std::string WriteScene(const std::string& text, const std::string& name) {
    const std::filesystem::path folder = testing::FreshTempDir(name);
    std::ofstream(folder / "scene.pbrt") << text;
    return (folder / "scene.pbrt").string();
}

class CutOutIntegrators : public ::testing::TestWithParam<Integrator> {};

TEST_P(CutOutIntegrators, AShapeOfAlphaZeroChangesNothing) {
    // The Cornell box, and a copy with quads of alpha 0 across the camera's view and between
    // the light and the floor (within the box's bounds, which set ray offsets): every ray
    // passes them as if they were not there, so the images are the same bits.
    const std::filesystem::path shipped = std::filesystem::path(PF_SOURCE_DIR) / "scenes/pbrt";
    const std::filesystem::path folder = testing::FreshTempDir("alpha-zero-box");
    for (const char* part : {"cornell-box.pbrt", "cornell-room.pbrt", "meshes"})
        std::filesystem::copy(shipped / part, folder / part,
                              std::filesystem::copy_options::recursive);
    std::ofstream(folder / "cornell-box.pbrt", std::ios::app)
        << "AttributeBegin\nMaterial \"diffuse\"\n"
           "Shape \"bilinearmesh\" \"point3 P\" [0.001 0.001 0.01  0.555 0.001 0.01  0.001 0.548 "
           "0.01  0.555 0.548 0.01] \"float alpha\" 0\n"
           "Shape \"bilinearmesh\" \"point3 P\" [0.001 0.5 0.001  0.555 0.5 0.001  0.001 0.5 0.558 "
           " "
           "0.555 0.5 0.558] \"float alpha\" 0\nAttributeEnd\n";
    const Image plain = Render((shipped / "cornell-box.pbrt").string(), GetParam());
    const Image cut = Render((folder / "cornell-box.pbrt").string(), GetParam());
    ASSERT_EQ(plain.pixels.size(), cut.pixels.size());
    size_t differing = 0;
    for (size_t i = 0; i < plain.pixels.size(); ++i)
        differing += !(plain.pixels[i] == cut.pixels[i]);
    EXPECT_EQ(differing, 0u) << "pixels changed by shapes no ray can meet";
}

TEST_P(CutOutIntegrators, APlaneOfAlphaAShowsTheSkyThroughItsHoles) {
    // A diffuse plane of albedo rho and alpha a facing the camera under a uniform sky L: a
    // camera ray meets it with probability a (and sees rho L: the sky lights its front
    // hemisphere in full) or passes to the sky. Every pixel on it: (a rho + 1 - a) L.
    constexpr double kAlpha = 0.4, kRho = 0.6;
    const Rgb sky(1.0f, 0.5f, 0.25f);
    const std::string path = WriteScene(
        absl::StrFormat("LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 20\n"
                        "WorldBegin\nLightSource \"infinite\" \"rgb L\" [%g %g %g]\n"
                        "Material \"diffuse\" \"rgb reflectance\" [%g %g %g]\n"
                        "Shape \"bilinearmesh\" \"point3 P\" [-3 -3 0  3 -3 0  -3 3 0  3 3 0] "
                        "\"float alpha\" %g\n",
                        sky.x, sky.y, sky.z, kRho, kRho, kRho, kAlpha),
        "alpha-plane");
    const Image image = Render(path, GetParam());
    // Blocks of 4x4 pixels: hit points are fixed (ppm) or share photons, so blocks are the
    // independent samples.
    for (int c = 0; c < 3; ++c) {
        const double expected = (kAlpha * kRho + 1 - kAlpha) * sky[c];
        std::vector<double> blocks;
        for (int by = 0; by < 48; by += 4)
            for (int bx = 0; bx < 48; bx += 4) {
                double sum = 0;
                for (int y = by; y < by + 4; ++y)
                    for (int x = bx; x < bx + 4; ++x) sum += image.pixels[y * 48 + x][c];
                blocks.push_back(sum / 16 / expected);
            }
        double mean = 0, var = 0;
        for (double b : blocks) mean += b / blocks.size();
        for (double b : blocks) var += (b - mean) * (b - mean) / (blocks.size() - 1);
        const double error = std::sqrt(var / blocks.size());
        EXPECT_NEAR(mean, 1.0, 5 * error + 1e-6) << "RGB"[c];
        EXPECT_LT(5 * error, 0.02) << "too noisy to catch a 2% bias";
        std::printf("%s %c: ratio %.4f, 5 sigma %.4f\n",
                    std::string(IntegratorName(GetParam())).c_str(), "RGB"[c], mean, 5 * error);
    }
}

// A floor and a wall under an area light card out of the camera's view, the card emitting L
// `radiance` with shape parameters `alpha` (a float texture "half" of 0.5 is defined).
std::string LightCardScene(const std::string& radiance, const std::string& alpha,
                           const std::string& name) {
    return WriteScene(
        "LookAt 0 -3 1.2  0 0 0.3  0 0 1\nCamera \"perspective\" \"float fov\" 40\n"
        "WorldBegin\nMaterial \"diffuse\" \"rgb reflectance\" [0.7 0.6 0.5]\n"
        "Shape \"bilinearmesh\" \"point3 P\" [-2 -2 0  2 -2 0  -2 2 0  2 2 0]\n"
        "Shape \"bilinearmesh\" \"point3 P\" [-2 1 0  2 1 0  -2 1 2  2 1 2]\n"
        "Texture \"half\" \"float\" \"bilerp\" \"float v00\" 0.5 \"float v01\" 0.5 "
        "\"float v10\" 0.5 \"float v11\" 0.5\n"
        "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [" +
            radiance +
            "]\n"
            "Material \"diffuse\" \"rgb reflectance\" [0 0 0]\nTranslate 0 0.3 2.2\n"
            "Rotate 180 1 0 0\nShape \"bilinearmesh\" \"point3 P\" "
            "[-0.4 -0.4 0  0.4 -0.4 0  -0.4 0.4 0  0.4 0.4 0] " +
            alpha + "\nAttributeEnd\n",
        name);
}

// Two renders of one expected image: their 8x8 blocks' differences average to zero within
// 5 standard errors, which are small enough to catch a 3% difference.
void ExpectSameImage(const Image& a_image, const Image& b_image) {
    for (int c = 0; c < 3; ++c) {
        std::vector<double> differences;
        double total = 0;
        for (int by = 0; by < 48; by += 8)
            for (int bx = 0; bx < 48; bx += 8) {
                double a = 0, b = 0;
                for (int y = by; y < by + 8; ++y)
                    for (int x = bx; x < bx + 8; ++x)
                        a += a_image.pixels[y * 48 + x][c], b += b_image.pixels[y * 48 + x][c];
                differences.push_back((b - a) / 64);
                total += a / 64;
            }
        const double n = double(differences.size()), level = total / n;
        double mean = 0, var = 0;
        for (double d : differences) mean += d / n;
        for (double d : differences) var += (d - mean) * (d - mean) / (n - 1);
        const double error = std::sqrt(var / n);
        EXPECT_NEAR(mean, 0.0, 5 * error) << "RGB"[c] << ": relative " << mean / level;
        EXPECT_LT(5 * error / level, 0.03) << "too noisy to catch a 3% difference";
    }
}

TEST_P(CutOutIntegrators, AnInvisibleLightLightsAsAVisibleOne) {
    // pbrt-v4's light cards: an area light of alpha 0 is seen by no ray but lights the scene
    // in full (light sampling alone finds it): the same image as the card visible.
    ExpectSameImage(
        Render(LightCardScene("4 4 4", "", "light-visible"), GetParam()),
        Render(LightCardScene("4 4 4", "\"float alpha\" 0", "light-invisible"), GetParam()));
}

TEST_P(CutOutIntegrators, AHalfMaskedLightLightsAsOneOfHalfItsRadiance) {
    // pbrt-v4 masks an area light's radiance where its alpha test fails: a card of alpha 0.5
    // emits half, as a constant and as a texture of 0.5 (an emission texture of the alpha, so
    // photons and light samples both see it). The card is black: light passing through it
    // where it is cut out leaves the scene, as light it absorbs does.
    const Image half = Render(LightCardScene("2 2 2", "", "light-half"), GetParam());
    ExpectSameImage(
        half, Render(LightCardScene("4 4 4", "\"float alpha\" 0.5", "light-alpha"), GetParam()));
    ExpectSameImage(
        half, Render(LightCardScene("4 4 4", "\"texture alpha\" \"half\"", "light-alpha-texture"),
                     GetParam()));
}

INSTANTIATE_TEST_SUITE_P(Integrators, CutOutIntegrators,
                         ::testing::Values(Integrator::kPpm, Integrator::kSppm, Integrator::kPm,
                                           Integrator::kPath),
                         [](const auto& param_info) {
                             return std::string(IntegratorName(param_info.param));
                         });

}  // namespace
}  // namespace pf
