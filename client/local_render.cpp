// The embedded render loop.
#include "client/local_render.h"

#include <spdlog/spdlog.h>
#include <tbb/task_arena.h>

#include <chrono>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/ppm/camera_pass.h"
#include "core/ppm/job_spec.h"
#include "core/scene/emitters.h"
#include "core/scene/gltf_loader.h"
#include "worker/backends/cpu_embree/cpu_backend.h"
#include "worker/backends/cpu_embree/embree_tracer.h"

namespace pf {

absl::StatusOr<RenderOutcome> RenderLocally(const RenderSettings& settings, const EpochCallback& on_epoch) {
    const JobSpec& spec = settings.job;
    if (absl::Status status = CheckJobSpec(spec); !status.ok()) return status;
    absl::StatusOr<Scene> scene = LoadGltf(settings.scene_path);
    if (!scene.ok()) return scene.status();
    const Emitters emitters(*scene);
    if (!emitters.HasPower()) return absl::InvalidArgumentError(absl::StrCat(settings.scene_path, ": lights emit no power"));
    const absl::StatusOr<CameraPassSettings> film = FilmFor(spec, scene->camera);
    if (!film.ok()) return film.status();
    absl::StatusOr<std::unique_ptr<embree::EmbreeTracer>> tracer = embree::EmbreeTracer::Create(*scene);
    if (!tracer.ok()) return tracer.status();

    tbb::task_arena arena(settings.threads > 0 ? settings.threads : tbb::this_task_arena::max_concurrency());
    RenderOutcome outcome;
    absl::Status status;
    arena.execute([&] {
        const auto start = std::chrono::steady_clock::now();
        auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
        CameraPassResult camera_pass = RunCameraPass(*scene, **tracer, *film);
        outcome.camera_pass_seconds = elapsed();
        outcome.hit_points = camera_pass.hit_points.size();
        const EstimateSettings estimate_settings = EstimateFor(spec, camera_pass, *scene, settings.scene_path);
        outcome.initial_radius = estimate_settings.initial_radius;
        spdlog::info("camera pass: {} hit points in {:.2f} s, initial radius {:.4g}", outcome.hit_points,
                     outcome.camera_pass_seconds, outcome.initial_radius);
        ProgressiveEstimate estimate(std::move(camera_pass), estimate_settings);

        embree::CpuBackend backend(**tracer);
        status = backend.BeginJob({&*scene, &emitters, estimate.HitPoints(), spec.seed});
        RenderProgress& progress = outcome.progress;
        while (status.ok() && progress.fraction < 1.0 && !(settings.stop != nullptr && settings.stop->load())) {
            backend.BeginEpoch(estimate.SearchRadiusSq());
            const std::vector<BatchResult> results = backend.RunBatches(estimate.EpochBatches());
            estimate.MergeEpoch(results);
            for (const BatchResult& result : results) progress.segments += result.segments_traced;
            progress.epochs = estimate.Epoch();
            progress.photons = estimate.PhotonsEmitted();
            progress.seconds = elapsed();
            progress.fraction = BudgetFraction(spec, progress.photons, progress.seconds);
            if (on_epoch) on_epoch(progress, estimate);
        }
        outcome.image = estimate.Resolve();
    });
    if (!status.ok()) return status;
    return outcome;
}

}  // namespace pf
