#include "core/ppm/epoch_passes.h"

#include "core/job/integrator.h"

namespace pf {

absl::StatusOr<EpochPasses> EpochPasses::Create(const JobSpec& spec, const Scene& scene,
                                                const Emitters& emitters,
                                                std::span<const HitPoint> fixed,
                                                const SceneFeatures& features) {
    EpochPasses passes;
    passes.spec_ = &spec;
    passes.scene_ = &scene;
    passes.emitters_ = &emitters;
    passes.stochastic_ = TracesHitPointsEachEpoch(spec.integrator);
    absl::StatusOr<CameraPassSettings> film = FilmFor(spec, scene);
    if (!film.ok()) return film.status();
    film->features = features;
    passes.film_ = *film;
    if (!passes.stochastic_) {
        absl::StatusOr<PixelHitPoints> indexed = IndexFixedHitPoints(fixed, passes.film_);
        if (!indexed.ok()) return indexed.status();
        passes.fixed_ = std::move(*indexed);
    }
    return passes;
}

size_t EpochPasses::MaxEpochPoints() const {
    // A growing epoch takes fewer samples than the largest.
    return size_t(film_.width) * size_t(film_.height) * size_t(MaxEpochSamplesPerPixel(*spec_)) *
           SlotsPerCameraSample(*spec_);
}

void EpochPasses::Begin(uint64_t epoch, const Tracer& tracer, const std::vector<HitPoint>* traced) {
    const CameraPassSettings pass = StochasticCameraPass(film_, *spec_, epoch);
    sequence_ =
        DirectLightSequence{pass.samples_per_pixel, pass.first_sample, 1 + pass.gather_rays};
    if (!stochastic_) {  // both traced by parts, as batches need them
        direct_points_.Reset(pass);
        emission_pass_ = EmissionCameraPass(film_, *spec_, epoch);
    } else if (traced != nullptr) {
        epoch_hit_points_ = *traced;
    } else {
        epoch_hit_points_ = RunCameraPass(*scene_, *emitters_, tracer, pass).hit_points;
    }
}

bool EpochPasses::CoverDirectPoints(const Tracer& tracer, std::span<const BatchSpec> specs) {
    return direct_points_.Cover(*scene_, *emitters_, tracer, specs);
}

void EpochPasses::AddEmission(const Tracer& tracer, std::span<BatchResult> results) const {
    TraceBatchEmission(*scene_, *emitters_, tracer, emission_pass_, fixed_, results);
}

}  // namespace pf
