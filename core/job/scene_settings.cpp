// A scene's own render settings, where the flags leave them open.
#include "core/job/scene_settings.h"

#include <algorithm>

#include "absl/strings/str_cat.h"
#include "core/job/job_spec.h"

namespace pf {
namespace {

constexpr uint64_t kDefaultEpochs = 16;

bool HasBudget(const JobSpec& spec) {
    return spec.until_cancelled || spec.photon_budget != 0 || spec.epoch_budget != 0 ||
           spec.seconds_budget != 0 || spec.target_error != 0;
}

}  // namespace

std::vector<std::string> ApplySceneSettings(const SceneRenderSettings& scene,
                                            const GivenSettings& given, JobSpec* spec) {
    std::vector<std::string> notes;
    const bool budget_given = HasBudget(*spec);
    const std::optional<Integrator> asked = ParseIntegrator(scene.integrator);
    if (asked && !given.integrator && *asked != spec->integrator) {
        spec->integrator = *asked;
        notes.push_back(absl::StrCat(scene.integrator_source, ": --integrator ",
                                     std::string(IntegratorName(spec->integrator))));
    }
    // The integrator's own parameters apply only to the integrator they were written for.
    const bool scene_integrator = asked && *asked == spec->integrator;
    if (scene_integrator && scene.max_depth > 0 && !given.max_depth &&
        spec->max_depth != scene.max_depth) {
        spec->max_depth = std::min(scene.max_depth, kMaxDepthSetting);
        notes.push_back(absl::StrCat(scene.integrator_source, ": --max-depth ", spec->max_depth));
    }
    if (scene_integrator && spec->integrator == Integrator::kSppm) {
        if (scene.iterations > 0 && !budget_given) {
            spec->epoch_budget = std::min(scene.iterations, kMaxEpochBudget);
            notes.push_back(
                absl::StrCat(scene.integrator_source, ": --epochs ", spec->epoch_budget));
        }
        if (scene.photons_per_iteration > 0 && !given.layout) {
            // The layout's batches, fewer where the epoch has fewer photons; photons rounded up
            // to a whole number per batch.
            const uint64_t batches = std::min<uint64_t>(spec->layout.batches_per_epoch > 0
                                                            ? spec->layout.batches_per_epoch
                                                            : kDefaultBatchesPerEpoch,
                                                        scene.photons_per_iteration);
            const uint64_t per_batch = std::min<uint64_t>(
                (scene.photons_per_iteration + batches - 1) / batches, kMaxPhotonsPerBatch);
            spec->layout.batches_per_epoch = static_cast<uint32_t>(batches);
            spec->layout.photons_per_batch = static_cast<uint32_t>(per_batch);
            notes.push_back(absl::StrCat(scene.integrator_source, ": --batches-per-epoch ", batches,
                                         " --photons-per-batch ", per_batch));
        }
        if (!given.samples_per_pixel && spec->samples_per_pixel != 1) {
            // pbrt's sppm takes one camera sample a pixel per iteration.
            spec->samples_per_pixel = 1;
            notes.push_back(absl::StrCat(scene.integrator_source, ": --spp 1"));
        }
    }
    if (scene.pixel_samples > 0 && !GathersAtHitPoints(spec->integrator)) {
        uint64_t epochs = spec->epoch_budget;
        if (!budget_given) {
            epochs = std::min<uint64_t>(kDefaultEpochs, scene.pixel_samples);
            spec->epoch_budget = epochs;
            notes.push_back(absl::StrCat(scene.sampler_source, ": --epochs ", epochs));
        }
        if (epochs == 0) epochs = kDefaultEpochs;  // a time or error budget
        if (!given.samples_per_pixel) {
            const uint64_t spp = (uint64_t(scene.pixel_samples) + epochs - 1) / epochs;
            spec->samples_per_pixel = static_cast<int>(std::clamp<uint64_t>(spp, 1, 1024));
            notes.push_back(
                absl::StrCat(scene.sampler_source, ": --spp ", spec->samples_per_pixel));
        }
    }
    ApplyDefaultBudget(spec);
    return notes;
}

void ApplyDefaultBudget(JobSpec* spec) {
    if (HasBudget(*spec)) return;
    if (GathersAtHitPoints(spec->integrator))
        spec->photon_budget = 20'000'000;
    else
        spec->epoch_budget = kDefaultEpochs;
}

}  // namespace pf
