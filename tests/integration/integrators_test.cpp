// Every integrator against the analytic white furnace (each channel's mean within a derived
// 4 sigma, shown to fail at 2% off), and every photon mapper against the unbiased path tracer
// on the shipped Cornell scenes, within statistical bounds measured from the path tracer's own
// epochs: a photon mapper that comes out darker or brighter than the path tracer has lost or
// invented light.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "client/local_render.h"
#include "core/pm/density_estimate.h"
#include "core/render/integrator.h"
#include "tests/support/numerics_cases.h"

namespace pf {
namespace {

std::string ScenePath(const std::string& name) {
    return std::string(PF_SOURCE_DIR) + "/scenes/" + name;
}

// A small render of `scene` with `integrator`, on two threads, with a budget that puts its
// noise well below the bounds below in a few seconds.
RenderSettings Small(const std::string& scene, Integrator integrator, int size) {
    RenderSettings settings;
    settings.scene_path = ScenePath(scene);
    settings.threads = 2;
    JobSpec& job = settings.job;
    job.integrator = integrator;
    job.width = job.height = size;
    job.seed = 5;
    job.layout = {1u << 18, 8};
    switch (integrator) {
        // Progressive photon mapping keeps its k camera samples a pixel for good: with 4, the
        // light's edge pixels alone move a 64-pixel image's mean by a few percent from seed to
        // seed, error that no photon removes (stochastic ppm re-samples them every epoch).
        case Integrator::kPpm:
            job.samples_per_pixel = 16, job.photon_budget = 12'000'000;
            break;
        case Integrator::kSppm:
            job.photon_budget = 12'000'000;
            break;
        case Integrator::kPm:
            job.photon_map.global_photons = 1'000'000;
            job.photon_map.caustic_photons = 1'000'000;
            job.epoch_budget = 8;
            break;
        case Integrator::kPath:
            job.epoch_budget = 96;
            break;
    }
    return settings;
}

std::string Name(const ::testing::TestParamInfo<Integrator>& info) {
    return std::string(IntegratorName(info.param));
}

// Means over square blocks of pixels, per channel, averaged into one value a block.
std::vector<double> BlockMeans(const Image& image, int block) {
    std::vector<double> means;
    for (int by = 0; by + block <= image.height; by += block)
        for (int bx = 0; bx + block <= image.width; bx += block) {
            double sum = 0;
            for (int y = by; y < by + block; ++y)
                for (int x = bx; x < bx + block; ++x) sum += Average(image.At(x, y));
            means.push_back(sum / (block * block));
        }
    return means;
}

// Every integrator's white furnace, checked on the pixels away from the cube's edges, whose
// expected value each knows in closed form, within 4 sigma derived for it below, and the
// median (testing::CheckFurnace, which says why the median needs more room).
class WhiteFurnace : public ::testing::TestWithParam<Integrator> {};

TEST_P(WhiteFurnace, ConvergesToEmissionOverOneMinusAlbedo) {
    // furnace.gltf: a closed room of albedo 0.5 emitting Le = 1 everywhere, so L = 2 exactly,
    // through every path length: direct emission, light sampling, photons and MIS weights alike.
    constexpr double kRho = 0.5, kRadiance = 2.0;
    const RenderSettings settings = Small("furnace.gltf", GetParam(), 32);
    const absl::StatusOr<RenderOutcome> outcome = RenderLocally(settings);
    ASSERT_TRUE(outcome.ok()) << outcome.status();
    for (const Rgb& pixel : outcome->image.pixels) ASSERT_TRUE(IsFinite(pixel));
    // The radius within which an estimate gathers: R0 for the progressive mappers (radii only
    // shrink), the k-nearest search's limit for pm (2% of the cube's diagonal, 2 sqrt(3)).
    const double radius =
        GetParam() == Integrator::kPm ? 0.02 * 2 * std::sqrt(3.0) : outcome->initial_radius;
    const testing::BoxInterior interior =
        testing::BoxInteriorPixels(settings.scene_path, 32, 32, radius);
    ASSERT_GE(interior.count, 512u);
    // Direct-light samples over the interior: one per camera sample (k a pixel) and epoch.
    const double direct_samples = static_cast<double>(interior.count) *
                                  settings.job.samples_per_pixel *
                                  static_cast<double>(outcome->progress.epochs);
    double expected = kRadiance, sigma = -1;
    switch (GetParam()) {
        case Integrator::kPpm:
        case Integrator::kSppm:
            // Unbiased on a flat density, noise as derived for numerics_cases.cpp's furnaces.
            sigma = testing::FurnaceMeanSigma(kRho, static_cast<double>(outcome->progress.photons),
                                              interior.area_fraction, direct_samples);
            break;
        case Integrator::kPm: {
            // The global map read at the camera's hit holds the photon part, rho^2 of L, and
            // Jensen's cone filter (weights 1 - d / (K r), normalised by 1 - 2 / (3K)) over the
            // k nearest overestimates a uniform density: the k - 1 inner photons lie uniformly
            // in the disc of the k-th, whose weight is 1 - 1/K, and E[1 / (pi r_k^2)] =
            // density / (k - 1) (pi r_k^2 density is Gamma(k)), so the estimate's expectation
            // is density x (1 + (1 - 1/K) / ((1 - 2/(3K)) (k - 1))): +0.37% at k = 64, K = 1.1.
            const double k = settings.job.photon_map.nearest, cone = kConeFilterK;
            expected *= 1 + kRho * kRho * (1 - 1 / cone) / ((1 - 2 / (3 * cone)) * (k - 1));
            sigma = testing::FurnaceMeanSigma(kRho, static_cast<double>(outcome->progress.photons),
                                              interior.area_fraction, direct_samples);
            break;
        }
        case Integrator::kPath:
            break;  // unbiased, and its pixels independent: sigma from their spread
    }
    const testing::FurnaceCheck check =
        testing::CheckFurnace(outcome->image, interior, expected, sigma);
    EXPECT_TRUE(check.Passed()) << check.Describe();
    std::printf("%s: %s\n", std::string(IntegratorName(GetParam())).c_str(),
                check.Describe().c_str());
    for (const Rgbd& bias : {Rgbd(1.02), Rgbd(0.98), Rgbd(1.0, 1.02, 1.0)}) {
        const testing::FurnaceCheck biased =
            testing::CheckFurnace(outcome->image, interior, expected, sigma, bias);
        EXPECT_FALSE(biased.Passed()) << "biased " << bias.x << " " << bias.y << " " << bias.z
                                      << " and passed: " << biased.Describe();
    }
}

INSTANTIATE_TEST_SUITE_P(Integrators, WhiteFurnace,
                         ::testing::Values(Integrator::kPpm, Integrator::kSppm, Integrator::kPm,
                                           Integrator::kPath),
                         Name);

// The path tracer's image of a scene, with each block's standard error measured from the
// spread of its epochs (independent samples).
struct Reference {
    std::vector<double> mean, standard_error;
};

Reference PathTracerReference(const std::string& scene, int size, int block) {
    Reference reference;
    std::vector<std::vector<double>> epochs;
    Image previous(size, size);
    const EpochCallback on_epoch = [&](const RenderProgress& progress, const Job& job) {
        // The job's image is the mean of its epochs: this epoch's own is n E_n - (n - 1) E_(n-1).
        const Image current = *job.CurrentImage();
        Image epoch(size, size);
        const float n = static_cast<float>(progress.epochs);
        for (size_t p = 0; p < current.pixels.size(); ++p)
            epoch.pixels[p] = current.pixels[p] * n - previous.pixels[p] * (n - 1);
        epochs.push_back(BlockMeans(epoch, block));
        previous = current;
    };
    const absl::StatusOr<RenderOutcome> outcome =
        RenderLocally(Small(scene, Integrator::kPath, size), on_epoch);
    EXPECT_TRUE(outcome.ok()) << outcome.status();
    if (!outcome.ok() || epochs.size() < 2) return reference;
    reference.mean = BlockMeans(outcome->image, block);
    const double n = static_cast<double>(epochs.size());
    for (size_t b = 0; b < reference.mean.size(); ++b) {
        double squares = 0;
        for (const std::vector<double>& epoch : epochs)
            squares += (epoch[b] - reference.mean[b]) * (epoch[b] - reference.mean[b]);
        reference.standard_error.push_back(std::sqrt(squares / (n - 1) / n));
    }
    return reference;
}

struct SceneCase {
    std::string scene;
    Integrator integrator;
};

class AgreesWithThePathTracer : public ::testing::TestWithParam<SceneCase> {};

TEST_P(AgreesWithThePathTracer, BlockByBlockAndOverall) {
    constexpr int kSize = 64, kBlock = 16;
    const SceneCase& c = GetParam();
    const Reference reference = PathTracerReference(c.scene, kSize, kBlock);
    ASSERT_FALSE(reference.mean.empty());
    const absl::StatusOr<RenderOutcome> outcome =
        RenderLocally(Small(c.scene, c.integrator, kSize));
    ASSERT_TRUE(outcome.ok()) << outcome.status();
    const std::vector<double> blocks = BlockMeans(outcome->image, kBlock);
    // Each block within 4 of the path tracer's standard errors plus 4% for the photon mapper's
    // own noise and its bias (radii or k-nearest discs that blur light across edges); the
    // whole image within 4 standard errors plus 1.5%.
    double sum = 0, reference_sum = 0, variance = 0;
    for (size_t b = 0; b < blocks.size(); ++b) {
        const double expected = reference.mean[b];
        EXPECT_NEAR(blocks[b], expected, 4 * reference.standard_error[b] + 0.04 * expected)
            << IntegratorName(c.integrator) << " on " << c.scene << ", block " << b << " of "
            << blocks.size();
        sum += blocks[b];
        reference_sum += expected;
        variance += reference.standard_error[b] * reference.standard_error[b];
    }
    const double count = static_cast<double>(blocks.size());
    EXPECT_NEAR(sum / count, reference_sum / count,
                4 * std::sqrt(variance) / count + 0.015 * reference_sum / count)
        << IntegratorName(c.integrator) << " on " << c.scene
        << ": the image mean against the path tracer's";
}

std::string CaseName(const ::testing::TestParamInfo<SceneCase>& info) {
    std::string scene = info.param.scene.substr(0, info.param.scene.find('.'));
    std::replace(scene.begin(), scene.end(), '-', '_');
    return std::string(IntegratorName(info.param.integrator)) + "_" + scene;
}

INSTANTIATE_TEST_SUITE_P(PhotonMappers, AgreesWithThePathTracer,
                         ::testing::Values(SceneCase{"cornell-box.gltf", Integrator::kPpm},
                                           SceneCase{"cornell-box.gltf", Integrator::kSppm},
                                           SceneCase{"cornell-box.gltf", Integrator::kPm},
                                           SceneCase{"cornell-glossy.gltf", Integrator::kSppm}),
                         CaseName);

}  // namespace
}  // namespace pf
