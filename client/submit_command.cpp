// Submitting and watching farm jobs: progress, snapshots, the final image.
#include "client/submit_command.h"

#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "client/convergence_report.h"
#include "client/farm_client.h"
#include "client/job_options.h"
#include "client/output_files.h"
#include "client/progress_display.h"
#include "core/film/exr_io.h"
#include "core/scene/scene_bundle.h"
#include "core/scene_io/scene_loader.h"
#include "core/util/command_line.h"
#include "wire/json.h"
#include "wire/proto_convert.h"

namespace pf {
namespace {

namespace v1 = photonfarm::v1;

struct WatchOptions {
    ServerFlags server;
    std::string job_id;
    std::string out, png, snapshot_dir, report_dir;
    double interval = 1.0;
    float exposure = 0;
    bool json = false;
};

void AddWatchOptions(CLI::App* command, WatchOptions* options) {
    AddServerOption(command, &options->server);
    command->add_option("--out", options->out, "Write the final image here (float RGB OpenEXR)");
    command->add_option("--png", options->png, "Also write the final image as a tone-mapped PNG");
    command->add_option("--exposure", options->exposure, "PNG exposure in stops")
        ->default_val(0.0f)
        ->check(FiniteNumber());
    command->add_option("--snapshot-dir", options->snapshot_dir,
                        "Write every snapshot here (snapshot-NNNN.exr and .png)");
    command->add_option("--interval", options->interval, "Seconds between snapshots")
        ->default_val(1.0)
        ->check(FiniteRange(0.0, 3600.0));
    command->add_flag("--json", options->json,
                      "One JSON status per snapshot on stdout, for scripts");
    AddReportOption(command, &options->report_dir);
}

RenderProgress ProgressOf(const v1::JobStatus& status) {
    RenderProgress progress;
    progress.epochs = status.epochs();
    progress.photons = status.photons();
    if (absl::StatusOr<Integrator> integrator =
            IntegratorFromProto(status.integrator(), "integrator");
        integrator.ok())
        progress.integrator = *integrator;
    progress.camera_samples = status.camera_samples();
    progress.seconds = status.elapsed_seconds();
    progress.fraction = status.budget_fraction();
    progress.workers = status.workers_active();
    if (status.has_estimated_error()) progress.estimated_error = status.estimated_error();
    if (status.has_reference_error())
        progress.measured_error = std::sqrt(status.reference_error().rel_mse());
    progress.nonfinite_discarded = status.nonfinite_discarded();
    return progress;
}

}  // namespace

ImageMetadata JobMetadata(const photonfarm::v1::JobStatus& status) {
    return {{"photonfarm:job", status.job_id()},
            {"photonfarm:scene", status.name()},
            {"photonfarm:photons", absl::StrCat(status.photons())},
            {"photonfarm:epochs", absl::StrCat(status.epochs())},
            {"photonfarm:seconds", absl::StrFormat("%.3f", status.elapsed_seconds())},
            {"photonfarm:estimated_error", status.has_estimated_error()
                                               ? absl::StrFormat("%.4g", status.estimated_error())
                                               : "unknown"},
            {"photonfarm:nonfinite_discarded", absl::StrCat(status.nonfinite_discarded())},
            {"photonfarm:scene_features", status.scene_features()},
            {"photonfarm:camera_samples", absl::StrCat(status.camera_samples())},
            {"photonfarm:integrator", std::string(IntegratorName(ProgressOf(status).integrator))}};
}

absl::Status WriteJobReport(FarmClient& client, const std::string& job_id, const std::string& dir) {
    absl::StatusOr<JobConvergence> convergence = client.Convergence(job_id);
    if (!convergence.ok()) return convergence.status();
    return WriteConvergenceReport(dir, convergence->name, convergence->points);
}

namespace {

// Follows a job to its end, writing snapshots and the final image. Exit code: 0 when the
// job is done, 1 otherwise (cancelled, failed, or the coordinator lost); whatever image
// arrived is written either way.
int Follow(FarmClient& client, const WatchOptions& options) {
    absl::Status prepared = PrepareOutputs(options.out, options.png, options.snapshot_dir);
    if (prepared.ok() && !options.report_dir.empty())
        prepared = PrepareReportDir(options.report_dir);
    if (!prepared.ok()) {
        spdlog::error("{}", std::string(prepared.message()));
        return 1;
    }
    ProgressDisplay display;
    Image image;
    v1::JobStatus last;
    int snapshots = 0;
    absl::Status write_status;
    const bool images =
        !options.out.empty() || !options.png.empty() || !options.snapshot_dir.empty();
    int first_warnings = -1;
    absl::StatusOr<v1::Snapshot> outcome =
        client.Watch(options.job_id, options.interval, images, [&](const v1::Snapshot& snapshot) {
            last = snapshot.status();
            if (first_warnings < 0) first_warnings = last.warnings_size();
            if (options.json) {
                std::printf("%s\n", ToJson(snapshot.status()).c_str());
                std::fflush(stdout);
            } else {
                display.Update(ProgressOf(snapshot.status()));
            }
            if (!snapshot.has_image()) return true;
            absl::StatusOr<Image> decoded = FromProto(snapshot.image());
            if (!decoded.ok()) {
                write_status = decoded.status();
                return true;
            }
            image = std::move(*decoded);
            if (!options.snapshot_dir.empty() && write_status.ok()) {
                const std::string stem =
                    absl::StrFormat("%s/snapshot-%04d", options.snapshot_dir, ++snapshots);
                write_status = WriteImageFiles(image, JobMetadata(snapshot.status()), stem + ".exr",
                                               stem + ".png", options.exposure);
            }
            return true;
        });
    if (!options.json) display.Finish();
    // Warnings that arose while the job ran (those from its submission were shown then).
    if (outcome.ok())
        for (int i = first_warnings; i < last.warnings_size(); ++i)
            spdlog::warn("job {}: {}", last.job_id(), last.warnings(i));
    int exit_code = 0;
    if (!outcome.ok()) {
        spdlog::error("{}", std::string(outcome.status().message()));
        exit_code = 1;
    } else if (last.state() != v1::JOB_STATE_DONE) {
        spdlog::error("job {} {}{}", last.job_id(), StateName(last.state()),
                      last.message().empty() ? "" : absl::StrCat(": ", last.message()));
        exit_code = 1;
    } else if (!options.json) {
        std::fprintf(stderr, "done: job %s, %s photons in %d epochs, %.1f s\n",
                     last.job_id().c_str(), absl::StrCat(last.photons()).c_str(),
                     static_cast<int>(last.epochs()), last.elapsed_seconds());
    }
    if (!write_status.ok()) {
        spdlog::error("{}", std::string(write_status.message()));
        exit_code = 1;
    }
    if (!options.out.empty() && image.width > 0) {
        if (absl::Status status = WriteImageFiles(image, JobMetadata(last), options.out,
                                                  options.png, options.exposure);
            !status.ok()) {
            spdlog::error("{}", std::string(status.message()));
            exit_code = 1;
        }
    }
    if (!options.report_dir.empty()) {
        if (absl::Status status = WriteJobReport(client, options.job_id, options.report_dir);
            !status.ok()) {
            spdlog::error("{}", std::string(status.message()));
            exit_code = 1;
        }
    }
    return exit_code;
}

struct SubmitOptions {
    std::string scene_path;
    std::string scene_root;
    std::string reference_path;
    std::string name;
    JobSpec spec;
    GivenSettings given;  // the settings given as flags, which the scene's do not change
    int priority = 0;
    bool watch = false;
    WatchOptions watch_options;
};

int RunSubmit(SubmitOptions& options) {
    JobSpec flags = options.spec;
    ApplyDefaultBudget(&flags);
    if (absl::Status status = CheckJobSpec(flags, SettingNames::kFlags); !status.ok()) {
        spdlog::error("{}", std::string(status.message()));
        return 2;
    }
    SceneRenderSettings scene_settings;
    absl::StatusOr<SceneBundle> bundle =
        PackSceneBundle(options.scene_path, &scene_settings, options.scene_root);
    if (!bundle.ok()) {
        spdlog::error("{}", std::string(bundle.status().message()));
        return 1;
    }
    const std::vector<std::string> notes =
        ApplySceneSettings(scene_settings, options.given, &options.spec);
    if (absl::Status status = CheckJobSpec(options.spec, SettingNames::kFlags); !status.ok()) {
        spdlog::error("{}", std::string(status.message()));
        return 2;
    }
    for (const std::string& note : notes) spdlog::info("{}", note);
    if (absl::Status status = BundleEnvironment(&options.spec.environment, &*bundle);
        !status.ok()) {
        spdlog::error("{}", std::string(status.message()));
        return 1;
    }
    absl::StatusOr<FarmClient> client = FarmClient::Connect(options.watch_options.server);
    if (!client.ok()) {
        spdlog::error("{}", std::string(client.status().message()));
        return 1;
    }
    v1::SubmitJobRequest request;
    *request.mutable_scene() = ToProto(*bundle);
    *request.mutable_settings() = ToProto(options.spec);
    request.mutable_settings()->set_priority(options.priority);
    request.set_name(options.name);
    if (!options.reference_path.empty()) {
        absl::StatusOr<Image> reference = ReadExr(options.reference_path);
        if (!reference.ok()) {
            spdlog::error("{}", std::string(reference.status().message()));
            return 1;
        }
        *request.mutable_reference() = ToProto(*reference);
    }
    spdlog::info("submitting {} ({} files, {} bytes)", options.scene_path, bundle->files.size(),
                 bundle->TotalBytes());
    absl::StatusOr<v1::JobStatus> status = client->Submit(request);
    if (!status.ok()) {
        spdlog::error("{}", std::string(status.status().message()));
        return 1;
    }
    for (const std::string& warning : status->warnings())
        spdlog::warn("job {}: {}", status->job_id(), warning);
    if (options.watch_options.json) {
        std::printf("%s\n", ToJson(*status).c_str());
        std::fflush(stdout);
    } else {
        // The job id alone on stdout, for scripts: JOB=$(photonfarm submit ...).
        std::printf("%s\n", status->job_id().c_str());
        std::fflush(stdout);
        spdlog::info("job {}: {} hit points", status->job_id(), status->hit_points());
    }
    if (!options.watch) return 0;
    options.watch_options.job_id = status->job_id();
    return Follow(*client, options.watch_options);
}

}  // namespace

void AddSubmitCommand(CLI::App& app, int* exit_code) {
    auto options = std::make_shared<SubmitOptions>();
    CLI::App* submit =
        app.add_subcommand("submit", "Submit a scene to a render farm (prints the job id)");
    submit
        ->add_option("scene", options->scene_path,
                     "Scene file (.gltf, .glb or .pbrt); it and every file it references are sent")
        ->required()
        ->check(CLI::ExistingFile);
    submit
        ->add_option(
            "--scene-root", options->scene_root,
            "The folder that holds the scene and every file it references, where they lie beside "
            "its own folder (../textures/...): nothing outside it is read (default: the "
            "scene's folder)")
        ->check(CLI::ExistingDirectory);
    submit->add_option("--name", options->name,
                       "Name in listings (default: the scene's file name)");
    submit
        ->add_option("--priority", options->priority,
                     "Its share of the workers weighs 2^priority: +1 gets twice the workers of 0")
        ->default_val(0)
        ->check(SignedWholeNumber(-kMaxJobPriority, kMaxJobPriority));
    AddJobOptions(submit, &options->spec);
    AddReferenceOption(submit, &options->reference_path);
    submit->add_flag("--watch", options->watch,
                     "Follow the job to its end: progress, snapshots, final image");
    AddWatchOptions(submit, &options->watch_options);
    submit->callback([options, submit, exit_code] {
        options->given = GivenSettingsOf(*submit);
        const WatchOptions& watch = options->watch_options;
        if (!options->watch && (!watch.out.empty() || !watch.png.empty() ||
                                !watch.snapshot_dir.empty() || !watch.report_dir.empty())) {
            spdlog::error(
                "--out, --png, --snapshot-dir and --report need --watch (or use `photonfarm watch "
                "JOB --out ...` later)");
            *exit_code = 2;
            return;
        }
        *exit_code = RunSubmit(*options);
    });
}

void AddWatchCommand(CLI::App& app, int* exit_code) {
    auto options = std::make_shared<WatchOptions>();
    CLI::App* watch =
        app.add_subcommand("watch", "Follow a farm job: progress, snapshots, final image");
    watch->add_option("job", options->job_id, "Job id (from submit or jobs)")->required();
    AddWatchOptions(watch, options.get());
    watch->callback([options, exit_code] {
        absl::StatusOr<FarmClient> client = FarmClient::Connect(options->server);
        if (!client.ok()) {
            spdlog::error("{}", std::string(client.status().message()));
            *exit_code = 1;
            return;
        }
        *exit_code = Follow(*client, *options);
    });
}

}  // namespace pf
