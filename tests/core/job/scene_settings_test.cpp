// A scene's own render settings (pbrt's Integrator and Sampler) where the flags leave them open.
#include "core/job/scene_settings.h"

#include <gtest/gtest.h>

#include "core/job/job_spec.h"

namespace pf {
namespace {

SceneRenderSettings Sppm() {
    SceneRenderSettings scene;
    scene.integrator = "sppm";
    scene.iterations = 64;
    scene.photons_per_iteration = 100'000;
    scene.max_depth = 7;
    scene.integrator_source = "s.pbrt:1:1: Integrator \"sppm\"";
    return scene;
}

TEST(SceneSettingsTest, SppmBecomesTheJobWhereNoFlagSaysOtherwise) {
    JobSpec spec;
    const std::vector<std::string> notes = ApplySceneSettings(Sppm(), {}, &spec);
    EXPECT_EQ(spec.integrator, Integrator::kSppm);
    EXPECT_EQ(spec.epoch_budget, 64u);
    EXPECT_EQ(spec.photon_budget, 0u);  // the iterations are the budget
    EXPECT_EQ(spec.layout.batches_per_epoch, 8u);
    EXPECT_EQ(spec.layout.photons_per_batch, 12'500u);  // 100,000 photons an epoch
    EXPECT_EQ(spec.samples_per_pixel, 1);
    EXPECT_EQ(spec.max_depth, 7);
    ASSERT_FALSE(notes.empty());
    EXPECT_EQ(notes.front(), "s.pbrt:1:1: Integrator \"sppm\": --integrator sppm");
    EXPECT_TRUE(CheckJobSpec(spec).ok());
}

TEST(SceneSettingsTest, FlagsWin) {
    JobSpec spec;
    spec.integrator = Integrator::kPpm;
    spec.seconds_budget = 10;
    spec.samples_per_pixel = 4;
    spec.max_depth = 3;
    // The integrator given: sppm's parameters belong to sppm and are left out.
    ApplySceneSettings(Sppm(), {.integrator = true, .max_depth = true}, &spec);
    EXPECT_EQ(spec.integrator, Integrator::kPpm);
    EXPECT_EQ(spec.epoch_budget, 0u);
    EXPECT_EQ(spec.seconds_budget, 10);
    EXPECT_EQ(spec.layout.photons_per_batch, BatchLayout{}.photons_per_batch);
    EXPECT_EQ(spec.samples_per_pixel, 4);
    EXPECT_EQ(spec.max_depth, 3);

    // sppm chosen by the scene, but the budget, samples and layout given.
    JobSpec given;
    given.photon_budget = 1'000'000;
    given.samples_per_pixel = 2;
    given.layout = {1000, 4};
    ApplySceneSettings(Sppm(), {.samples_per_pixel = true, .layout = true}, &given);
    EXPECT_EQ(given.integrator, Integrator::kSppm);
    EXPECT_EQ(given.epoch_budget, 0u);
    EXPECT_EQ(given.photon_budget, 1'000'000u);
    EXPECT_EQ(given.samples_per_pixel, 2);
    EXPECT_EQ(given.layout.photons_per_batch, 1000u);
    EXPECT_EQ(given.max_depth, 7);
}

TEST(SceneSettingsTest, PixelSamplesSpreadOverEpochsForTheIntegratorsThatSamplePixels) {
    SceneRenderSettings scene;
    scene.integrator = "path";
    scene.pixel_samples = 1000;
    JobSpec spec;
    ApplySceneSettings(scene, {}, &spec);
    EXPECT_EQ(spec.integrator, Integrator::kPath);
    EXPECT_EQ(spec.epoch_budget, 16u);
    EXPECT_EQ(spec.samples_per_pixel, 63);  // 16 x 63 = 1008: at least the scene's 1000

    JobSpec few;
    scene.pixel_samples = 4;
    ApplySceneSettings(scene, {}, &few);
    EXPECT_EQ(few.epoch_budget, 4u);
    EXPECT_EQ(few.samples_per_pixel, 1);

    JobSpec epochs_given;  // --epochs 5: 1000 over 5
    epochs_given.epoch_budget = 5;
    scene.pixel_samples = 1000;
    ApplySceneSettings(scene, {}, &epochs_given);
    EXPECT_EQ(epochs_given.samples_per_pixel, 200);

    JobSpec ppm;  // ppm's k hit points are not pixel samples
    ApplySceneSettings(scene, {.integrator = true}, &ppm);
    EXPECT_EQ(ppm.samples_per_pixel, JobSpec{}.samples_per_pixel);
    EXPECT_EQ(ppm.photon_budget, 20'000'000u);  // the default budget
}

TEST(SceneSettingsTest, NoSceneSettingsLeaveTheDefaults) {
    JobSpec spec;
    EXPECT_TRUE(ApplySceneSettings({}, {}, &spec).empty());
    EXPECT_EQ(spec.integrator, Integrator::kPpm);
    EXPECT_EQ(spec.photon_budget, 20'000'000u);
    EXPECT_EQ(spec.max_depth, 0);
}

}  // namespace
}  // namespace pf
