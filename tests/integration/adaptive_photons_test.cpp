// Adaptive photon tracing (core/shared/photon_chain.h): its batches estimate what uniform
// tracing's do, each batch an independent estimate, compared by their means within 4 sigma of
// the batches' own spread (shown to fail 10% off); on the scene it is for, a room lit through a
// slit, with far less spread at each hit point; a pure function of the batch whatever the thread
// count; and the coordinator's auto choice picks it where few photons reach the camera's hit
// points.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "core/camera/camera_pass.h"
#include "core/ppm/hash_grid.h"
#include "core/ppm/photon_pass.h"
#include "core/shared/photon_chain.h"
#include "embedded/local_render.h"
#include "tests/support/lit_scene.h"

namespace pf {
namespace {

// A shipped scene with its 24x24 camera pass, every radius `radius`.
struct LoadedScene {
    std::unique_ptr<const testing::LitScene> lit;
    std::vector<HitPoint> hit_points;
    HashGrid grid;

    PhotonPassInputs Inputs(bool adaptive) const {
        PhotonPassInputs inputs{
            &lit->scene, lit->emitters.get(), lit->tracer.get(), hit_points, &grid,
            9,           lit->features};
        inputs.adaptive = adaptive;
        return inputs;
    }
};

std::unique_ptr<LoadedScene> Load(const std::string& name, float radius) {
    auto loaded = std::make_unique<LoadedScene>();
    loaded->lit = testing::LoadLitScene(name);
    EXPECT_NE(loaded->lit, nullptr);
    if (loaded->lit == nullptr) return nullptr;
    loaded->hit_points = RunCameraPass(loaded->lit->scene, *loaded->lit->emitters,
                                       *loaded->lit->tracer, {24, 24, 1, 3})
                             .hit_points;
    loaded->grid.Build(loaded->hit_points,
                       std::vector<float>(loaded->hit_points.size(), radius * radius));
    return loaded;
}

// The light batches bring each hit point: tally flux times weight, summed over channels, per
// photon emitted.
std::vector<double> HitPointLight(const BatchResult& result, std::span<const HitPoint> hit_points) {
    std::vector<double> light(hit_points.size(), 0.0);
    for (size_t e = 0; e < result.tally.Size(); ++e) {
        const Rgb sum = result.tally.flux[e] * hit_points[result.tally.hit_point[e]].weight;
        light[result.tally.hit_point[e]] =
            (double(sum.x) + sum.y + sum.z) / double(result.photons_emitted);
    }
    return light;
}

struct Spread {
    double mean = 0, variance = 0;  // of one batch's light over all hit points
    double point_variance = 0;      // of one batch's light at a hit point, summed over them
};

Spread BatchSpread(const LoadedScene& loaded, bool adaptive, int batches, uint32_t photons) {
    std::vector<BatchSpec> specs;
    for (int b = 0; b < batches; ++b) specs.push_back({uint64_t(b), 0, photons, 0, 0});
    PhotonPassScratch scratch;
    const std::vector<BatchResult> results =
        RunPhotonBatches(loaded.Inputs(adaptive), specs, scratch);
    const size_t n = loaded.hit_points.size();
    std::vector<double> totals, sum(n, 0.0), sum_sq(n, 0.0);
    for (const BatchResult& result : results) {
        const std::vector<double> light = HitPointLight(result, loaded.hit_points);
        double total = 0;
        for (size_t i = 0; i < n; ++i) {
            total += light[i];
            sum[i] += light[i];
            sum_sq[i] += light[i] * light[i];
        }
        totals.push_back(total);
    }
    Spread spread;
    for (const double total : totals) spread.mean += total / batches;
    for (const double total : totals)
        spread.variance += (total - spread.mean) * (total - spread.mean) / (batches - 1);
    for (size_t i = 0; i < n; ++i)
        spread.point_variance += (sum_sq[i] - sum[i] * sum[i] / batches) / (batches - 1);
    return spread;
}

TEST(AdaptivePhotonsTest, MutationsStayInTheUnitIntervalAndTheSizeWithinItsBounds) {
    for (const float u : {0.0f, 0.3f, 0.999999f})
        for (const float v : {0.0f, 0.5f, 0.999999f})
            for (const float size : {gpu::kLeastMutationSize, 0.1f, gpu::kMostMutationSize}) {
                const float moved = gpu::MutateNumber(u, v, size);
                EXPECT_GE(moved, 0.0f);
                EXPECT_LT(moved, 1.0f);
            }
    EXPECT_FLOAT_EQ(gpu::MutateNumber(0.25f, 0.5f, 0.3f), 0.25f);  // v = 1/2 moves nothing
    EXPECT_FLOAT_EQ(gpu::MutateNumber(0.1f, 0.0f, 0.25f), 0.85f);  // wrapped below 0
    // Every mutation taken grows the size, none shrinks it, within the bounds.
    EXPECT_GT(gpu::AdaptMutationSize(0.1f, 1, 1), 0.1f);
    EXPECT_LT(gpu::AdaptMutationSize(0.1f, 0, 1), 0.1f);
    EXPECT_EQ(gpu::AdaptMutationSize(0.5f, 10, 10), gpu::kMostMutationSize);
    EXPECT_EQ(gpu::AdaptMutationSize(gpu::kLeastMutationSize, 0, 2), gpu::kLeastMutationSize);
}

TEST(AdaptivePhotonsTest, BatchesEstimateWhatUniformOnesDoWithLessSpreadThroughASlit) {
    // light-gap: a room lit by a lamp outside through a slit; about one photon in twenty gets
    // in. Each batch is an independent estimate (its chains start afresh), so the means of 48
    // of each compare within 4 sigma of their spread.
    const std::unique_ptr<LoadedScene> loaded = Load("light-gap.gltf", 0.08f);
    ASSERT_NE(loaded, nullptr);
    ASSERT_GT(loaded->hit_points.size(), 400u);
    const double visible = VisiblePhotonShare(loaded->Inputs(false), 1u << 15);
    EXPECT_GT(visible, 0.0);
    EXPECT_LT(visible, kAdaptiveBelowVisibleShare);
    constexpr int kBatches = 48;
    const Spread uniform = BatchSpread(*loaded, false, kBatches, 1u << 15);
    const Spread adaptive = BatchSpread(*loaded, true, kBatches, 1u << 15);
    const double sigma = std::sqrt((uniform.variance + adaptive.variance) / kBatches);
    std::printf(
        "visible share %.4f; a batch's light: uniform %.5g +- %.3g, adaptive %.5g +- %.3g; "
        "at a hit point, variance summed: uniform %.4g, adaptive %.4g\n",
        visible, uniform.mean, std::sqrt(uniform.variance), adaptive.mean,
        std::sqrt(adaptive.variance), uniform.point_variance, adaptive.point_variance);
    EXPECT_LT(std::abs(adaptive.mean - uniform.mean), 4 * sigma);
    // The check has the power to see a normalisation 10% off.
    EXPECT_GT(std::abs(1.1 * adaptive.mean - uniform.mean), 4 * sigma);
    // The chains put many times as many photons where they count: each hit point's estimate
    // spreads far less. (The total spreads about as much: it rests on the fresh photons' share
    // V_c, whose noise is common to all hit points and, over a render's many batches, small.)
    EXPECT_LT(adaptive.point_variance, 0.25 * uniform.point_variance);
}

TEST(AdaptivePhotonsTest, ABatchIsTheSameOnOneThreadAndOnTwo) {
    const std::unique_ptr<LoadedScene> loaded = Load("caustic-room.gltf", 0.02f);
    ASSERT_NE(loaded, nullptr);
    const PhotonPassInputs inputs = loaded->Inputs(true);
    // Two chunks a batch, so the chunks' sums meet too.
    const std::vector<BatchSpec> specs = {{3, 0, kPhotonsPerChunk + 5000, 0, 0},
                                          {4, 0, 20000, 0, 0}};
    std::vector<BatchResult> one, two;
    tbb::task_arena(1).execute([&] {
        PhotonPassScratch scratch;
        one = RunPhotonBatches(inputs, specs, scratch);
    });
    tbb::task_arena(2).execute([&] {
        PhotonPassScratch scratch;
        two = RunPhotonBatches(inputs, specs, scratch);
    });
    ASSERT_EQ(one.size(), two.size());
    for (size_t b = 0; b < one.size(); ++b) {
        EXPECT_GT(one[b].tally.Size(), 0u);
        EXPECT_EQ(one[b].tally.hit_point, two[b].tally.hit_point);
        EXPECT_EQ(one[b].tally.photons, two[b].tally.photons);
        ASSERT_EQ(one[b].tally.flux.size(), two[b].tally.flux.size());
        for (size_t e = 0; e < one[b].tally.flux.size(); ++e)
            EXPECT_TRUE(one[b].tally.flux[e] == two[b].tally.flux[e]);
    }
}

// light-gap and caustic-glass (an open scene: photons off the plane escape) send few photons
// where the camera looks; caustic-room mirrors its whole room in its sphere, so most of its
// photons reach something the camera sees, as most of cornell-box's do.
TEST(AdaptivePhotonsTest, AutoChoosesAdaptiveWhereFewPhotonsReachTheCamerasHitPoints) {
    for (const auto& [name, expected] : {std::pair{"light-gap.gltf", PhotonTracing::kAdaptive},
                                         std::pair{"caustic-glass.gltf", PhotonTracing::kAdaptive},
                                         std::pair{"caustic-room.gltf", PhotonTracing::kUniform},
                                         std::pair{"cornell-box.gltf", PhotonTracing::kUniform}}) {
        RenderSettings settings;
        settings.scene_path = std::string(PF_SOURCE_DIR) + "/scenes/" + name;
        settings.threads = 2;
        settings.job.width = settings.job.height = 64;
        settings.job.epoch_budget = 1;
        settings.job.layout = {1u << 14, 2};
        const absl::StatusOr<RenderOutcome> outcome = RenderLocally(settings);
        ASSERT_TRUE(outcome.ok()) << outcome.status();
        EXPECT_EQ(outcome->job.photon_tracing, expected) << name;
        for (const Rgb& pixel : outcome->image.pixels) EXPECT_TRUE(IsFinite(pixel)) << name;
    }
}

}  // namespace
}  // namespace pf
