// Direct light at hit points: light sampling weighed against cosine-distributed rays by the
// power heuristic keeps every sample bounded where light sampling alone has 1/d^2 (a point
// near the corner of emitting walls), and stays unbiased.
#include "core/ppm/direct_light.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/scene/scene_loader.h"
#include "embree/embree_tracer.h"

namespace pf {
namespace {

TEST(DirectLightTest, SamplesNearEmittingWallsAreBoundedAndUnbiased) {
    // The white furnace: a closed cube, every wall of albedo 0.5 emitting Le = 1 inward, so
    // the irradiance at any point inside is pi Le and the reflected direct light rho Le = 0.5.
    const absl::StatusOr<Scene> scene =
        LoadScene(std::string(PF_SOURCE_DIR) + "/scenes/furnace.gltf");
    ASSERT_TRUE(scene.ok()) << scene.status();
    const Emitters emitters(*scene);
    auto tracer = embree::EmbreeTracer::Create(*scene);
    ASSERT_TRUE(tracer.ok()) << tracer.status();
    constexpr float kAlbedo = 0.5f;
    // Points on the floor (y = -1), from its centre to 1e-4 from a corner and from an edge.
    std::vector<HitPoint> hit_points;
    for (const float gap : {1e-4f, 1e-3f, 1e-2f, 0.1f, 1.0f}) {
        hit_points.push_back({Vec3(-1 + gap, -1, -1 + gap), Vec3(0, 1, 0), Rgb(kAlbedo / kPi), 0});
        hit_points.push_back({Vec3(-1 + gap, -1, 0), Vec3(0, 1, 0), Rgb(kAlbedo / kPi), 0});
    }
    constexpr int kEpochs = 20000;
    std::vector<double> sum(hit_points.size()), sum_sq(hit_points.size());
    std::vector<Rgb> samples(hit_points.size());
    float largest = 0;
    for (int epoch = 0; epoch < kEpochs; ++epoch) {
        ASSERT_EQ(SampleDirectLight(emitters, **tracer, scene->materials, hit_points, 0, 5, epoch,
                                    samples),
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
        EXPECT_NEAR(mean, kAlbedo, 5 * standard_error + 1e-3) << "hit point " << i;
    }
}

}  // namespace
}  // namespace pf
