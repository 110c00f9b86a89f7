// The Vulkan backend's images against the CPU backend's, within a statistical bound.
//
// Three renders of a scene with the same seed (so the same hit points), photon budget and
// batch layout, each with its own photon stream: A and B on the CPU, V on Vulkan. If the
// Vulkan backend samples the same estimator, the three are independent draws of one random
// image: the same expectation (bias included) and per-pixel variance s^2. So
//  - spread: each pair's mean squared pixel difference estimates 2 s^2. Over P pixels of
//    which about P/4 are independent (a photon reaches the hit points of a few neighbouring
//    pixels), one such mean has a relative spread of sqrt(2 / (P/4)), 9% at 32x32; we require
//    (MSE(V,A) + MSE(V,B)) / 2 <= 1.5 MSE(A,B), over four of those spreads.
//  - mean: the image mean's variance is at most 4 s^2 / P (the same correlation), so
//    mean(V) - (mean(A) + mean(B)) / 2 has variance at most 1.5 x 4 s^2 / P with
//    s^2 = MSE(A,B) / 2; we require it within 4 of its standard deviations. At the budgets
//    below that is about 2% of the image mean: a backend 2% too bright or dark fails.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "client/local_render.h"
#include "tests/support/vulkan_validation.h"

namespace pf {
namespace {

Image Render(const std::string& scene, const std::string& backend, uint64_t stream) {
    RenderSettings settings;
    settings.scene_path = std::string(PF_SOURCE_DIR) + "/scenes/" + scene;
    settings.backend = backend;
    settings.threads = 2;
    settings.job.width = 32;
    settings.job.height = 32;
    settings.job.photon_budget = 1'000'000;
    settings.job.layout = {1u << 16, 4};
    settings.job.photon_stream = stream;
    absl::StatusOr<RenderOutcome> outcome = RenderLocally(settings);
    EXPECT_TRUE(outcome.ok()) << outcome.status();
    return outcome.ok() ? outcome->image : Image();
}

double MeanSquaredDifference(const Image& a, const Image& b) {
    double sum = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        const double d = Average(a.pixels[i]) - Average(b.pixels[i]);
        sum += d * d;
    }
    return sum / a.pixels.size();
}

double Mean(const Image& image) {
    double sum = 0;
    for (const Rgb& pixel : image.pixels) sum += Average(pixel);
    return sum / image.pixels.size();
}

class BackendAgreement : public ::testing::TestWithParam<std::string> {};

TEST_P(BackendAgreement, VulkanImageMatchesTheCpuImagesWithinTheirNoise) {
    testing::SkipWithoutVulkan();
    if (IsSkipped() || HasFatalFailure()) return;
    const unsigned long long errors_before = testing::VulkanValidationErrors();
    const Image a = Render(GetParam(), "cpu", 1), b = Render(GetParam(), "cpu", 2), v = Render(GetParam(), "vulkan", 3);
    ASSERT_EQ(v.pixels.size(), a.pixels.size());
    const double pixels = static_cast<double>(a.pixels.size());
    const double cpu_spread = MeanSquaredDifference(a, b);
    const double vulkan_spread = (MeanSquaredDifference(v, a) + MeanSquaredDifference(v, b)) / 2;
    EXPECT_LE(vulkan_spread, 1.5 * cpu_spread) << "CPU pair " << cpu_spread;
    const double mean_sigma = std::sqrt(1.5 * 4 * (cpu_spread / 2) / pixels);
    EXPECT_NEAR(Mean(v), (Mean(a) + Mean(b)) / 2, 4 * mean_sigma)
        << "CPU means " << Mean(a) << ", " << Mean(b) << "; Vulkan spread " << vulkan_spread << ", CPU " << cpu_spread;
    EXPECT_EQ(testing::VulkanValidationErrors(), errors_before);
}

INSTANTIATE_TEST_SUITE_P(Scenes, BackendAgreement, ::testing::Values("cornell-box.gltf", "cornell-glass.gltf"),
                         [](const ::testing::TestParamInfo<std::string>& scene) {
                             return scene.param.substr(0, scene.param.find('.')) == "cornell-box" ? "cornell_box"
                                                                                                 : "cornell_glass";
                         });

}  // namespace
}  // namespace pf
