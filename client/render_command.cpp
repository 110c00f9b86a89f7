// `photonfarm render SCENE --out FILE.exr ...`: flags, signal handling, snapshots, outputs.
#include "client/render_command.h"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <filesystem>
#include <memory>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "client/local_render.h"
#include "client/progress_display.h"
#include "core/film/exr_io.h"
#include "core/film/png_writer.h"

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
    float exposure = 0;
};

ImageMetadata Metadata(const RenderOptions& options, const RenderOutcome& outcome) {
    const RenderSettings& s = options.settings;
    return {{"photonfarm:scene", s.scene_path},
            {"photonfarm:photons", absl::StrCat(outcome.progress.photons)},
            {"photonfarm:epochs", absl::StrCat(outcome.progress.epochs)},
            {"photonfarm:seconds", absl::StrFormat("%.3f", outcome.progress.seconds)},
            {"photonfarm:seed", absl::StrCat(s.job.seed)},
            {"photonfarm:alpha", absl::StrFormat("%.17g", s.job.alpha)},
            {"photonfarm:initial_radius", absl::StrFormat("%.9g", outcome.initial_radius)},
            {"photonfarm:spp", absl::StrCat(s.job.samples_per_pixel)},
            {"photonfarm:photons_per_batch", absl::StrCat(s.job.layout.photons_per_batch)},
            {"photonfarm:batches_per_epoch", absl::StrCat(s.job.layout.batches_per_epoch)}};
}

absl::Status WriteOutputs(const RenderOptions& options, const RenderOutcome& outcome) {
    if (absl::Status status = WriteExr(options.out, outcome.image, Metadata(options, outcome)); !status.ok())
        return status;
    spdlog::info("wrote {}", options.out);
    if (!options.png.empty()) {
        if (absl::Status status = WritePng(options.png, outcome.image, options.exposure); !status.ok()) return status;
        spdlog::info("wrote {}", options.png);
    }
    return absl::OkStatus();
}

// Fails before any rendering if an output could not be written, so no work is lost to a typo.
absl::Status CheckWritable(const std::string& path) {
    if (path.empty()) return absl::OkStatus();
    const std::filesystem::path parent = std::filesystem::absolute(path).parent_path();
    if (!std::filesystem::is_directory(parent) || access(parent.c_str(), W_OK) != 0)
        return absl::InvalidArgumentError(absl::StrCat(path, ": cannot write here (", parent.string(),
                                                       " is not a writable directory)"));
    return absl::OkStatus();
}

int RunRender(const RenderOptions& options) {
    for (const std::string* path : {&options.out, &options.png}) {
        if (absl::Status status = CheckWritable(*path); !status.ok()) {
            spdlog::error("{}", std::string(status.message()));
            return 1;
        }
    }
    if (options.snapshot_every > 0) {
        std::error_code error;
        std::filesystem::create_directories(options.snapshot_dir, error);
        if (error) {
            spdlog::error("{}: cannot create snapshot directory: {}", options.snapshot_dir, error.message());
            return 1;
        }
    }
    g_stop_requested = false;
    std::signal(SIGINT, OnStopSignal);
    std::signal(SIGTERM, OnStopSignal);
    RenderSettings settings = options.settings;
    settings.stop = &g_stop_requested;

    ProgressDisplay display;
    double next_snapshot = options.snapshot_every;
    int snapshot_count = 0;
    absl::Status snapshot_status;
    const auto on_epoch = [&](const RenderProgress& progress, const Job& job) {
        display.Update(progress);
        if (options.snapshot_every <= 0 || progress.seconds < next_snapshot || !snapshot_status.ok()) return;
        next_snapshot = progress.seconds + options.snapshot_every;
        const std::string path = absl::StrFormat("%s/snapshot-%04d.exr", options.snapshot_dir, ++snapshot_count);
        snapshot_status = WriteExr(path, *job.CurrentImage(),
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
    if (g_stop_requested) spdlog::warn("stopped early by a signal; writing what was rendered");
    if (!snapshot_status.ok()) spdlog::error("{}", std::string(snapshot_status.message()));
    if (absl::Status status = WriteOutputs(options, *outcome); !status.ok()) {
        spdlog::error("{}", std::string(status.message()));
        return 1;
    }
    return snapshot_status.ok() ? 0 : 1;
}

}  // namespace

void AddRenderCommand(CLI::App& app, int* exit_code) {
    auto options = std::make_shared<RenderOptions>();
    RenderSettings& s = options->settings;
    CLI::App* render = app.add_subcommand("render", "Render a scene on this machine (no server)");
    const auto count = CLI::AsNumberWithUnit(std::map<std::string, uint64_t>{{"k", 1000}, {"m", 1000000}, {"g", 1000000000}, {"t", 1000000000000}},
                                             CLI::AsNumberWithUnit::CASE_INSENSITIVE, "COUNT");
    render->add_option("scene", s.scene_path, "Scene file (.gltf or .glb)")->required()->check(CLI::ExistingFile);
    render->add_option("--out", options->out, "Output image: float RGB OpenEXR with metadata")->required();
    render->add_option("--png", options->png, "Also write a tone-mapped sRGB PNG");
    render->add_option("--exposure", options->exposure, "PNG exposure in stops")->default_val(0.0f);
    auto* photons = render->add_option("--photons", s.job.photon_budget, "Photon budget, e.g. 20M (finishes the epoch that reaches it)")
                        ->transform(count);
    render->add_option("--seconds", s.job.seconds_budget, "Time budget in seconds (finishes the epoch that reaches it)")
        ->check(CLI::PositiveNumber)->excludes(photons);
    render->add_option("--photons-per-batch", s.job.layout.photons_per_batch, "Photon paths per batch, the unit of work")
        ->default_val(s.job.layout.photons_per_batch)->check(CLI::Range(1u, 1u << 26));
    render->add_option("--batches-per-epoch", s.job.layout.batches_per_epoch, "Batches per epoch; radii shrink once per epoch")
        ->default_val(s.job.layout.batches_per_epoch)->check(CLI::Range(1u, 1u << 20));
    render->add_option("--alpha", s.job.alpha, "Radius reduction ratio alpha in (0, 1]")->default_val(s.job.alpha)->check(CLI::Range(1e-9, 1.0));
    render->add_option("--radius", s.job.initial_radius, "Initial search radius R0, world units (default: one pixel footprint)")
        ->check(CLI::PositiveNumber);
    render->add_option("--spp", s.job.samples_per_pixel, "Hit points (camera paths) per pixel")->default_val(s.job.samples_per_pixel)
        ->check(CLI::Range(1, 1024));
    render->add_option("--threads", s.threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 4096));
    render->add_option("--seed", s.job.seed, "Random seed; the same seed and batch layout give the same image")->default_val(s.job.seed);
    render->add_option("--width", s.job.width, "Image width in pixels (default 512)")->check(CLI::Range(1, 32768));
    render->add_option("--height", s.job.height, "Image height in pixels (default: width / camera aspect)")->check(CLI::Range(1, 32768));
    auto* every = render->add_option("--snapshot-every", options->snapshot_every, "Write a snapshot EXR every SECONDS")
                      ->check(CLI::PositiveNumber);
    auto* dir = render->add_option("--snapshot-dir", options->snapshot_dir, "Directory for snapshot-NNNN.exr");
    every->needs(dir);
    dir->needs(every);
    render->callback([options, exit_code] {
        if (options->settings.job.photon_budget == 0 && options->settings.job.seconds_budget == 0)
            options->settings.job.photon_budget = 20'000'000;
        *exit_code = RunRender(*options);
    });
}

}  // namespace pf
