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

// Hit points cost about this much memory each across the estimate (~140 bytes), the grid (8
// entries of 24 bytes) and one tally accumulator per thread (16 bytes): 2^25 of them (4K at
// 4 hit points per pixel) take ~12 GB.
constexpr uint64_t kMaxHitPoints = uint64_t{1} << 25;
constexpr uint64_t kBytesPerHitPoint = 360;

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

// Film size: what was asked, else 512 wide with the camera's aspect ratio; refused if its hit
// points would not fit.
absl::StatusOr<CameraPassSettings> FilmFor(const RenderSettings& settings, const Camera& camera) {
    CameraPassSettings film{settings.width, settings.height, settings.samples_per_pixel, settings.seed};
    const double aspect = camera.aspect_ratio > 0 ? camera.aspect_ratio : 1.0;
    if (film.width == 0 && film.height == 0) film.width = 512;
    if (film.width == 0) film.width = std::max(1, static_cast<int>(std::lround(film.height * aspect)));
    if (film.height == 0) film.height = std::max(1, static_cast<int>(std::lround(film.width / aspect)));
    const uint64_t most_hit_points = uint64_t(film.width) * uint64_t(film.height) * uint64_t(film.samples_per_pixel);
    if (most_hit_points > kMaxHitPoints)
        return absl::ResourceExhaustedError(absl::StrFormat(
            "%dx%d pixels x %d spp = %d hit points exceeds the limit of %d (about %d bytes each)", film.width,
            film.height, film.samples_per_pixel, most_hit_points, kMaxHitPoints, kBytesPerHitPoint));
    return film;
}

EstimateSettings EstimateFor(const RenderSettings& settings, const CameraPassResult& camera_pass, const Scene& scene) {
    EstimateSettings estimate{settings.alpha, settings.initial_radius, settings.samples_per_pixel, settings.layout};
    if (estimate.initial_radius == 0) estimate.initial_radius = DefaultInitialRadius(camera_pass, scene);
    if (camera_pass.hit_points.empty() || !(estimate.initial_radius > 0)) {
        spdlog::warn("{}: the camera sees no diffuse surface; the image holds emission only", settings.scene_path);
        estimate.initial_radius = std::max(estimate.initial_radius, 1e-3 * scene.bounds.Diagonal());
    }
    return estimate;
}

// The share of the budget spent, in [0, 1]; 1 ends the render after the current epoch.
double BudgetSpent(const RenderSettings& settings, const RenderProgress& progress) {
    const double by_photons =
        settings.photon_budget > 0 ? double(progress.photons) / double(settings.photon_budget) : 0.0;
    const double by_time = settings.seconds_budget > 0 ? progress.seconds / settings.seconds_budget : 0.0;
    return std::min(1.0, std::max(by_photons, by_time));
}

}  // namespace

absl::StatusOr<RenderOutcome> RenderLocally(const RenderSettings& settings, const EpochCallback& on_epoch) {
    if (absl::Status status = CheckSettings(settings); !status.ok()) return status;
    absl::StatusOr<Scene> scene = LoadGltf(settings.scene_path);
    if (!scene.ok()) return scene.status();
    const Emitters emitters(*scene);
    if (!emitters.HasPower()) return absl::InvalidArgumentError(absl::StrCat(settings.scene_path, ": lights emit no power"));
    const absl::StatusOr<CameraPassSettings> film = FilmFor(settings, scene->camera);
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
        const EstimateSettings estimate_settings = EstimateFor(settings, camera_pass, *scene);
        outcome.initial_radius = estimate_settings.initial_radius;
        spdlog::info("camera pass: {} hit points in {:.2f} s, initial radius {:.4g}", outcome.hit_points,
                     outcome.camera_pass_seconds, outcome.initial_radius);
        ProgressiveEstimate estimate(std::move(camera_pass), estimate_settings);

        embree::CpuBackend backend(**tracer);
        status = backend.BeginJob({&*scene, &emitters, estimate.HitPoints(), settings.seed});
        RenderProgress& progress = outcome.progress;
        while (status.ok() && progress.fraction < 1.0 && !(settings.stop != nullptr && settings.stop->load())) {
            backend.BeginEpoch(estimate.SearchRadiusSq());
            const std::vector<BatchResult> results = backend.RunBatches(estimate.EpochBatches());
            estimate.MergeEpoch(results);
            for (const BatchResult& result : results) progress.segments += result.segments_traced;
            progress.epochs = estimate.Epoch();
            progress.photons = estimate.PhotonsEmitted();
            progress.seconds = elapsed();
            progress.fraction = BudgetSpent(settings, progress);
            if (on_epoch) on_epoch(progress, estimate);
        }
        outcome.image = estimate.Resolve();
    });
    if (!status.ok()) return status;
    return outcome;
}

}  // namespace pf
