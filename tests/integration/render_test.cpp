// Whole renders through the embedded renderer: the white furnace and punctual lights against
// their analytic answers on every backend, glass without NaN, bit-identical images on 1, 2, 3
// and 7 threads with every integrator, and a target error that stops on an honest estimate.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "core/camera/camera_pass.h"
#include "core/ppm/photon_pass.h"
#include "core/scene_io/scene_loader.h"
#include "embedded/local_render.h"
#include "embree/embree_tracer.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/numerics_cases.h"
#include "tests/support/vulkan_validation.h"
#include "worker/backend_factory.h"

namespace pf {
namespace {

std::string ScenePath(const std::string& name) {
    return std::string(PF_SOURCE_DIR) + "/scenes/" + name;
}

RenderSettings SmallRender(const std::string& scene, uint64_t photons, int threads,
                           const std::string& backend = "cpu") {
    RenderSettings settings;
    settings.backend = backend;
    settings.scene_path = ScenePath(scene);
    settings.job.width = 48;
    settings.job.height = 48;
    settings.job.photon_budget = photons;
    settings.threads = threads;
    settings.job.layout = {1u << 14, 8};
    return settings;
}

// The analytic cases, run on every backend (the Vulkan one on lavapipe where there is no GPU,
// under the validation layer: tests/support/vulkan_validation.cpp).
class AnalyticRender : public ::testing::TestWithParam<std::string> {
protected:
    void SetUp() override {
        if (GetParam() == "vulkan") testing::SkipWithoutVulkan();
        errors_before_ = testing::VulkanValidationErrors();
    }
    void TearDown() override {
        EXPECT_EQ(testing::VulkanValidationErrors(), errors_before_) << "Vulkan validation errors";
    }

private:
    unsigned long long errors_before_ = 0;
};

TEST_P(AnalyticRender, WhiteFurnaceConvergesToEmissionOverOneMinusAlbedo) {
    // furnace.gltf: a closed room of albedo 0.5 emitting Le = 1 everywhere, so L = 2 exactly.
    // Checked on the pixels away from the cube's edges: each channel's mean within 4 sigma,
    // sigma derived as for numerics_cases.cpp's furnaces, and the median (testing::CheckFurnace
    // says why it needs more room); the same check fails the image 2% brighter, darker or green.
    const RenderSettings settings = SmallRender("furnace.gltf", 3'000'000, 2, GetParam());
    const absl::StatusOr<RenderOutcome> outcome = RenderLocally(settings);
    ASSERT_TRUE(outcome.ok()) << outcome.status();
    for (const Rgb& pixel : outcome->image.pixels) ASSERT_TRUE(IsFinite(pixel));
    const testing::BoxInterior interior = testing::BoxInteriorPixels(
        settings.scene_path, settings.job.width, settings.job.height, outcome->initial_radius);
    ASSERT_GE(interior.count, 1000u);
    const double sigma = testing::FurnaceMeanSigma(
        0.5, static_cast<double>(outcome->progress.photons), interior.area_fraction,
        static_cast<double>(interior.count) * settings.job.samples_per_pixel *
            static_cast<double>(outcome->progress.epochs));
    const testing::FurnaceCheck check = testing::CheckFurnace(outcome->image, interior, 2.0, sigma);
    EXPECT_TRUE(check.Passed()) << check.Describe();
    RecordProperty("furnace", check.Describe());
    for (const Rgbd& bias : {Rgbd(1.02), Rgbd(0.98), Rgbd(1.0, 1.02, 1.0)})
        EXPECT_FALSE(testing::CheckFurnace(outcome->image, interior, 2.0, sigma, bias).Passed())
            << "the check passed the image biased by " << bias.x << ", " << bias.y << ", "
            << bias.z;
}

TEST_P(AnalyticRender, GlassInTheFurnaceConservesEnergy) {
    // furnace-glass.gltf: the furnace (albedo 0.5, Le = 1, so L = 2) with a clear glass sphere in
    // view. Lossless scattering leaves a uniform radiance field uniform, so a pixel seen through
    // the glass shows 2 x the throughput of its camera paths, and that throughput is 1: energy
    // lost or made by Fresnel, refraction or the splitting would show (testing::FurnacePass).
    // Two sides, each checked against its analytic answer:
    //  - the camera's: the pass's emission through the glass (Le carried by the paths) has
    //    median exactly Le = 1 over the glass pixels (testing::MedianEmission says why);
    //  - the light's: K independent draws given the camera pass, each channel's mean over the
    //    glass pixels whose hit points all lie farther than R0 from the room's edges, against
    //    emission / (1 - rho), by Student's t over the draws (testing::CheckFurnaceStreams);
    //    and the same over every such pixel of the image. Near the room's edges a gather disc
    //    reaches the next wall, a bias of several percent; hit points seen through the glass
    //    land anywhere, so the pixels are chosen by their own hit points, not by where the
    //    camera looks. The draws are the K epochs of one render at alpha = 1
    //    (testing::RenderEpochDraws says why they are independent draws of one render's
    //    expectation): one backend and one camera pass, not K (on lavapipe a render costs about
    //    10 s of pipeline set-up before its first photon).
    // Known bias on flat discs: the photon part (rho^2 of L) is uniform only in sum with the
    // sampled direct light; the sphere shades the direct light on the walls near it, and photons
    // through it make up for it, so the photon part varies over the gap between the sphere and
    // the nearest wall (0.2 m), and a disc of R0 averages it away by at most
    // rho^2 (R0 / gap)^2 / 8: 0.09% at R0 = 3.5 cm (R0 stays R0 at alpha = 1). Glass pixels
    // share few photons (they see a small patch of wall behind the sphere: their mean varies 24x
    // more than independent pixels would), so catching 2% there takes many photons: on the CPU
    // kCpuEpochs epochs of 2^19 (34M), where the glass pixels' check catches 1.49% (the whole
    // image's 0.35%), a margin for other machines' rounding under the 2% it must; 16 renders
    // of 3M took 48M for about as much. Vulkan on lavapipe traces a few 100k photons a second:
    // kVulkanEpochs epochs of 2^18 (6.3M, as its 12 renders of 500k had), where its whole
    // image's check catches 0.64% and its glass pixels' 2.8% (12 renders: 1.4% and about 6%);
    // its kernels are held to the CPU's batch by batch in vulkan_backend_test.
    constexpr double kRho = 0.5, kGap = 0.2;
    constexpr int kCpuEpochs = 64, kVulkanEpochs = 24;
    const bool vulkan = GetParam() == "vulkan";
    RenderSettings settings = SmallRender("furnace-glass.gltf", 0, 2, GetParam());
    settings.job.alpha = 1;
    settings.job.layout = {vulkan ? 1u << 15 : 1u << 16, 8};
    settings.job.photon_budget =
        settings.job.layout.PhotonsPerEpoch() * (vulkan ? kVulkanEpochs : kCpuEpochs);
    const absl::StatusOr<testing::EpochDraws> draws = testing::RenderEpochDraws(settings);
    ASSERT_TRUE(draws.ok()) << draws.status();
    for (const Rgb& pixel : draws->outcome.image.pixels) ASSERT_TRUE(IsFinite(pixel));
    const std::vector<Image>& images = draws->epochs;
    const double initial_radius = draws->outcome.initial_radius;
    const uint64_t hit_points = draws->outcome.hit_points;
    const testing::FurnacePass pass =
        testing::TraceFurnacePass(settings.scene_path, settings.job, initial_radius);
    ASSERT_EQ(pass.hit_points, hit_points) << "not the job's camera pass";
    ASSERT_FLOAT_EQ(pass.initial_radius, initial_radius) << "not the job's camera pass";
    std::vector<bool> glass = pass.through_glass;
    for (size_t p = 0; p < glass.size(); ++p) glass[p] = glass[p] && pass.flat[p];
    ASSERT_GE(std::count(glass.begin(), glass.end(), true), 300) << "too few glass pixels";
    const double known_bias = kRho * kRho * std::pow(initial_radius / kGap, 2) / 8;
    const auto check = [&](const std::vector<bool>& region, const Rgbd& bias) {
        return testing::CheckFurnaceStreams(images, pass, region, kRho, known_bias, bias);
    };
    const Rgbd median = testing::MedianEmission(pass, pass.through_glass);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(median[c], 1.0, 1e-5) << "channel " << c;
    const testing::FurnaceStreamsCheck through_glass = check(glass, Rgbd(1.0));
    const testing::FurnaceStreamsCheck whole = check(pass.flat, Rgbd(1.0));
    EXPECT_TRUE(through_glass.Passed()) << "through the glass: " << through_glass.Describe();
    EXPECT_TRUE(whole.Passed()) << "the whole image: " << whole.Describe();
    RecordProperty("through_glass", through_glass.Describe());
    RecordProperty("whole", whole.Describe());
    std::printf("%s through the glass: %s\n%s whole: %s\n", GetParam().c_str(),
                through_glass.Describe().c_str(), GetParam().c_str(), whole.Describe().c_str());
    EXPECT_LE(whole.DetectableBias(), 0.02) << whole.Describe();
    if (!vulkan) {
        EXPECT_LE(through_glass.DetectableBias(), 0.02) << through_glass.Describe();
    }
    // Each fails its renders made 2% brighter, darker or green (the glass pixels' check on the
    // CPU, the whole image's on both) and the pass's emission made 2% brighter.
    for (const Rgbd& bias : {Rgbd(1.02), Rgbd(0.98), Rgbd(1.0, 1.02, 1.0)}) {
        EXPECT_FALSE(check(pass.flat, bias).Passed())
            << "the whole image biased by " << bias.x << ", " << bias.y << ", " << bias.z;
        if (!vulkan) {
            EXPECT_FALSE(check(glass, bias).Passed())
                << "the glass pixels biased by " << bias.x << ", " << bias.y << ", " << bias.z;
        }
    }
    EXPECT_GT(std::abs(1.02 * median.y - 1.0), 1e-5);
}

// Renders a 2x2 quad of albedo 0.5 at z = 0, seen from above, lit by one punctual light, and
// returns the mean of the 4x4 pixels at the image's centre (the point under the camera).
double CentreOfQuadLitBy(const std::string& light, const std::string& node_fields,
                         const std::string& name, const std::string& backend) {
    testing::TestScene scene = testing::LitQuadScene();
    scene.meshes.resize(1);  // no area light
    scene.lights = {light};
    scene.light_node_fields = {node_fields};
    RenderSettings settings = SmallRender("", 100'000, 2, backend);
    settings.scene_path = testing::WriteGltf(scene, name);
    const absl::StatusOr<RenderOutcome> outcome = RenderLocally(settings);
    EXPECT_TRUE(outcome.ok()) << outcome.status();
    if (!outcome.ok()) return -1;
    double sum = 0;
    for (int y = 22; y < 26; ++y)
        for (int x = 22; x < 26; ++x) sum += outcome->image.At(x, y).x;
    return sum / 16;
}

// The mean over the centre 4x4 pixels of I h / (h^2 + r^2)^(3/2): the irradiance from a point
// source of intensity I at height h = 1 above the quad, seen by the test camera (z = 3, y-fov
// 0.8, 48x48 pixels looking straight down); with a range, times glTF's window
// 1 - (d / range)^4 at the distance d.
double CentreIrradianceFromPointAbove(double intensity, double range = 0) {
    const double pixel = 2 * 3 * std::tan(0.4) / 48;
    double sum = 0;
    constexpr int kSteps = 64;
    for (int i = 0; i < kSteps; ++i)
        for (int j = 0; j < kSteps; ++j) {
            const double x = (-2 + 4 * (i + 0.5) / kSteps) * pixel,
                         y = (-2 + 4 * (j + 0.5) / kSteps) * pixel;
            const double d2 = 1 + x * x + y * y;
            const double window = range > 0 ? 1 - d2 * d2 / std::pow(range, 4) : 1;
            sum += intensity * window / std::pow(d2, 1.5);
        }
    return sum / (kSteps * kSteps);
}

TEST_P(AnalyticRender, PunctualLightsGiveTheirAnalyticRadiance) {
    // A Lambertian surface of albedo rho under irradiance E has radiance rho E / pi; nothing
    // else is in the scene, so there is no indirect light. Intensities are candela (point,
    // spot) and lux (directional), 683 to the watt: 2732 cd is 4 W/sr; the lights hang 1 above
    // the quad's centre, pointing down.
    const double rho_over_pi = 0.5 / kPiD;
    const double point_expected = rho_over_pi * CentreIrradianceFromPointAbove(4.0);
    const std::string& backend = GetParam();
    EXPECT_NEAR(CentreOfQuadLitBy(R"({"type":"point","intensity":2732})",
                                  R"(,"translation":[0,0,1])", "point.gltf", backend),
                point_expected, 0.005 * point_expected);
    // A range of 1.2 takes (1 / 1.2)^4 = 48% off at the centre, and the window falls across
    // the pixels: the light samples (direct light) take it at their distance. Photons take it
    // at their first hit, which the indirect light of the test below checks.
    const double ranged_expected = rho_over_pi * CentreIrradianceFromPointAbove(4.0, 1.2);
    EXPECT_NEAR(CentreOfQuadLitBy(R"({"type":"point","intensity":2732,"range":1.2})",
                                  R"(,"translation":[0,0,1])", "ranged.gltf", backend),
                ranged_expected, 0.005 * ranged_expected);
    // Within the inner cone a spot light is a point light.
    EXPECT_NEAR(
        CentreOfQuadLitBy(
            R"({"type":"spot","intensity":2732,"spot":{"innerConeAngle":0.3,"outerConeAngle":0.6}})",
            R"(,"translation":[0,0,1])", "spot.gltf", backend),
        point_expected, 0.005 * point_expected);
    EXPECT_NEAR(CentreOfQuadLitBy(R"({"type":"directional","intensity":2049})", "",
                                  "directional.gltf", backend),
                rho_over_pi * 3.0, 0.01 * rho_over_pi * 3.0);
}

// A glTF point light with a range (KHR_lights_punctual's window 1 - (d / range)^4) beside a
// wall: past the range the floor is lit only by the wall, so there ppm's photons must take the
// window at their first hit (the wall) as the path tracer's light samples take it at the wall.
// The region's means agree within 4 sigma of their noise (the path tracer's from its pixels,
// ppm's from two independent photon streams) and ppm's kernel bias on a smooth density
// (1%), and a 10% error would fail: without the window the wall's light is 20-60% brighter.
TEST(RangedLight, PhotonsAndLightSamplesTakeTheWindowAlike) {
    testing::TestScene scene = testing::LitQuadScene();
    scene.meshes.resize(1);
    scene.meshes.push_back(
        {{{1, -1, 0}, {1, 1, 1}, {1, 1, 0}, {1, -1, 0}, {1, -1, 1}, {1, 1, 1}}, 0});
    scene.lights = {R"({"type":"point","intensity":6830,"range":1.0})"};
    scene.light_node_fields = {R"(,"translation":[0.6,0,0.4])"};
    const std::string path = testing::WriteGltf(scene, "ranged-wall.gltf");
    auto render = [&](Integrator integrator, uint64_t stream) {
        RenderSettings settings;
        settings.scene_path = path;
        settings.threads = 2;
        settings.job.integrator = integrator;
        settings.job.width = settings.job.height = 64;
        settings.job.photon_stream = stream;
        settings.job.samples_per_pixel = 16;
        if (integrator == Integrator::kPpm)
            settings.job.photon_budget = 8'000'000, settings.job.layout = {1u << 18, 8};
        else
            settings.job.epoch_budget = 256;
        const absl::StatusOr<RenderOutcome> outcome = RenderLocally(settings);
        EXPECT_TRUE(outcome.ok()) << outcome.status();
        return outcome.ok() ? outcome->image : Image();
    };
    const Image ppm1 = render(Integrator::kPpm, 1), ppm2 = render(Integrator::kPpm, 2);
    const Image reference = render(Integrator::kPath, 0);
    ASSERT_FALSE(reference.pixels.empty());
    // The floor past the light's range (and a margin for ppm's radius): x < -0.45 at y = 0.
    const double half_width = 3 * std::tan(0.4);  // the test camera, z = 3, y-fov 0.8
    double sum_path = 0, sum_path_sq = 0, sum1 = 0, sum2 = 0;
    int count = 0;
    for (int py = 0; py < 64; ++py)
        for (int px = 0; px < 64; ++px) {
            const double x = (2 * (px + 0.5) / 64 - 1) * half_width,
                         y = (1 - 2 * (py + 0.5) / 64) * half_width;
            const double distance = std::sqrt((x - 0.6) * (x - 0.6) + y * y + 0.16);
            if (std::abs(x) > 0.9 || std::abs(y) > 0.9 || distance < 1.1) continue;
            const double p = reference.At(px, py).y;
            sum_path += p, sum_path_sq += p * p;
            sum1 += ppm1.At(px, py).y, sum2 += ppm2.At(px, py).y;
            ++count;
        }
    ASSERT_GE(count, 400);
    const double path_mean = sum_path / count, ppm_mean = (sum1 + sum2) / (2 * count);
    const double path_sigma =
        std::sqrt((sum_path_sq / count - path_mean * path_mean) / (count - 1));
    const double ppm_sigma = std::abs(sum1 - sum2) / count / 2;  // |a - b| / 2 estimates it
    const double bound = 4 * std::hypot(path_sigma, ppm_sigma) + 0.01 * path_mean;
    std::printf(
        "past the range (%d pixels): ppm %.5f, path %.5f, bound %.5f (%.2f%%; sigma path %.2e, "
        "ppm %.2e)\n",
        count, ppm_mean, path_mean, bound, 100 * bound / path_mean, path_sigma, ppm_sigma);
    EXPECT_GT(path_mean, 0.0);
    EXPECT_NEAR(ppm_mean, path_mean, bound);
    EXPECT_LT(bound, 0.1 * path_mean);  // a 10% error cannot pass
}

INSTANTIATE_TEST_SUITE_P(Backends, AnalyticRender, ::testing::ValuesIn(BackendNames()),
                         [](const ::testing::TestParamInfo<std::string>& backend) {
                             return backend.param;
                         });

TEST(RenderTest, GlassSceneHasNoNaNOrInf) {
    const absl::StatusOr<RenderOutcome> outcome =
        RenderLocally(SmallRender("cornell-glass.gltf", 400'000, 2));
    ASSERT_TRUE(outcome.ok()) << outcome.status();
    double sum = 0;
    for (const Rgb& pixel : outcome->image.pixels) {
        ASSERT_TRUE(IsFinite(pixel));
        ASSERT_GE(std::min({pixel.x, pixel.y, pixel.z}), 0.0f);
        sum += Average(pixel);
    }
    EXPECT_GT(sum, 0.0);
}

// The thread counts every determinism test renders with: one, two, a count that does not
// divide the chunks evenly, and more threads than this 2-core machine has.
constexpr int kThreadCounts[] = {1, 2, 3, 7};

bool BitIdentical(const Image& a, const Image& b) {
    return a.pixels.size() == b.pixels.size() &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Rgb)) == 0;
}

// A small render of `scene` with `integrator`: ppm and sppm by photons (300k, epochs of
// 8 x 2^14), pm with maps of 100k photons in 2 epochs, path in 4 epochs.
RenderSettings DeterminismRender(const std::string& scene, Integrator integrator, int threads) {
    RenderSettings settings = SmallRender(scene, 300'000, threads);
    settings.job.integrator = integrator;
    if (integrator == Integrator::kPm) {
        settings.job.photon_budget = 0;
        settings.job.photon_map.global_photons = 100'000;
        settings.job.photon_map.caustic_photons = 100'000;
        settings.job.epoch_budget = 2;
    } else if (integrator == Integrator::kPath) {
        settings.job.photon_budget = 0;
        settings.job.epoch_budget = 4;
    }
    return settings;
}

class Determinism : public ::testing::TestWithParam<Integrator> {};

TEST_P(Determinism, SameSeedGivesBitIdenticalImagesForOneTwoThreeAndSevenThreads) {
    // cornell-glass (glass, a mirror) for every integrator; caustic-glass too for those that
    // gather photons at hit points, whose caustic paths are the longest.
    std::vector<std::string> scenes = {"cornell-glass.gltf"};
    if (GetParam() == Integrator::kPpm || GetParam() == Integrator::kSppm ||
        GetParam() == Integrator::kRpm)
        scenes.push_back("caustic-glass.gltf");
    for (const std::string& scene : scenes) {
        const absl::StatusOr<RenderOutcome> one =
            RenderLocally(DeterminismRender(scene, GetParam(), 1));
        ASSERT_TRUE(one.ok()) << one.status();
        ASSERT_FALSE(one->image.pixels.empty());
        for (const int threads : kThreadCounts) {
            if (threads == 1) continue;
            const absl::StatusOr<RenderOutcome> other =
                RenderLocally(DeterminismRender(scene, GetParam(), threads));
            ASSERT_TRUE(other.ok()) << other.status();
            EXPECT_TRUE(BitIdentical(one->image, other->image))
                << scene << ": " << threads << " threads against 1";
            EXPECT_EQ(one->progress.photons, other->progress.photons) << scene;
            EXPECT_EQ(one->progress.epochs, other->progress.epochs) << scene;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Integrators, Determinism,
                         ::testing::Values(Integrator::kPpm, Integrator::kSppm, Integrator::kPm,
                                           Integrator::kRpm, Integrator::kPath),
                         [](const ::testing::TestParamInfo<Integrator>& integrator) {
                             return std::string(IntegratorName(integrator.param));
                         });

TEST(RenderTest, BatchesOfSeveralChunksGiveTheSameImageForOneTwoThreeAndSevenThreads) {
    // One batch per epoch of two chunks and a short third: on several threads its chunks run
    // at once and are summed in chunk order, as one thread runs them one after the other.
    RenderSettings settings = SmallRender("cornell-box.gltf", 0, 1);
    settings.job.layout = {2 * kPhotonsPerChunk + 4096, 1};
    settings.job.photon_budget = settings.job.layout.PhotonsPerEpoch();
    const absl::StatusOr<RenderOutcome> one = RenderLocally(settings);
    ASSERT_TRUE(one.ok()) << one.status();
    EXPECT_EQ(one->progress.photons, settings.job.layout.PhotonsPerEpoch());
    for (const int threads : kThreadCounts) {
        if (threads == 1) continue;
        settings.threads = threads;
        const absl::StatusOr<RenderOutcome> other = RenderLocally(settings);
        ASSERT_TRUE(other.ok()) << other.status();
        EXPECT_TRUE(BitIdentical(one->image, other->image)) << threads << " threads against 1";
    }
}

// The relative error the progress line reports, measured against a reference: the root of the
// mean over pixels and channels of (image - reference)^2 / (reference^2 + 0.01) (the metric of
// ErrorEstimate::rel_mse), computed here by hand.
double RelativeError(const Image& image, const Image& reference) {
    double sum = 0;
    for (size_t p = 0; p < image.pixels.size(); ++p)
        for (int c = 0; c < 3; ++c) {
            const double value = image.pixels[p][c], expected = reference.pixels[p][c];
            sum += (value - expected) * (value - expected) / (expected * expected + 0.01);
        }
    return std::sqrt(sum / (3.0 * static_cast<double>(image.pixels.size())));
}

// Whether an estimated error is honest against the measured one: within a factor of 1.5 either
// way. The measured error includes the reference's own, from 16x the photons in small epochs:
// PPM's error falls as photons^-1/3, so at most 16^-1/3 = 0.40 of the render's, inflating the
// measurement by up to sqrt(1 + 0.40^2) = 1.08. The estimate's bias part is a model (the inner
// disc, docs/convergence.md), held on cornell-box to 0.94-1.36 of the measured error at every
// epoch from the eighth (convergence_test.cpp); 1.36 x 1.08 = 1.47, and both errors are sums
// over 48 x 48 x 3 values, whose own noise is a few percent.
bool EstimateIsHonest(double estimated, double measured) {
    return estimated <= 1.5 * measured && estimated >= measured / 1.5;
}

TEST(RenderTest, TargetErrorStopsAtTheFirstEpochWhoseHonestEstimateMeetsIt) {
    // 2%, met at the tenth epoch (estimate 0.84 of the measured error when written). At 3% it
    // is met at the fourth, where the estimate runs low, 0.74 of the measured error (0.81 at
    // the fifth epoch, where 3% was met before direct light took stratified samples): the
    // first epochs' wide radii put more of the error in the bias, whose model is least exact
    // then (docs/convergence.md).
    constexpr double kTarget = 0.02;
    RenderSettings settings = SmallRender("cornell-box.gltf", 100'000'000, 2);
    settings.job.target_error = kTarget;
    std::vector<std::optional<double>> estimates;
    const absl::StatusOr<RenderOutcome> outcome =
        RenderLocally(settings, [&](const RenderProgress& progress, const Job&) {
            estimates.push_back(progress.estimated_error);
        });
    ASSERT_TRUE(outcome.ok()) << outcome.status();
    ASSERT_TRUE(outcome->progress.estimated_error.has_value());
    const double estimated = *outcome->progress.estimated_error;
    EXPECT_LE(estimated, kTarget);
    EXPECT_LT(outcome->progress.photons, settings.job.photon_budget)
        << "the target, not the photons, ended it";
    // It stopped at the first epoch that met the target, not later.
    ASSERT_EQ(estimates.size(), outcome->progress.epochs);
    for (size_t epoch = 0; epoch + 1 < estimates.size(); ++epoch)
        EXPECT_TRUE(!estimates[epoch] || *estimates[epoch] > kTarget)
            << "epoch " << epoch + 1 << " already met the target: " << *estimates[epoch];

    // The estimate it stopped on against the error measured on a reference: the same seed (the
    // same hit points), another photon stream, 16x the photons in epochs of 2 x 2^14.
    RenderSettings reference = settings;
    reference.job.target_error = 0;
    reference.job.photon_stream = 1;
    reference.job.photon_budget = 16 * outcome->progress.photons;
    reference.job.layout = {1u << 14, 2};
    const absl::StatusOr<RenderOutcome> long_render = RenderLocally(reference);
    ASSERT_TRUE(long_render.ok()) << long_render.status();
    const double measured = RelativeError(outcome->image, long_render->image);
    EXPECT_TRUE(EstimateIsHonest(estimated, measured))
        << "estimated " << estimated << " against a measured " << measured;
    RecordProperty("estimated_over_measured", std::to_string(estimated / measured));
    // The check fails an estimate off by 2x either way: a render that stopped on half its
    // true error, or ran on past twice it.
    EXPECT_FALSE(EstimateIsHonest(estimated / 2, measured));
    EXPECT_FALSE(EstimateIsHonest(estimated * 2, measured));
}

TEST(RenderTest, DifferentSeedsGiveDifferentImages) {
    RenderSettings a = SmallRender("cornell-box.gltf", 200'000, 2), b = a;
    b.job.seed = a.job.seed + 1;
    const absl::StatusOr<RenderOutcome> first = RenderLocally(a), second = RenderLocally(b);
    ASSERT_TRUE(first.ok() && second.ok());
    EXPECT_NE(std::memcmp(first->image.pixels.data(), second->image.pixels.data(),
                          first->image.pixels.size() * sizeof(Rgb)),
              0);
}

TEST(RenderTest, BadSettingsAreRefusedWithAClearError) {
    RenderSettings settings = SmallRender("cornell-box.gltf", 1000, 1);
    settings.job.alpha = 1.5;
    const absl::StatusOr<RenderOutcome> outcome = RenderLocally(settings);
    ASSERT_FALSE(outcome.ok());
    EXPECT_NE(std::string(outcome.status().message()).find("--alpha"), std::string::npos);
}

TEST(RenderTest, TooManyHitPointsAreRefusedBeforeAnyWork) {
    RenderSettings settings = SmallRender("cornell-box.gltf", 1000, 1);
    settings.job.width = settings.job.height = 32768;
    settings.job.samples_per_pixel = 64;
    const absl::StatusOr<RenderOutcome> outcome = RenderLocally(settings);
    ASSERT_FALSE(outcome.ok());
    EXPECT_EQ(outcome.status().code(), absl::StatusCode::kResourceExhausted);
    EXPECT_NE(std::string(outcome.status().message()).find("hit points exceeds the limit"),
              std::string::npos);
}

TEST(RenderTest, PhotonsAndDirectSamplesTurnedNanAreDroppedAndCounted) {
    // Loaded input cannot hold NaN (the loader refuses it), so it is planted after loading: the
    // quad's albedo becomes NaN. Every photon that scatters off it, and every direct sample
    // there, turns NaN: each must be dropped and counted, and the tally must stay finite.
    absl::StatusOr<Scene> scene =
        LoadScene(testing::WriteGltf(testing::LitQuadScene(), "nan-albedo.gltf"));
    ASSERT_TRUE(scene.ok()) << scene.status();
    absl::StatusOr<std::unique_ptr<embree::EmbreeTracer>> tracer =
        embree::EmbreeTracer::Create(*scene);
    ASSERT_TRUE(tracer.ok());
    const CameraPassResult camera_pass =
        RunCameraPass(*scene, Emitters(*scene), **tracer, {16, 16, 1, 1});
    ASSERT_FALSE(camera_pass.hit_points.empty());
    scene->materials[scene->triangles[0].material].base_color = Rgb(std::nanf(""));  // the quad's
    std::vector<HitPoint> hit_points = camera_pass.hit_points;
    for (HitPoint& hit_point : hit_points)
        hit_point.weight = Rgb(std::nanf(""));  // direct samples turn NaN
    const Emitters emitters(*scene);
    HashGrid grid;
    grid.Build(hit_points, std::vector<float>(hit_points.size(), 0.01f));
    const PhotonPassInputs inputs{&*scene, &emitters, tracer->get(), hit_points, &grid, 1};
    PhotonPassScratch scratch;
    const BatchSpec spec =
        MakeBatchSpec({20000, 1}, 0, 0, static_cast<uint32_t>(hit_points.size()));
    const std::vector<BatchResult> results = RunPhotonBatches(inputs, std::vector{spec}, scratch);
    ASSERT_EQ(results.size(), 1u);
    EXPECT_GT(results[0].nonfinite_discarded, hit_points.size())
        << "the direct samples and the scattered photons";
    for (const Rgb& flux : results[0].tally.flux) EXPECT_TRUE(IsFinite(flux));
    for (const Rgb& direct : results[0].samples) EXPECT_TRUE(IsFinite(direct));
}

}  // namespace
}  // namespace pf
