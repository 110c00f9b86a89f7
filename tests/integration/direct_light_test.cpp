// Direct light at hit points: light sampling weighed against cosine-distributed rays by the
// power heuristic keeps every sample bounded where light sampling alone has 1/d^2 (a point
// near the corner of emitting walls), and stays unbiased, drawn from a stream per point or from
// the pixels' stratified sequences.
#include "core/ppm/direct_light.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "core/camera/camera_pass.h"
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

// Bit for bit: a float's bits, so that -0 and NaN compare as stored.
bool SameBits(const HitPoint& a, const HitPoint& b) {
    return std::memcmp(&a, &b, sizeof(HitPoint)) == 0;
}

TEST(DirectLightTest, APartOfAnEpochsPassHoldsTheWholePassesSlotsAndSamples) {
    // A worker traces only the pixels of its batches' direct-light slices (CameraPassPart):
    // their slots and the light sampled there must be the whole pass's, for slices that start
    // and end inside rows and pixels, with rpm's gather rays (three slots a sample) and without.
    const std::unique_ptr<const LitScene> lit = LoadLitScene("cornell-glossy.gltf");
    ASSERT_NE(lit, nullptr);
    for (const int gather_rays : {0, 2}) {
        SCOPED_TRACE(::testing::Message() << gather_rays << " gather rays");
        CameraPassSettings pass{37, 23, 2, 9};  // rows of 37 pixels, 2 samples a pixel
        pass.stochastic = true;
        pass.epoch = 3;
        pass.first_sample = 6;
        pass.gather_rays = gather_rays;
        pass.features = lit->features;
        const std::vector<HitPoint> whole =
            RunCameraPass(lit->scene, *lit->emitters, *lit->tracer, pass).hit_points;
        const uint64_t slots_per_pixel = 2ull * (1 + gather_rays);
        ASSERT_EQ(whole.size(), 37u * 23u * slots_per_pixel);
        const DirectLightSequence sequence{2, 6, 1 + gather_rays};
        CameraPassPart part;
        part.Reset(pass);
        const std::vector<std::vector<BatchSpec>> leases = {
            {{.epoch = 3, .sample_begin = 5, .sample_end = 100}},
            {{.epoch = 3, .sample_begin = 97, .sample_end = 1301}},
            {{.epoch = 3, .sample_begin = 10, .sample_end = 20},
             {.epoch = 3, .sample_begin = 500, .sample_end = 611}},
            {{.epoch = 3, .sample_begin = 0, .sample_end = uint32_t(whole.size())}}};
        for (const std::vector<BatchSpec>& specs : leases) {
            EXPECT_TRUE(part.Cover(lit->scene, *lit->emitters, *lit->tracer, specs));
            EXPECT_FALSE(part.Cover(lit->scene, *lit->emitters, *lit->tracer, specs))
                << "traced it twice";
            const std::span<const HitPoint> points = part.Points();
            ASSERT_LE(part.FirstSlot() + points.size(), whole.size());
            EXPECT_EQ(part.FirstSlot() % slots_per_pixel, 0u);
            for (size_t i = 0; i < points.size(); ++i)
                ASSERT_TRUE(SameBits(points[i], whole[part.FirstSlot() + i])) << "slot " << i;
            for (const BatchSpec& spec : specs) {
                ASSERT_LE(part.FirstSlot(), spec.sample_begin);
                ASSERT_LE(spec.sample_end, part.FirstSlot() + points.size());
                std::vector<Rgb> from_part(spec.sample_end - spec.sample_begin),
                    from_whole(from_part.size());
                SampleDirectLight(*lit->emitters, *lit->tracer, lit->scene.materials, points,
                                  spec.sample_begin, 5, 3, &sequence, from_part, part.FirstSlot());
                SampleDirectLight(*lit->emitters, *lit->tracer, lit->scene.materials, whole,
                                  spec.sample_begin, 5, 3, &sequence, from_whole);
                EXPECT_EQ(std::memcmp(from_part.data(), from_whole.data(),
                                      from_part.size() * sizeof(Rgb)),
                          0);
            }
        }
        // A lease inside the part held traces nothing more.
        EXPECT_FALSE(part.Cover(lit->scene, *lit->emitters, *lit->tracer,
                                std::vector<BatchSpec>{{.sample_begin = 7, .sample_end = 8}}));
    }
}

TEST(DirectLightTest, BatchesShareOutTheEmissionPassAsTheWholePassGivesIt) {
    // ppm's workers trace each epoch's emission pass, each batch at its slice's pixels
    // (TraceBatchEmission), leases of several batches as one part: together the batches must
    // give every pixel's emission and every fixed hit point's coverage as the whole pass does,
    // each once. Glass, so samples split and pixels hold several hit points.
    const std::unique_ptr<const LitScene> lit = LoadLitScene("cornell-glass.gltf");
    ASSERT_NE(lit, nullptr);
    CameraPassSettings film{29, 17, 3, 4};
    film.features = lit->features;
    const std::vector<HitPoint> points =
        RunCameraPass(lit->scene, *lit->emitters, *lit->tracer, film).hit_points;
    const absl::StatusOr<PixelHitPoints> fixed = IndexFixedHitPoints(points, film);
    ASSERT_TRUE(fixed.ok()) << fixed.status();
    CameraPassSettings pass = film;
    pass.emission_only = true;
    pass.epoch = 5;
    const CameraPassResult whole =
        RunCameraPass(lit->scene, *lit->emitters, *lit->tracer, pass, &*fixed);
    ASSERT_EQ(whole.coverage.size(), points.size());
    // Seven batches over the pass's slots (3 a pixel), leased as {0, 1, 2}, {3}, {4, 5, 6}.
    constexpr uint32_t kBatches = 7;
    std::vector<BatchResult> results(kBatches);
    for (uint32_t j = 0; j < kBatches; ++j)
        results[j].spec = MakeBatchSpec({1000, kBatches}, 5, j, 29 * 17 * 3);
    for (const auto& [first, count] : {std::pair(0, 3), std::pair(3, 1), std::pair(4, 3)})
        TraceBatchEmission(lit->scene, *lit->emitters, *lit->tracer, pass, *fixed,
                           std::span(results).subspan(first, count));
    std::vector<Rgb> emission, coverage;
    for (const BatchResult& result : results) {
        emission.insert(emission.end(), result.emission.begin(), result.emission.end());
        coverage.insert(coverage.end(), result.coverage.begin(), result.coverage.end());
    }
    ASSERT_EQ(emission.size(), whole.emission.pixels.size());
    EXPECT_EQ(
        std::memcmp(emission.data(), whole.emission.pixels.data(), emission.size() * sizeof(Rgb)),
        0);
    ASSERT_EQ(coverage.size(), whole.coverage.size());
    EXPECT_EQ(std::memcmp(coverage.data(), whole.coverage.data(), coverage.size() * sizeof(Rgb)),
              0);
}

}  // namespace
}  // namespace pf
