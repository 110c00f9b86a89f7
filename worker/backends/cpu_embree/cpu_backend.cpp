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
    passes_.reset();
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
            absl::StatusOr<EpochPasses> passes = EpochPasses::Create(
                *job.spec, *job.scene, *job.emitters, job.hit_points, features_);
            if (!passes.ok()) return passes.status();
            passes_ = std::move(*passes);
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
    if (passes_) {
        // sppm's and rpm's hit points are the pass's; ppm samples direct light there.
        passes_->Begin(epoch, tracer_, traced);
        if (passes_->Stochastic()) job_.hit_points = passes_->HitPoints();
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
    if (passes_) {
        if (!passes_->Stochastic()) {
            passes_->CoverDirectPoints(tracer_, specs);
            inputs.direct_points = passes_->DirectPoints();
            inputs.direct_offset = passes_->DirectOffset();
        } else {
            inputs.direct_points = passes_->HitPoints();
        }
        inputs.direct_sequence = passes_->Sequence();
    }
    if (job_.spec != nullptr) {
        inputs.max_bounces = DepthLimit(job_.spec->max_depth, kMaxPhotonBounces);
        inputs.adaptive = job_.spec->photon_tracing == PhotonTracing::kAdaptive;
        inputs.direct_photons = job_.spec->integrator == Integrator::kRpm;
    }
    std::vector<BatchResult> results = RunPhotonBatches(inputs, specs, scratch_);
    if (passes_ && !passes_->Stochastic()) passes_->AddEmission(tracer_, results);
    return results;
}

}  // namespace pf::embree
