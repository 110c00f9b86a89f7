// Reverse photon mapping's parts: the camera pass's gather slots, the direct light they leave
// to the photons, and the settings it refuses. Its images are checked with every integrator's
// (integrators_test.cpp: the white furnace, and against the path tracer on the Cornell scenes;
// render_test.cpp and farm_test.cpp: bit-identical on any thread count and on a farm).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/camera/camera_pass.h"
#include "core/job/job_spec.h"
#include "core/ppm/direct_light.h"
#include "tests/support/lit_scene.h"

namespace pf {
namespace {

constexpr int kPixels = 16, kSamples = 2, kGatherRays = 3;

JobSpec ReverseJob() {
    JobSpec spec;
    spec.integrator = Integrator::kRpm;
    spec.width = spec.height = kPixels;
    spec.samples_per_pixel = kSamples;
    spec.seed = 7;
    spec.photon_budget = 1'000'000;
    spec.photon_map.final_gather = kGatherRays;
    return spec;
}

// Epoch 2's pass of the rpm job on `scene`, with the film it was traced for.
struct ReversePass {
    CameraPassSettings settings;
    CameraPassResult result;
};
ReversePass TraceReversePass(const testing::LitScene& lit) {
    const JobSpec spec = ReverseJob();
    CameraPassSettings film = *FilmFor(spec, lit.scene);
    film.features = lit.features;
    const CameraPassSettings pass = StochasticCameraPass(film, spec, 2);
    return {pass, RunCameraPass(lit.scene, *lit.emitters, *lit.tracer, pass)};
}

// Each camera sample keeps 1 + gather rays slots of its pixel, in order: the camera hit point
// (caustics alone), then one per gather ray (every photon) on a diffuse surface that faces the
// camera hit point, weighted by the camera hit point's weight x pi / rays x the landing's
// albedo / pi: in the all-diffuse Cornell box, the camera hit point's weight / rays x an
// albedo, so at most its weight / rays.
TEST(ReversePhotonMapping, EachCameraSampleKeepsItsGatherSlotsInOrder) {
    const std::unique_ptr<const testing::LitScene> lit = testing::LoadLitScene("cornell-box.gltf");
    ASSERT_TRUE(lit);
    const ReversePass pass = TraceReversePass(*lit);
    ASSERT_EQ(pass.settings.gather_rays, kGatherRays);
    const std::vector<HitPoint>& slots = pass.result.hit_points;
    constexpr size_t kSlots = 1 + kGatherRays;
    ASSERT_EQ(slots.size(), size_t(kPixels) * kPixels * kSamples * kSlots);
    size_t gathered = 0, empty = 0;
    for (size_t sample = 0; sample < slots.size() / kSlots; ++sample) {
        const HitPoint& camera = slots[sample * kSlots];
        EXPECT_EQ(camera.pixel, sample / kSamples);
        EXPECT_EQ(camera.gathers, kCausticPhoton);
        for (size_t ray = 1; ray < kSlots; ++ray) {
            const HitPoint& gather = slots[sample * kSlots + ray];
            EXPECT_EQ(gather.pixel, camera.pixel);
            EXPECT_EQ(gather.gathers, kAllPhotons);
            if (IsBlack(gather.weight)) {
                ++empty;
                continue;
            }
            ++gathered;
            ASSERT_FALSE(IsBlack(camera.weight));
            // Facing the point it lights, and in the hemisphere the camera hit point sees.
            const Vec3 toward = camera.position - gather.position;
            EXPECT_GT(Dot(gather.normal, toward), 0.0f);
            EXPECT_GT(Dot(camera.normal, -toward), 0.0f);
            for (int c = 0; c < 3; ++c) {
                EXPECT_GT(gather.weight[c], 0.0f);
                EXPECT_LE(gather.weight[c], camera.weight[c] / kGatherRays * 1.0001f);
            }
        }
    }
    // The box is open toward the camera, where about two gather rays in three leave it (the
    // render's mean agrees with the path tracer's: integrators_test.cpp); a third land.
    EXPECT_GT(gathered, empty / 4);
}

// Direct light is sampled at the camera hit points only (their slots' samples follow the
// camera samples' sequences), never at the gather hits, whose photons carry it.
TEST(ReversePhotonMapping, DirectLightIsSampledAtCameraHitPointsAlone) {
    const std::unique_ptr<const testing::LitScene> lit = testing::LoadLitScene("cornell-box.gltf");
    ASSERT_TRUE(lit);
    const ReversePass pass = TraceReversePass(*lit);
    const std::vector<HitPoint>& slots = pass.result.hit_points;
    const DirectLightSequence sequence{pass.settings.samples_per_pixel, pass.settings.first_sample,
                                       1 + kGatherRays};
    std::vector<Rgb> direct(slots.size());
    EXPECT_EQ(SampleDirectLight(*lit->emitters, *lit->tracer, lit->scene.materials, slots, 0, 7, 2,
                                &sequence, direct),
              0u);
    size_t lit_camera_hits = 0;
    for (size_t i = 0; i < slots.size(); ++i) {
        if (slots[i].gathers & kDirectPhoton)
            EXPECT_TRUE(IsBlack(direct[i])) << "gather slot " << i;
        else
            lit_camera_hits += !IsBlack(direct[i]);
    }
    EXPECT_GT(lit_camera_hits, slots.size() / (1 + kGatherRays) / 2);
}

// What rpm does not offer is refused by name: alpha (its radii stay), adaptive tracing and a
// depth limit; its gather rays and k are pm's, checked as pm's are.
TEST(ReversePhotonMapping, SettingsItDoesNotTakeAreRefused) {
    EXPECT_TRUE(CheckJobSpec(ReverseJob()).ok());
    const auto refused = [](auto change, const std::string& flag) {
        JobSpec spec = ReverseJob();
        change(spec);
        const absl::Status status = CheckJobSpec(spec);
        EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << flag;
        EXPECT_NE(status.message().find(flag), std::string::npos) << status;
    };
    refused([](JobSpec& s) { s.alpha = 0.7; }, "--alpha");
    refused([](JobSpec& s) { s.photon_tracing = PhotonTracing::kAdaptive; }, "--photon-tracing");
    refused([](JobSpec& s) { s.max_depth = 5; }, "--max-depth");
    refused([](JobSpec& s) { s.photon_map.final_gather = kMaxFinalGatherRays + 1; },
            "--final-gather");
    refused([](JobSpec& s) { s.photon_map.nearest = 0; }, "--pm-nearest");
    // Gather slots count against the hit points a job may have.
    JobSpec huge = ReverseJob();
    huge.width = huge.height = 2048;
    huge.samples_per_pixel = 4;
    huge.photon_map.final_gather = 16;
    const absl::StatusOr<Scene> scene =
        LoadScene(std::string(PF_SOURCE_DIR) + "/scenes/cornell-box.gltf");
    ASSERT_TRUE(scene.ok()) << scene.status();
    const absl::StatusOr<CameraPassSettings> film = FilmFor(huge, *scene);
    EXPECT_EQ(film.status().code(), absl::StatusCode::kResourceExhausted);
    EXPECT_NE(film.status().message().find("16 gather rays"), std::string::npos) << film.status();
}

}  // namespace
}  // namespace pf
