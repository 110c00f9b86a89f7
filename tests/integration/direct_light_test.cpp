// Direct light at hit points: light sampling weighed against cosine-distributed rays by the
// power heuristic keeps every sample bounded where light sampling alone has 1/d^2 (a point
// near the corner of emitting walls), and stays unbiased, drawn from a stream per point or from
// the pixels' stratified sequences.
#include "core/ppm/direct_light.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "tests/support/lit_scene.h"

namespace pf {
namespace {

using testing::LitScene;
using testing::LoadLitScene;

TEST(DirectLightTest, SamplesNearEmittingWallsAreBoundedAndUnbiased) {
    // The white furnace: a closed cube, every wall of albedo 0.5 emitting Le = 1 inward, so
    // the irradiance at any point inside is pi Le and the reflected direct light rho Le = 0.5.
    const std::unique_ptr<const LitScene> lit = LoadLitScene("furnace.gltf");
    ASSERT_NE(lit, nullptr);
    const Scene& scene = lit->scene;
    const Emitters& emitters = *lit->emitters;
    const embree::EmbreeTracer& tracer = *lit->tracer;
    constexpr float kAlbedo = 0.5f;
    // Points on the floor (y = -1), from its centre to 1e-4 from a corner and from an edge,
    // each a pixel of its own (one slot a pixel, as a pass of one sample a pixel lays them).
    std::vector<HitPoint> hit_points;
    for (const float gap : {1e-4f, 1e-3f, 1e-2f, 0.1f, 1.0f}) {
        const auto pixel = static_cast<uint32_t>(hit_points.size());
        hit_points.push_back(
            {Vec3(-1 + gap, -1, -1 + gap), Vec3(0, 1, 0), Rgb(kAlbedo / kPi), pixel});
        hit_points.push_back({Vec3(-1 + gap, -1, 0), Vec3(0, 1, 0), Rgb(kAlbedo / kPi), pixel + 1});
    }
    constexpr int kEpochs = 20000;
    for (const bool sequenced : {false, true}) {
        std::vector<double> sum(hit_points.size()), sum_sq(hit_points.size());
        std::vector<Rgb> samples(hit_points.size());
        float largest = 0;
        for (int epoch = 0; epoch < kEpochs; ++epoch) {
            const DirectLightSequence sequence{1, uint64_t(epoch) >> 1};
            ASSERT_EQ(SampleDirectLight(emitters, tracer, scene.materials, hit_points, 0, 5, epoch,
                                        sequenced ? &sequence : nullptr, samples),
                      0u);
            for (size_t i = 0; i < samples.size(); ++i) {
                largest = std::max(largest, MaxComponent(samples[i]));
                sum[i] += samples[i].x;
                sum_sq[i] += double(samples[i].x) * samples[i].x;
            }
        }
        // Each strategy's weighted sample is at most Le pi (the cosine ray's) or Le pi / 2 (light
        // sampling's: Le cos p_l / (p_l^2 + p_b^2) <= Le cos / (2 p_b)), times albedo / pi.
        EXPECT_LE(largest, 1.5f * kAlbedo * 1.001f);
        for (size_t i = 0; i < hit_points.size(); ++i) {
            const double mean = sum[i] / kEpochs;
            const double standard_error =
                std::sqrt(std::max(0.0, sum_sq[i] / kEpochs - mean * mean) / kEpochs);
            EXPECT_NEAR(mean, kAlbedo, 5 * standard_error + 1e-3)
                << "hit point " << i << (sequenced ? ", sequenced" : "");
        }
    }
}

TEST(DirectLightTest, APixelsSequencesStratifyItsLightSamplesAcrossEpochs) {
    // A point on top of cornell-box's short block, lit by the ceiling's light: its mean over
    // 64 epochs (one sample an epoch, the pixel's sequences counting on per parity) against the
    // converged value, over independent seeds. Stratified over the light (its two triangles
    // picked by the same number, rescaled), the mean's squared error falls far below that of
    // independent samples: 1.1e-6 against 3.0e-4 when written.
    const std::unique_ptr<const LitScene> lit = LoadLitScene("cornell-box.gltf");
    ASSERT_NE(lit, nullptr);
    const Scene& scene = lit->scene;
    const Emitters& emitters = *lit->emitters;
    const embree::EmbreeTracer& tracer = *lit->tracer;
    const std::vector<HitPoint> point = {{Vec3(0.21f, 0.166f, 0.15f), Vec3(0, 1, 0), Rgb(1.0f), 0}};
    std::vector<Rgb> sample(1);
    const auto mean = [&](uint64_t seed, int epochs, bool sequenced) {
        double sum = 0;
        for (int epoch = 0; epoch < epochs; ++epoch) {
            const DirectLightSequence sequence{1, uint64_t(epoch) >> 1};
            SampleDirectLight(emitters, tracer, scene.materials, point, 0, seed, epoch,
                              sequenced ? &sequence : nullptr, sample);
            sum += sample[0].x;
        }
        return sum / epochs;
    };
    const double converged = mean(1, 1 << 18, false);
    ASSERT_GT(converged, 0);
    double squared[2] = {0, 0};
    constexpr int kSeeds = 64;
    for (uint64_t seed = 2; seed < 2 + kSeeds; ++seed)
        for (const bool sequenced : {false, true}) {
            const double error = mean(seed, 64, sequenced) - converged;
            squared[sequenced] += error * error;
        }
    EXPECT_LT(squared[1], 0.1 * squared[0])
        << "stream MSE " << squared[0] / kSeeds << ", sequenced " << squared[1] / kSeeds;
}

}  // namespace
}  // namespace pf
