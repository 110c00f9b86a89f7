// The embedded render: one coordinator, one in-process worker.
#include "embedded/local_render.h"

#include <spdlog/spdlog.h>
#include <sys/resource.h>
#include <tbb/task_arena.h>

#include <cmath>

#include "absl/strings/str_cat.h"
#include "core/job/scene_settings.h"
#include "core/scene/scene_bundle.h"
#include "core/scene_io/scene_loader.h"
#include "server/coordinator.h"
#include "server/dashboard_server.h"
#include "server/in_process_source.h"
#include "worker/backend_factory.h"
#include "worker/worker_loop.h"

namespace pf {

absl::StatusOr<RenderOutcome> RenderLocally(const RenderSettings& settings,
                                            const EpochCallback& on_epoch) {
    JobSpec spec = settings.job;
    auto check = [&](const JobSpec& job) -> absl::Status {
        return CheckJobSpec(job, SettingNames::kFlags);
    };
    {  // the flags alone, before any work
        JobSpec flags = spec;
        ApplyDefaultBudget(&flags);
        if (absl::Status status = check(flags); !status.ok()) return status;
    }
    SceneRenderSettings scene_settings;
    absl::StatusOr<SceneBundle> bundle =
        PackSceneBundle(settings.scene_path, &scene_settings, settings.scene_root);
    if (!bundle.ok()) return bundle.status();
    const std::vector<std::string> notes =
        ApplySceneSettings(scene_settings, settings.given, &spec);
    if (absl::Status status = check(spec); !status.ok()) return status;
    for (const std::string& note : notes) spdlog::info("{}", note);
    // The backend's device before any rendering: without one, say so.
    const absl::StatusOr<BackendDevice> device = OpenBackendDevice(settings.backend);
    if (!device.ok()) return device.status();
    if (absl::Status status = BundleEnvironment(&spec.environment, &*bundle); !status.ok())
        return status;

    CoordinatorOptions options;
    options.setting_names = SettingNames::kFlags;
    Coordinator coordinator(options);
    const AccessControl open_access(ServerSecurity{.plaintext = true});
    std::unique_ptr<DashboardServer> dashboard;  // destroyed before the coordinator
    if (!settings.web_listen.empty()) {
        absl::StatusOr<std::unique_ptr<DashboardServer>> started = DashboardServer::Start(
            settings.web_listen, ServerSecurity{.plaintext = true}, coordinator, open_access);
        if (!started.ok()) return started.status();
        dashboard = std::move(*started);
        spdlog::info("watch the render at {}", dashboard->Url());
    }
    tbb::task_arena arena(settings.threads > 0 ? settings.threads
                                               : tbb::this_task_arena::max_concurrency());
    absl::StatusOr<RenderOutcome> outcome = RenderOutcome{};
    outcome->job = spec;
    arena.execute([&] {
        absl::StatusOr<JobProgress> submitted = coordinator.Submit(
            {settings.scene_path, "this process", std::move(*bundle), spec, 0, settings.reference});
        if (!submitted.ok()) {
            outcome = submitted.status();
            return;
        }
        outcome->camera_pass_seconds = submitted->elapsed_seconds;
        outcome->hit_points = submitted->hit_points;
        outcome->initial_radius = submitted->initial_radius;
        outcome->scene_features = submitted->scene_features;
        const std::shared_ptr<Job> job = *coordinator.FindJob(submitted->job_id);
        outcome->job = job->Spec();  // the film size and layout resolved

        // The worker leases a whole epoch at a time: its batches' chunks run in parallel on
        // this arena.
        InProcessSource source(coordinator,
                               {device->description, static_cast<uint32_t>(arena.max_concurrency()),
                                std::string(kPhotonfarmVersion), ""},
                               0.0);
        const BatchLayout& layout = job->Spec().layout;  // resolved
        const uint64_t epoch_chunks =
            uint64_t{layout.batches_per_epoch} *
            ChunkCount(MakeBatchSpec(layout, layout.GrowingEpochs(), 0, 0));
        WorkerLoop worker(source, settings.backend,
                          static_cast<uint32_t>(std::min<uint64_t>(epoch_chunks, UINT32_MAX)));
        uint64_t version = job->Version();
        RenderProgress& progress = outcome->progress;
        while (job->Progress(Clock::now()).state == JobState::kRunning) {
            if (settings.stop != nullptr && settings.stop->load()) {
                (void)coordinator.Cancel(job->Id(), "stopped by a signal");
                break;
            }
            if (absl::StatusOr<size_t> ran = worker.Step(); !ran.ok()) {
                outcome = ran.status();
                return;
            }
            if (job->Version() == version) continue;
            version = job->Version();
            const JobProgress state = job->Progress(Clock::now());
            progress.epochs = state.epochs;
            progress.photons = state.photons;
            progress.integrator = state.integrator;
            progress.camera_samples = state.camera_samples;
            progress.segments = worker.Stats().segments;
            progress.seconds = state.elapsed_seconds;
            progress.estimated_error = state.estimated_error;
            progress.nonfinite_discarded = state.nonfinite_discarded;
            if (state.measured_error)
                progress.measured_error = std::sqrt(state.measured_error->rel_mse);
            progress.fraction = state.state == JobState::kDone ? 1.0 : state.budget_fraction;
            if (on_epoch) on_epoch(progress, *job);
        }
        outcome->image = *job->CurrentImage();
        outcome->convergence = job->Convergence();
        outcome->warnings = job->Progress(Clock::now()).warnings;
    });
    if (outcome.ok()) {
        rusage usage{};
        if (getrusage(RUSAGE_SELF, &usage) == 0)
            outcome->peak_memory_bytes = uint64_t(usage.ru_maxrss) * 1024;
    }
    return outcome;
}

}  // namespace pf
