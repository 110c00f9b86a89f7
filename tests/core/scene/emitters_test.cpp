// Emitters: photons leave each light in proportion to its power, carry the scene's total
// power on average, and direct-light samples integrate to the known irradiance.
#include "core/scene/emitters.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/scene/scene_loader.h"
#include "tests/support/chi_square.h"
#include "tests/support/gltf_builder.h"

namespace pf {
namespace {

TEST(EmittersTest, AreaLightPowerIsPiTimesAreaTimesRadiance) {
    const absl::StatusOr<Scene> scene =
        LoadScene(testing::WriteGltf(testing::LitQuadScene(), "emit-quad.gltf"));
    ASSERT_TRUE(scene.ok()) << scene.status();
    const Emitters emitters(*scene);
    // A 0.4 x 0.4 quad of radiance 10: pi * 0.16 * 10.
    EXPECT_NEAR(emitters.TotalPower().x, kPiD * 0.16 * 10.0, 1e-4);
}

TEST(EmittersTest, PhotonsLeaveLightsInProportionToPowerAndCarryTheTotal) {
    testing::TestScene test_scene = testing::LitQuadScene();
    // Intensities in candela, 683 to the watt: 1 and 3 W/sr.
    test_scene.lights = {R"({"type":"point","intensity":683})",
                         R"({"type":"point","intensity":2049})"};
    const absl::StatusOr<Scene> scene =
        LoadScene(testing::WriteGltf(test_scene, "emit-mixed.gltf"));
    ASSERT_TRUE(scene.ok()) << scene.status();
    const Emitters emitters(*scene);
    // Emitters: 2 area triangles (power pi*0.08*10 each), point lights 4 pi and 12 pi.
    const double powers[] = {kPiD * 0.8, kPiD * 0.8, 4 * kPiD, 12 * kPiD};
    const double total = powers[0] + powers[1] + powers[2] + powers[3];
    EXPECT_NEAR(emitters.TotalPower().x, total, 1e-3);
    Rng rng(1);
    constexpr int kPhotons = 200000;
    std::vector<double> observed(2, 0.0);  // from the area light, from the point lights
    double flux_sum = 0;
    for (int i = 0; i < kPhotons; ++i) {
        const EmittedPhoton photon = emitters.Emit(rng);
        flux_sum += photon.flux.x;
        observed[std::abs(photon.ray.origin.z - 1.0f) < 1e-3f ? 0 : 1] += 1;
    }
    const std::vector<double> expected = {kPhotons * (powers[0] + powers[1]) / total,
                                          kPhotons * (powers[2] + powers[3]) / total};
    EXPECT_TRUE(testing::ChiSquarePasses(observed, expected));
    // Each photon carries its light's power over its selection probability: the total on average.
    EXPECT_NEAR(flux_sum / kPhotons, total, 1e-3 * total);
}

TEST(EmittersTest, DirectSamplesIntegrateToThePointLightIrradiance) {
    testing::TestScene test_scene = testing::LitQuadScene();
    test_scene.materials[1].emission = Rgb(0.0f);
    test_scene.lights = {R"({"type":"point","intensity":1366})"};  // 2 W/sr
    const absl::StatusOr<Scene> scene =
        LoadScene(testing::WriteGltf(test_scene, "emit-point.gltf"));
    ASSERT_TRUE(scene.ok()) << scene.status();
    const Emitters emitters(*scene);
    Rng rng(2);
    LightSample sample;
    // A receiver at distance 2 below the light, facing it: E = I cos / d^2 = 2 / 4.
    ASSERT_TRUE(emitters.SampleDirect(Vec3(0, 0, -2), Vec3(0, 0, 1), rng, &sample));
    EXPECT_NEAR(sample.radiance_over_pdf.x * Dot(sample.direction, Vec3(0, 0, 1)), 0.5f, 1e-4f);
    // Facing away: no light.
    EXPECT_FALSE(emitters.SampleDirect(Vec3(0, 0, -2), Vec3(0, 0, -1), rng, &sample));
}

TEST(EmittersTest, AreaLightDirectSamplesConvergeToTheAnalyticIrradiance) {
    const absl::StatusOr<Scene> scene =
        LoadScene(testing::WriteGltf(testing::LitQuadScene(), "emit-area.gltf"));
    ASSERT_TRUE(scene.ok()) << scene.status();
    const Emitters emitters(*scene);
    // Irradiance at the centre below a square of half-side a at height h with radiance L:
    // E = 4 L [ a / sqrt(a^2 + h^2) atan(a / sqrt(a^2 + h^2)) ] (four corner rectangles).
    const double a = 0.2, h = 1.0, radiance = 10.0;
    const double s = a / std::sqrt(a * a + h * h);
    const double expected = 4 * radiance * s * std::atan(s);
    Rng rng(3);
    double sum = 0, sum_sq = 0;
    constexpr int kSamples = 200000;
    LightSample sample;
    for (int i = 0; i < kSamples; ++i) {
        double value = 0;
        if (emitters.SampleDirect(Vec3(0, 0, 0), Vec3(0, 0, 1), rng, &sample))
            value = sample.radiance_over_pdf.x * Dot(sample.direction, Vec3(0, 0, 1));
        sum += value;
        sum_sq += value * value;
    }
    const double mean = sum / kSamples;
    const double standard_error = std::sqrt((sum_sq / kSamples - mean * mean) / kSamples);
    EXPECT_NEAR(mean, expected, 5 * standard_error + 1e-4 * expected);
}

}  // namespace
}  // namespace pf
