// CPU batch execution.
#include "worker/backends/cpu_embree/cpu_backend.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "core/pm/photon_mapping.h"
#include "core/ppm/photon_pass.h"
#include "core/render/path_tracer.h"
#include "core/util/check.h"

namespace pf::embree {

absl::Status CpuBackend::BeginJob(const JobInputs& job) {
    if (job.scene == nullptr || job.emitters == nullptr || !job.emitters->HasPower())
        return absl::InvalidArgumentError("job has no scene or no light");
    job_ = job;
    features_ = AnalyseFeatures(*job.scene, *job.emitters);
    grid_ = HashGrid();
    radiance_ = nullptr;
    film_.reset();
    fixed_ = {};
    epoch_hit_points_.clear();
    direct_sequence_.reset();
    maps_.reset();
    // A camera sample's cone, for textures where the integrators that render pixels meet them
    // (an orthographic camera's samples have none: point lookups).
    const float filter_angle = job.spec == nullptr
                                   ? 0.0f
                                   : job.scene->camera.Footprint(job.spec->height).angle /
                                         std::sqrt(static_cast<float>(job.spec->samples_per_pixel));
    // Without a spec (ppm's batches alone: tests, benchmarks) direct light is sampled at the
    // hit points given.
    switch (job.spec != nullptr ? job.spec->integrator : Integrator::kPpm) {
        case Integrator::kPpm:
        case Integrator::kSppm:
        case Integrator::kRpm: {
            if (job.spec == nullptr) break;
            absl::StatusOr<CameraPassSettings> film = FilmFor(*job.spec, *job.scene);
            if (!film.ok()) return film.status();
            film->features = features_;
            film_ = *film;
            if (job.spec->integrator == Integrator::kPpm) {
                absl::StatusOr<PixelHitPoints> fixed = IndexFixedHitPoints(job.hit_points, *film_);
                if (!fixed.ok()) return fixed.status();
                fixed_ = std::move(*fixed);
            }
            break;
        }
        case Integrator::kPath: {
            PathInputs inputs{job.scene, job.emitters, &tracer_, features_, filter_angle};
            inputs.max_depth = DepthLimit(job.spec->max_depth, kMaxPathDepth);
            radiance_ = [inputs](const Ray& ray, Rng& rng) { return TracePath(inputs, ray, rng); };
            break;
        }
        case Integrator::kPm: {
            // Every worker builds the same maps from the job's seed; they must fit here too.
            const PhotonMapSettings& settings = job.spec->photon_map;
            const PhotonMapForecast forecast =
                ForecastPhotonMaps(*job.scene, *job.emitters, tracer_, features_, settings,
                                   job.seed, job.spec->max_depth);
            if (absl::Status status =
                    CheckPhotonMapsFit(forecast, settings, AvailableMemoryBytes());
                !status.ok())
                return status;
            const auto start = std::chrono::steady_clock::now();
            maps_ = std::make_shared<const PhotonMaps>(
                BuildPhotonMaps(*job.scene, *job.emitters, tracer_, features_, settings, job.seed,
                                job.spec->max_depth));
            spdlog::info(
                "photon maps: {} global and {} caustic photons stored ({:.0f} MB) in {:.2f} s",
                maps_->global->Photons().size(), maps_->caustic->Photons().size(),
                maps_->Bytes() / 1e6,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
            const PhotonMappingInputs inputs{
                job.scene,    job.emitters, &tracer_,
                maps_.get(),  settings,     MaxSearchRadius(settings, *job.scene),
                filter_angle, features_,    job.spec->max_depth};
            radiance_ = [inputs, maps = maps_](const Ray& ray, Rng& rng) {
                return PhotonMappingRadiance(inputs, ray, rng);
            };
            break;
        }
    }
    return absl::OkStatus();
}

absl::Status CpuBackend::BeginEpoch(uint64_t epoch, const GatherRegions& regions,
                                    const std::vector<HitPoint>* traced) {
    if (film_) {
        // sppm's and rpm's hit points are the pass's; ppm samples direct light there.
        const bool stochastic = TracesHitPointsEachEpoch(job_.spec->integrator);
        const CameraPassSettings pass = StochasticCameraPass(*film_, *job_.spec, epoch);
        if (!stochastic) {  // both traced by parts, as batches need them
            direct_points_.Reset(pass);
            emission_pass_ = EmissionCameraPass(*film_, *job_.spec, epoch);
        } else if (traced != nullptr)
            epoch_hit_points_ = *traced;
        else
            epoch_hit_points_ =
                RunCameraPass(*job_.scene, *job_.emitters, tracer_, pass).hit_points;
        if (stochastic) job_.hit_points = epoch_hit_points_;
        direct_sequence_ =
            DirectLightSequence{pass.samples_per_pixel, pass.first_sample, 1 + pass.gather_rays};
    }
    PF_CHECK(regions.radius_sq.size() == job_.hit_points.size() &&
             (regions.edges.empty() || regions.edges.size() == regions.radius_sq.size()));
    if (!regions.radius_sq.empty()) grid_.Build(job_.hit_points, regions.radius_sq, regions.edges);
    return absl::OkStatus();
}

absl::StatusOr<std::vector<BatchResult>> CpuBackend::RunBatches(std::span<const BatchSpec> specs) {
    if (radiance_) {
        const JobSpec& spec = *job_.spec;
        return RunPixelBatches(job_.scene->camera,
                               {spec.width, spec.height, spec.samples_per_pixel}, job_.seed, specs,
                               radiance_);
    }
    PhotonPassInputs inputs{job_.scene, job_.emitters, &tracer_, job_.hit_points,
                            &grid_,     job_.seed,     features_};
    if (film_ && !TracesHitPointsEachEpoch(job_.spec->integrator)) {
        direct_points_.Cover(*job_.scene, *job_.emitters, tracer_, specs);
        inputs.direct_points = direct_points_.Points();
        inputs.direct_offset = direct_points_.FirstSlot();
    } else {
        inputs.direct_points = epoch_hit_points_;
    }
    inputs.direct_sequence = direct_sequence_;
    if (job_.spec != nullptr) {
        inputs.max_bounces = DepthLimit(job_.spec->max_depth, kMaxPhotonBounces);
        inputs.adaptive = job_.spec->photon_tracing == PhotonTracing::kAdaptive;
        inputs.direct_photons = job_.spec->integrator == Integrator::kRpm;
    }
    std::vector<BatchResult> results = RunPhotonBatches(inputs, specs, scratch_);
    if (film_ && !TracesHitPointsEachEpoch(job_.spec->integrator))
        TraceBatchEmission(*job_.scene, *job_.emitters, tracer_, emission_pass_, fixed_, results);
    return results;
}

}  // namespace pf::embree
