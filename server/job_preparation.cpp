// Job preparation: the scene loaded, the camera pass run and the estimate set up.
#include "server/job_preparation.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <set>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "core/camera/camera_pass.h"
#include "core/estimate/pixel_estimate.h"
#include "core/estimate/progressive_estimate.h"
#include "core/film/image_metrics.h"
#include "core/pm/density_radii.h"
#include "core/pm/photon_map.h"
#include "core/ppm/caustic_probe.h"
#include "core/ppm/hash_grid.h"
#include "core/ppm/photon_pass.h"
#include "core/scene/scene_features.h"
#include "core/scene_io/scene_loader.h"
#include "embree/embree_tracer.h"
#include "server/camera_passes.h"

namespace pf {
namespace {

const char* SettingName(SettingNames names, const char* field, const char* flag) {
    return names == SettingNames::kFlags ? flag : field;
}

// The share of photons that reach the first pass's hit points within their radii (`radii` per
// hit point, or `radius` for all), from a pilot.
double VisibleShare(const JobPayload& payload, const Tracer& tracer, const SceneFeatures& features,
                    std::span<const HitPoint> hit_points, std::span<const float> radii,
                    double radius) {
    std::vector<float> radius_sq(hit_points.size(), float(radius * radius));
    for (size_t i = 0; i < radii.size(); ++i) radius_sq[i] = radii[i] * radii[i];
    HashGrid grid;
    grid.Build(hit_points, radius_sq);
    PhotonPassInputs inputs{&payload.scene, &payload.emitters, &tracer, hit_points,
                            &grid,          payload.seed,      features};
    inputs.max_bounces = DepthLimit(payload.spec.max_depth, kMaxPhotonBounces);
    return VisiblePhotonShare(inputs, kVisibilityPilotPhotons);
}

absl::Status CheckReference(const Image* reference, int width, int height) {
    if (reference == nullptr) return absl::OkStatus();
    if (reference->width != width || reference->height != height)
        return absl::InvalidArgumentError(
            absl::StrFormat("reference: the image is %dx%d but the job renders %dx%d",
                            reference->width, reference->height, width, height));
    if (const uint64_t nonfinite = NonfinitePixels(*reference); nonfinite > 0)
        return absl::InvalidArgumentError(absl::StrFormat(
            "reference: %d pixels hold NaN or Inf; a reference must be finite", nonfinite));
    return absl::OkStatus();
}

}  // namespace

absl::StatusOr<PreparedJob> PrepareJob(JobRequest request, const CoordinatorOptions& options) {
    const SettingNames names = options.setting_names;
    const ClientLimits& client_limits = options.client_limits;
    if (absl::Status status = CheckJobSpec(request.spec, names); !status.ok()) return status;
    if (request.priority < -kMaxJobPriority || request.priority > kMaxJobPriority)
        return absl::InvalidArgumentError(
            absl::StrCat(SettingName(names, "settings.priority", "--priority"), " must lie in [",
                         -kMaxJobPriority, ", ", kMaxJobPriority, "], not ", request.priority));
    if (absl::Status status = CheckSceneBundle(request.bundle); !status.ok()) return status;
    if (const uint64_t bytes = request.bundle.TotalBytes(); bytes > client_limits.max_bundle_bytes)
        return absl::ResourceExhaustedError(absl::StrCat(
            "scene: the bundle holds ", bytes, " bytes, over this coordinator's limit of ",
            client_limits.max_bundle_bytes, " (--max-bundle-bytes)"));
    if (request.name.empty())
        request.name = std::filesystem::path(request.bundle.main_file).filename().string();
    absl::StatusOr<Scene> scene = LoadScene(
        request.bundle, request.bundle.main_file,
        {options.scene_limits, nullptr, true, request.spec.environment, request.spec.camera});
    if (!scene.ok()) return scene.status();
    absl::StatusOr<CameraPassSettings> film = FilmFor(request.spec, *scene);
    if (!film.ok()) return film.status();
    if (const uint64_t pixels = uint64_t(film->width) * film->height;
        pixels > client_limits.max_render_pixels)
        return absl::ResourceExhaustedError(
            absl::StrFormat("%s: the image is %dx%d, %d pixels, over this coordinator's limit of "
                            "%d (--max-render-pixels)",
                            SettingName(names, "settings.width", "--width"), film->width,
                            film->height, pixels, client_limits.max_render_pixels));
    // The film size resolved (workers that render pixels need it), and with it the layout.
    request.spec.width = film->width;
    request.spec.height = film->height;
    request.spec.layout = ResolvedLayout(request.spec, uint64_t(film->width) * film->height);
    if (request.spec.layout.photons_per_batch > client_limits.max_photons_per_batch)
        return absl::ResourceExhaustedError(absl::StrCat(
            SettingName(names, "settings.photons_per_batch", "--photons-per-batch"), ": ",
            request.spec.layout.photons_per_batch, " is over this coordinator's limit of ",
            client_limits.max_photons_per_batch, " (--max-photons-per-batch)"));
    auto payload = std::make_shared<JobPayload>(std::move(*scene), nullptr, request.spec);
    if (!payload->emitters.HasPower())
        return absl::InvalidArgumentError(
            absl::StrCat(request.bundle.main_file, ": lights emit no power"));
    if (const double power = MaxComponent(payload->emitters.TotalPower()); power > kMaxLightPower)
        return absl::InvalidArgumentError(
            absl::StrFormat("%s: lights emit %.3g W in all, over the %.3g W that single-precision "
                            "photon sums hold (docs/numerics.md)",
                            request.bundle.main_file, power, kMaxLightPower));
    // For the camera pass and the job's record; each backend analyses the scene it is given
    // the same way (AnalyseFeatures) for its photon loop.
    film->features = AnalyseFeatures(payload->scene, payload->emitters);
    if (absl::Status status = CheckReference(request.reference.get(), film->width, film->height);
        !status.ok())
        return status;
    absl::StatusOr<std::unique_ptr<embree::EmbreeTracer>> made =
        embree::EmbreeTracer::Create(payload->scene);
    if (!made.ok()) return made.status();
    // One Embree scene for the probe, the camera passes and the forecast.
    const std::shared_ptr<const Tracer> tracer = std::move(*made);
    if (film->features.Specular()) {
        const CausticProbe probe =
            ProbeCaustics(payload->scene, payload->emitters, *tracer, request.spec.seed);
        film->features.caustics = probe.caustic > 0;
        spdlog::info(
            "{}: {:.2f}% of light paths reach a diffuse surface through specular bounces "
            "(caustics)",
            request.name, 100 * probe.Fraction());
    }
    PreparedJob prepared;
    const Integrator integrator = request.spec.integrator;
    if (GathersAtHitPoints(integrator)) {
        const auto start = Clock::now();
        // sppm's and rpm's camera pass of every epoch, traced here: their photons gather and
        // direct light is sampled there. ppm's photons gather at hit points traced once; the
        // workers trace each epoch's emission and direct light, each batch its pixels'.
        const bool stochastic = TracesHitPointsEachEpoch(integrator);
        EpochCameraPass passes =
            stochastic ? EpochCameraPasses(payload, *film, tracer) : EpochCameraPass{};
        CameraPassResult camera_pass =
            stochastic ? passes(0)
                       : RunCameraPass(payload->scene, payload->emitters, *tracer, *film);
        EstimateSettings settings =
            EstimateFor(request.spec, camera_pass, payload->scene, request.bundle.main_file);
        const double camera_seconds = std::chrono::duration<double>(Clock::now() - start).count();
        // R0 left open (no --radius, no pbrt "radius"): each hit point's from the photons.
        std::vector<float> radii;
        if (integrator == Integrator::kRpm) {
            // Its passes bring each slot's radius, epoch by epoch (EpochCameraPasses).
            if (const double median = MedianRadius(camera_pass.radius, camera_pass.footprint);
                median > 0)
                settings.initial_radius = median;
            settings.min_radius = std::min(settings.min_radius, settings.initial_radius);
        } else if (request.spec.initial_radius == 0 && payload->scene.hints.initial_radius == 0 &&
                   !camera_pass.hit_points.empty()) {
            const auto pilot_start = Clock::now();
            DensityRadiiSettings density;
            // The first pass: a full epoch (the growing epochs are one pass together).
            density.first_epoch_photons = settings.layout.PhotonsPerEpoch();
            density.seed = request.spec.seed;
            density.max_depth = request.spec.max_depth;
            const double footprint_radius = settings.initial_radius;
            radii = DensityInitialRadii(payload->scene, payload->emitters, *tracer, film->features,
                                        camera_pass.hit_points, camera_pass.footprint,
                                        float(settings.initial_radius), density);
            if (const double median = MedianRadius(radii, camera_pass.footprint); median > 0)
                settings.initial_radius = median;
            settings.min_radius = std::min(settings.min_radius, settings.initial_radius);
            spdlog::info(
                "{}: initial radii from a pilot photon map in {:.2f} s (median pixel "
                "footprint {:.4g})",
                request.name, std::chrono::duration<double>(Clock::now() - pilot_start).count(),
                footprint_radius);
        }
        PhotonTracing& tracing = request.spec.photon_tracing;
        if (integrator == Integrator::kRpm) {  // uniform only (CheckJobSpec)
            tracing = PhotonTracing::kUniform;
            payload->spec.photon_tracing = tracing;
        }
        if (tracing != PhotonTracing::kUniform) {
            const double share =
                VisibleShare(*payload, *tracer, film->features, camera_pass.hit_points, radii,
                             settings.initial_radius);
            if (tracing == PhotonTracing::kAuto)
                tracing = share < kAdaptiveBelowVisibleShare ? PhotonTracing::kAdaptive
                                                             : PhotonTracing::kUniform;
            payload->spec.photon_tracing = tracing;
            spdlog::info("{}: {:.2f}% of photons reach what the camera sees: {} photon tracing",
                         request.name, 100 * share, PhotonTracingName(tracing));
            // The chains bring about 1 / share as many photons near the hit points as the
            // pilot found, and a radius balancing bias (~R^2) against noise (~1 / (density
            // R^2)) goes as density^-1/4; but a chain's steps are correlated, worth fewer
            // photons than they find: radii from the pilot's density shrink by share^1/8 (on
            // light-gap the best of the powers tried, docs/integrators.md).
            if (tracing == PhotonTracing::kAdaptive && !radii.empty() && share > 0) {
                const double least = DensityRadiiSettings{}.least_footprints;
                for (size_t i = 0; i < radii.size(); ++i)
                    radii[i] = std::max(radii[i] * float(std::pow(share, 0.125)),
                                        float(least * camera_pass.footprint[i]));
                if (const double median = MedianRadius(radii, camera_pass.footprint); median > 0)
                    settings.initial_radius = median;
                settings.min_radius = std::min(settings.min_radius, settings.initial_radius);
            }
        }
        // ppm: where each fixed hit point's surface ends, as far as its initial radius reaches
        // (docs/design.md). sppm's hit points, new every epoch, gather in their spheres: probing
        // each pass cost it half its photons, more than the edges gained it (docs/integrators.md).
        const auto probe_start = Clock::now();
        if (integrator == Integrator::kPpm) {
            std::vector<float> reach = radii;
            if (reach.empty())
                reach.assign(camera_pass.hit_points.size(), float(settings.initial_radius));
            camera_pass.extent =
                ProbeSurfaceExtents(payload->scene, *tracer, camera_pass.hit_points, reach);
        }
        spdlog::info(
            "{}: camera pass: {}x{}, {} hit points in {:.2f} s, their surfaces probed in {:.2f} s, "
            "initial radius {:.4g}",
            request.name, film->width, film->height, camera_pass.hit_points.size(), camera_seconds,
            std::chrono::duration<double>(Clock::now() - probe_start).count(),
            settings.initial_radius);
        prepared.estimate = std::make_unique<ProgressiveEstimate>(std::move(camera_pass), settings,
                                                                  std::move(passes), radii);
    } else {
        const PhotonMapSettings& maps = request.spec.photon_map;
        if (integrator == Integrator::kPm) {  // refused here rather than by every worker
            const PhotonMapForecast forecast = ForecastPhotonMaps(
                payload->scene, payload->emitters, *tracer, film->features, maps, payload->seed);
            if (absl::Status status = CheckPhotonMapsFit(forecast, maps, AvailableMemoryBytes());
                !status.ok())
                return status;
            spdlog::info("{}: the photon maps will hold about {:.3g} MB", request.name,
                         forecast.bytes / 1e6);
        }
        prepared.estimate = std::make_unique<PixelEstimate>(PixelEstimateSettings{
            request.spec.integrator, film->width, film->height, film->samples_per_pixel,
            request.spec.layout.batches_per_epoch,
            integrator == Integrator::kPm
                ? maps.global_photons +
                      (film->features.Specular() ? maps.caustic_photons : 0)  // as BuildPhotonMaps
                : 0});
    }
    // Workers trace a stochastic job's hit points themselves, epoch by epoch.
    payload->hit_points = TracesHitPointsEachEpoch(integrator)
                              ? std::make_shared<const std::vector<HitPoint>>()
                              : prepared.estimate->SharedHitPoints();
    prepared.payload = std::move(payload);
    prepared.name = std::move(request.name);
    prepared.owner = std::move(request.owner);
    prepared.spec = request.spec;
    prepared.priority = request.priority;
    prepared.bundle = std::move(request.bundle);
    prepared.reference = std::move(request.reference);
    prepared.scene_features = film->features.ToString();
    return prepared;
}

}  // namespace pf
