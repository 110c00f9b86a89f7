// `photonfarm render SCENE --out FILE.exr ...`: flags, signal handling, snapshots, outputs.
#include "client/render_command.h"

#include <spdlog/spdlog.h>

#include <atomic>
#include <csignal>
#include <filesystem>
#include <memory>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "client/convergence_report.h"
#include "client/job_options.h"
#include "client/output_files.h"
#include "client/progress_display.h"
#include "core/film/exr_io.h"
#include "core/job/integrator.h"
#include "core/util/command_line.h"
#include "embedded/local_render.h"

namespace pf {
namespace {

std::atomic<bool> g_stop_requested{false};

void OnStopSignal(int) {
    g_stop_requested.store(true);
    std::signal(SIGINT, SIG_DFL);  // a second Ctrl-C ends the process at once
}

struct RenderOptions {
    RenderSettings settings;
    std::string out, png;
    double snapshot_every = 0;
    std::string snapshot_dir;
    std::string reference_path, report_dir;
    float exposure = 0;
    bool plaintext = false;  // lets --web-listen take a non-loopback address
};

// 127.0.0.0/8, ::1 and localhost: where a plain-text, token-less dashboard may listen.
bool IsLoopback(const std::string& address) {
    const std::string host = address.substr(0, address.rfind(':'));
    return host.starts_with("127.") || host == "[::1]" || host == "localhost";
}

ImageMetadata Metadata(const RenderOptions& options, const RenderOutcome& outcome) {
    const RenderSettings& s = options.settings;
    const JobSpec& job = outcome.job;
    return {{"photonfarm:scene", s.scene_path},
            {"photonfarm:photons", absl::StrCat(outcome.progress.photons)},
            {"photonfarm:epochs", absl::StrCat(outcome.progress.epochs)},
            {"photonfarm:seconds", absl::StrFormat("%.3f", outcome.progress.seconds)},
            {"photonfarm:estimated_error",
             outcome.progress.estimated_error
                 ? absl::StrFormat("%.4g", *outcome.progress.estimated_error)
                 : "unknown"},
            {"photonfarm:nonfinite_discarded", absl::StrCat(outcome.progress.nonfinite_discarded)},
            {"photonfarm:seed", absl::StrCat(job.seed)},
            {"photonfarm:photon_stream", absl::StrCat(job.photon_stream)},
            {"photonfarm:alpha", job.alpha == 0 ? "balanced" : absl::StrFormat("%.17g", job.alpha)},
            {"photonfarm:initial_radius", absl::StrFormat("%.9g", outcome.initial_radius)},
            {"photonfarm:scene_features", outcome.scene_features},
            {"photonfarm:integrator", std::string(IntegratorName(job.integrator))},
            {"photonfarm:photon_tracing", std::string(PhotonTracingName(job.photon_tracing))},
            {"photonfarm:camera_samples", absl::StrCat(outcome.progress.camera_samples)},
            {"photonfarm:peak_memory_bytes", absl::StrCat(outcome.peak_memory_bytes)},
            {"photonfarm:backend", s.backend},
            {"photonfarm:spp", absl::StrCat(job.samples_per_pixel)},
            {"photonfarm:photons_per_batch", absl::StrCat(job.layout.photons_per_batch)},
            {"photonfarm:batches_per_epoch", absl::StrCat(job.layout.batches_per_epoch)},
            {"photonfarm:first_epoch_photons", absl::StrCat(job.layout.first_epoch_photons)},
            {"photonfarm:max_depth", absl::StrCat(job.max_depth)}};
}

int RunRender(const RenderOptions& options) {
    RenderSettings settings = options.settings;
    absl::Status prepared = PrepareOutputs(options.out, options.png, options.snapshot_dir);
    if (prepared.ok() && !options.report_dir.empty())
        prepared = PrepareReportDir(options.report_dir);
    if (prepared.ok() && !options.reference_path.empty()) {
        absl::StatusOr<Image> reference = ReadExr(options.reference_path);
        if (reference.ok())
            settings.reference = std::make_shared<const Image>(std::move(*reference));
        else
            prepared = reference.status();
    }
    if (prepared.ok() && !settings.web_listen.empty() && !options.plaintext &&
        !IsLoopback(settings.web_listen))
        prepared = absl::InvalidArgumentError(absl::StrCat(
            "--web-listen: ", settings.web_listen,
            " is not a loopback address; the embedded dashboard is plain HTTP with no login, so "
            "add --plaintext to serve it there (or run a coordinator with TLS and tokens)"));
    if (!prepared.ok()) {
        spdlog::error("{}", std::string(prepared.message()));
        return 1;
    }
    g_stop_requested = false;
    std::signal(SIGINT, OnStopSignal);
    std::signal(SIGTERM, OnStopSignal);
    settings.stop = &g_stop_requested;

    ProgressDisplay display;
    double next_snapshot = options.snapshot_every;
    int snapshot_count = 0;
    absl::Status snapshot_status;
    const auto on_epoch = [&](const RenderProgress& progress, const Job& job) {
        display.Update(progress);
        if (options.snapshot_every <= 0 || progress.seconds < next_snapshot ||
            !snapshot_status.ok())
            return;
        next_snapshot = progress.seconds + options.snapshot_every;
        const std::string path =
            absl::StrFormat("%s/snapshot-%04d.exr", options.snapshot_dir, ++snapshot_count);
        snapshot_status =
            WriteExr(path, *job.CurrentImage(),
                     {{"photonfarm:photons", absl::StrCat(progress.photons)},
                      {"photonfarm:seconds", absl::StrFormat("%.3f", progress.seconds)}});
    };
    const absl::StatusOr<RenderOutcome> outcome = RenderLocally(settings, on_epoch);
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    if (!outcome.ok()) {
        spdlog::error("{}", std::string(outcome.status().message()));
        return 1;
    }
    display.Finish(*outcome);
    if (outcome->progress.nonfinite_discarded > 0)
        spdlog::warn(
            "{} photon paths or direct-light samples became NaN or Inf and were left out; "
            "please report the scene (docs/numerics.md)",
            outcome->progress.nonfinite_discarded);
    if (g_stop_requested) spdlog::warn("stopped early by a signal; writing what was rendered");
    if (!snapshot_status.ok()) spdlog::error("{}", std::string(snapshot_status.message()));
    if (absl::Status status = WriteImageFiles(outcome->image, Metadata(options, *outcome),
                                              options.out, options.png, options.exposure);
        !status.ok()) {
        spdlog::error("{}", std::string(status.message()));
        return 1;
    }
    if (!options.report_dir.empty()) {
        const std::string title = std::filesystem::path(settings.scene_path).filename().string();
        if (absl::Status status =
                WriteConvergenceReport(options.report_dir, title, outcome->convergence);
            !status.ok()) {
            spdlog::error("{}", std::string(status.message()));
            return 1;
        }
    }
    return snapshot_status.ok() ? 0 : 1;
}

}  // namespace

void AddRenderCommand(CLI::App& app, int* exit_code) {
    auto options = std::make_shared<RenderOptions>();
    RenderSettings& s = options->settings;
    CLI::App* render = app.add_subcommand("render", "Render a scene on this machine (no server)");
    render->add_option("scene", s.scene_path, "Scene file (.gltf, .glb or .pbrt)")
        ->required()
        ->check(CLI::ExistingFile);
    render
        ->add_option(
            "--scene-root", s.scene_root,
            "The folder that holds the scene and every file it references, where they lie beside "
            "its own folder (../textures/...): nothing outside it is read (default: the "
            "scene's folder)")
        ->check(CLI::ExistingDirectory);
    render->add_option("--out", options->out, "Output image: float RGB OpenEXR with metadata")
        ->required();
    render->add_option("--png", options->png, "Also write a tone-mapped sRGB PNG");
    render->add_option("--exposure", options->exposure, "PNG exposure in stops")
        ->default_val(0.0f)
        ->check(FiniteNumber());
    AddJobOptions(render, &s.job);
    render->add_option("--threads", s.threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(1, 4096));
    render
        ->add_option("--backend", s.backend,
                     "Backend of the batches: cpu (Embree) or vulkan (compute on a GPU)")
        ->default_val(s.backend)
        ->check(CLI::IsMember(BackendNames()));
    auto* every = render
                      ->add_option("--snapshot-every", options->snapshot_every,
                                   "Write a snapshot EXR every SECONDS")
                      ->check(FinitePositive());
    auto* dir = render->add_option("--snapshot-dir", options->snapshot_dir,
                                   "Directory for snapshot-NNNN.exr");
    every->needs(dir);
    dir->needs(every);
    render
        ->add_option("--web-listen", s.web_listen,
                     "Serve the browser dashboard at HOST:PORT while rendering (plain HTTP; a "
                     "loopback address unless --plaintext)")
        ->check(HostAndPort(0));
    render->add_flag("--plaintext", options->plaintext,
                     "Let --web-listen serve plain HTTP on a non-loopback address");
    AddReferenceOption(render, &options->reference_path);
    AddReportOption(render, &options->report_dir);
    render->callback([options, render, exit_code] {
        options->settings.given = GivenSettingsOf(*render);
        *exit_code = RunRender(*options);
    });
}

}  // namespace pf
