// The embedded render loop.
#include "client/local_render.h"

#include <spdlog/spdlog.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/ppm/camera_pass.h"
#include "core/scene/emitters.h"
#include "core/scene/gltf_loader.h"
#include "worker/backends/cpu_embree/cpu_backend.h"
#include "worker/backends/cpu_embree/embree_tracer.h"

namespace pf {
namespace {

// Hit points are indexed with 32 bits and cost about this much memory each across the
// estimate, the grid and one tally accumulator per thread: 2^26 of them take ~15 GB.
constexpr uint64_t kMaxHitPoints = uint64_t{1} << 26;
constexpr uint64_t kBytesPerHitPoint = 220;

absl::Status CheckSettings(const RenderSettings& s) {
    if (s.width < 0 || s.height < 0 || s.width > 32768 || s.height > 32768)
        return absl::InvalidArgumentError("--width/--height must lie in [1, 32768]");
    if (s.samples_per_pixel < 1 || s.samples_per_pixel > 1024) return absl::InvalidArgumentError("--spp must lie in [1, 1024]");
    if (!(s.alpha > 0 && s.alpha <= 1)) return absl::InvalidArgumentError("--alpha must lie in (0, 1]");
    if (!(s.initial_radius >= 0 && std::isfinite(s.initial_radius)))
        return absl::InvalidArgumentError("--radius must be positive and finite");
    if (s.layout.photons_per_batch < 1 || s.layout.batches_per_epoch < 1)
        return absl::InvalidArgumentError("--photons-per-batch and --batches-per-epoch must be at least 1");
    if (!(s.seconds_budget >= 0 && std::isfinite(s.seconds_budget)))
        return absl::InvalidArgumentError("--seconds must be positive");
    if (s.photon_budget == 0 && s.seconds_budget == 0)
        return absl::InvalidArgumentError("give a budget: --photons N or --seconds S");
    return absl::OkStatus();
}

// Film size: what was asked, else 512 wide with the camera's aspect ratio.
void ResolveFilmSize(const Camera& camera, int* width, int* height) {
    const double aspect = camera.aspect_ratio > 0 ? camera.aspect_ratio : 1.0;
    if (*width == 0 && *height == 0) *width = 512;
    if (*width == 0) *width = std::max(1, static_cast<int>(std::lround(*height * aspect)));
    if (*height == 0) *height = std::max(1, static_cast<int>(std::lround(*width / aspect)));
}

}  // namespace

absl::StatusOr<RenderOutcome> RenderLocally(const RenderSettings& settings, const EpochCallback& on_epoch) {
    if (absl::Status status = CheckSettings(settings); !status.ok()) return status;
    absl::StatusOr<Scene> scene = LoadGltf(settings.scene_path);
    if (!scene.ok()) return scene.status();
    const Emitters emitters(*scene);
    if (!emitters.HasPower()) return absl::InvalidArgumentError(absl::StrCat(settings.scene_path, ": lights emit no power"));
    absl::StatusOr<std::unique_ptr<embree::EmbreeTracer>> tracer = embree::EmbreeTracer::Create(*scene);
    if (!tracer.ok()) return tracer.status();

    const int threads = settings.threads > 0 ? settings.threads : tbb::this_task_arena::max_concurrency();
    tbb::task_arena arena(threads);
    RenderOutcome outcome;
    absl::Status status;
    arena.execute([&] {
        const auto start = std::chrono::steady_clock::now();
        auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
        CameraPassSettings camera{settings.width, settings.height, settings.samples_per_pixel, settings.seed};
        ResolveFilmSize(scene->camera, &camera.width, &camera.height);
        const uint64_t most_hit_points = uint64_t(camera.width) * uint64_t(camera.height) * uint64_t(camera.samples_per_pixel);
        if (most_hit_points > kMaxHitPoints) {
            status = absl::ResourceExhaustedError(absl::StrFormat(
                "%dx%d pixels x %d spp = %d hit points exceeds the limit of %d (about %d bytes each)", camera.width,
                camera.height, camera.samples_per_pixel, most_hit_points, kMaxHitPoints, kBytesPerHitPoint));
            return;
        }
        CameraPassResult camera_pass = RunCameraPass(*scene, **tracer, camera);
        outcome.camera_pass_seconds = elapsed();
        outcome.hit_points = camera_pass.hit_points.size();
        EstimateSettings estimate_settings{settings.alpha, settings.initial_radius, settings.samples_per_pixel, settings.layout};
        if (estimate_settings.initial_radius == 0) estimate_settings.initial_radius = DefaultInitialRadius(camera_pass, *scene);
        if (camera_pass.hit_points.empty() || !(estimate_settings.initial_radius > 0)) {
            spdlog::warn("{}: the camera sees no diffuse surface; the image holds emission only", settings.scene_path);
            estimate_settings.initial_radius = std::max(estimate_settings.initial_radius, 1e-3 * scene->bounds.Diagonal());
        }
        outcome.initial_radius = estimate_settings.initial_radius;
        spdlog::info("camera pass: {} hit points in {:.2f} s, initial radius {:.4g}", outcome.hit_points,
                     outcome.camera_pass_seconds, outcome.initial_radius);
        ProgressiveEstimate estimate(std::move(camera_pass), estimate_settings);

        embree::CpuBackend backend(**tracer);
        status = backend.BeginJob({&*scene, &emitters, estimate.HitPoints(), settings.seed});
        if (!status.ok()) return;
        RenderProgress& progress = outcome.progress;
        while (true) {
            const bool photons_done = settings.photon_budget > 0 && progress.photons >= settings.photon_budget;
            const bool time_done = settings.seconds_budget > 0 && progress.seconds >= settings.seconds_budget;
            const bool stopped = settings.stop != nullptr && settings.stop->load();
            if (photons_done || time_done || stopped) break;
            backend.BeginEpoch(estimate.SearchRadiusSq());
            const std::vector<BatchResult> results = backend.RunBatches(estimate.EpochBatches());
            estimate.MergeEpoch(results);
            for (const BatchResult& result : results) progress.segments += result.segments_traced;
            progress.epochs = estimate.Epoch();
            progress.photons = estimate.PhotonsEmitted();
            progress.seconds = elapsed();
            progress.fraction = std::max(
                settings.photon_budget > 0 ? double(progress.photons) / double(settings.photon_budget) : 0.0,
                settings.seconds_budget > 0 ? progress.seconds / settings.seconds_budget : 0.0);
            progress.fraction = std::min(progress.fraction, 1.0);
            if (on_epoch) on_epoch(progress, estimate);
        }
        outcome.image = estimate.Resolve();
    });
    if (!status.ok()) return status;
    return outcome;
}

}  // namespace pf
