// Checks and scene-derived defaults of a render's settings.
#include "core/job/job_spec.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/sampling/rng.h"

namespace pf {

absl::Status CheckJobSpec(const JobSpec& s, SettingNames names) {
    const bool flags = names == SettingNames::kFlags;
    auto invalid = [&](const char* flag, const char* field, const std::string& what) {
        return absl::InvalidArgumentError(absl::StrCat(flags ? flag : field, " ", what));
    };
    if (s.width < 0 || s.height < 0 || s.width > 32768 || s.height > 32768)
        return invalid("--width/--height", "settings.width/settings.height",
                       "must lie in [1, 32768]");
    if (s.samples_per_pixel < 1 || s.samples_per_pixel > 1024)
        return invalid("--spp", "settings.samples_per_pixel", "must lie in [1, 1024]");
    if (!(s.alpha >= 0 && s.alpha <= 1))
        return invalid("--alpha", "settings.alpha", "must lie in (0, 1] (0: balanced)");
    if (!(s.initial_radius >= 0 && std::isfinite(s.initial_radius)))
        return invalid("--radius", "settings.initial_radius", "must be positive and finite");
    // 0: left to the job (ResolvedLayout).
    if (s.layout.photons_per_batch > kMaxPhotonsPerBatch)
        return invalid("--photons-per-batch", "settings.photons_per_batch",
                       absl::StrCat("must lie in [1, ", kMaxPhotonsPerBatch, "]"));
    if (s.layout.batches_per_epoch > kMaxBatchesPerEpoch)
        return invalid("--batches-per-epoch", "settings.batches_per_epoch",
                       absl::StrCat("must lie in [1, ", kMaxBatchesPerEpoch, "]"));
    if (s.layout.first_epoch_photons > uint64_t{kMaxPhotonsPerBatch} * kMaxBatchesPerEpoch)
        return invalid("--first-epoch-photons", "settings.first_epoch_photons",
                       absl::StrCat("must lie in [1, ",
                                    uint64_t{kMaxPhotonsPerBatch} * kMaxBatchesPerEpoch, "]"));
    if (s.photon_budget > kMaxPhotonBudget)
        return invalid("--photons", "settings.photon_budget",
                       absl::StrCat("must lie in [0, ", kMaxPhotonBudget, "], not ",
                                    s.photon_budget, " (0: none)"));
    if (s.epoch_budget > kMaxEpochBudget)
        return invalid("--epochs", "settings.epoch_budget",
                       absl::StrCat("must lie in [0, ", kMaxEpochBudget, "], not ", s.epoch_budget,
                                    " (0: none)"));
    if (!(s.seconds_budget >= 0 && s.seconds_budget <= kMaxSecondsBudget))
        return invalid("--seconds", "settings.seconds_budget",
                       absl::StrFormat("must lie in [0, %g], not %g (0: none)", kMaxSecondsBudget,
                                       s.seconds_budget));
    if (!(s.target_error >= 0 && s.target_error < 1e3))
        return invalid("--target-error", "settings.target_error",
                       "must lie in [0, 1000) (a relative error, 0.01 = 1%)");
    const bool budgeted =
        s.photon_budget != 0 || s.epoch_budget != 0 || s.seconds_budget != 0 || s.target_error != 0;
    if (!budgeted && !s.until_cancelled)
        return absl::InvalidArgumentError(
            flags ? "give a budget: --photons N, --epochs N, --seconds S or --target-error E "
                    "(or --until-cancelled)"
                  : "settings: give a budget (photon_budget, epoch_budget, seconds_budget or "
                    "target_error), or until_cancelled for none");
    if (budgeted && s.until_cancelled)
        return invalid("--until-cancelled", "settings.until_cancelled",
                       "asks for no budget: give it without --photons, --epochs, --seconds and "
                       "--target-error");
    if (s.photon_budget > 0 && !GathersAtHitPoints(s.integrator))
        return invalid(
            "--photons", "settings.photon_budget",
            absl::StrCat(
                "is a budget of photons traced progressively, and the ",
                std::string(IntegratorName(s.integrator)),
                " integrator traces none as it goes: give --epochs, --seconds or --target-error",
                s.integrator == Integrator::kPm ? " (its maps' size is --pm-photons)" : ""));
    if (s.photon_tracing != PhotonTracing::kAuto && !GathersAtHitPoints(s.integrator))
        return invalid("--photon-tracing", "settings.photon_tracing",
                       absl::StrCat("applies to ppm, sppm and rpm, whose photons gather at hit "
                                    "points, not to the ",
                                    std::string(IntegratorName(s.integrator)), " integrator"));
    if (s.integrator == Integrator::kRpm) {
        if (s.photon_tracing == PhotonTracing::kAdaptive)
            return invalid("--photon-tracing", "settings.photon_tracing",
                           "adaptive is not offered for rpm: its gather hits see most of the "
                           "scene, where Markov chains toward them would not pay");
        if (s.alpha != 0)
            return invalid("--alpha", "settings.alpha",
                           "applies to ppm and sppm: rpm keeps its radii, as classic photon "
                           "mapping does (--pm-nearest and --pm-photons set them)");
        // A gather hit's photons would have to reach it within the depth the camera path and
        // its gather ray left them, which a deposit does not record.
        if (s.max_depth != 0)
            return invalid("--max-depth", "settings.max_depth",
                           "is not offered for rpm, whose photons reach its gather hits at any "
                           "depth: give it to ppm, sppm, pm or path");
    }
    if (absl::Status status = CheckEnvironmentSettings(s.environment, names); !status.ok())
        return status;
    if (s.max_depth < 0 || s.max_depth > kMaxDepthSetting)
        return invalid("--max-depth", "settings.max_depth",
                       absl::StrCat("must lie in [0, ", kMaxDepthSetting, "] (0: no limit)"));
    if (s.camera.size() > 256)
        return invalid("--camera", "settings.camera", "must be at most 256 characters");
    if (s.integrator == Integrator::kPm || s.integrator == Integrator::kRpm)
        return CheckPhotonMapSettings(s.photon_map, names);
    return absl::OkStatus();
}

absl::Status CheckEnvironmentSettings(const EnvironmentSettings& e, SettingNames names) {
    const bool flags = names == SettingNames::kFlags;
    auto invalid = [&](const char* flag, const char* field, const std::string& what) {
        return absl::InvalidArgumentError(absl::StrCat(flags ? flag : field, " ", what));
    };
    if (!e.file.empty() && e.color)
        return invalid("--environment-color", "settings.environment.color",
                       "excludes --environment (a file): give one");
    if (e.color && (!IsFinite(*e.color) || MinComponent(*e.color) < 0 ||
                    MaxComponent(*e.color) > kMaxEnvironmentScale))
        return invalid("--environment-color", "settings.environment.color",
                       absl::StrFormat("must be R,G,B each in [0, %g]", kMaxEnvironmentScale));
    if (!(e.scale > 0 && e.scale <= kMaxEnvironmentScale))
        return invalid(
            "--environment-scale", "settings.environment.scale",
            absl::StrFormat("must lie in (0, %g], not %g", kMaxEnvironmentScale, e.scale));
    if (!(std::abs(e.rotate_degrees) <= 360))
        return invalid("--environment-rotate", "settings.environment.rotate_degrees",
                       "must lie in [-360, 360] degrees");
    if (!e.Given() && (e.scale != 1 || e.rotate_degrees != 0))
        return invalid("--environment-scale/--environment-rotate",
                       "settings.environment.scale/rotate_degrees",
                       "apply to an environment: give --environment FILE or --environment-color");
    return absl::OkStatus();
}

absl::Status CheckPhotonMapSettings(const PhotonMapSettings& m, SettingNames names) {
    const bool flags = names == SettingNames::kFlags;
    auto invalid = [&](const char* flag, const char* field, const std::string& what) {
        return absl::InvalidArgumentError(absl::StrCat(flags ? flag : field, " ", what));
    };
    if (m.global_photons + m.caustic_photons == 0 || m.global_photons > kMaxMapPhotons ||
        m.caustic_photons > kMaxMapPhotons)
        return invalid("--pm-photons/--pm-caustic-photons",
                       "settings.photon_map.global_photons/caustic_photons",
                       absl::StrCat("must lie in [0, ", kMaxMapPhotons, "], not both 0"));
    if (m.nearest < 1 || m.nearest > kMaxNearestPhotons)
        return invalid("--pm-nearest", "settings.photon_map.nearest",
                       absl::StrCat("must lie in [1, ", kMaxNearestPhotons, "]"));
    if (!(m.max_radius >= 0 && std::isfinite(m.max_radius)))
        return invalid("--pm-max-radius", "settings.photon_map.max_radius",
                       "must be positive and finite");
    if (m.final_gather > kMaxFinalGatherRays)
        return invalid("--final-gather", "settings.photon_map.final_gather",
                       absl::StrCat("must lie in [0, ", kMaxFinalGatherRays, "]"));
    if (static_cast<uint32_t>(m.filter) > static_cast<uint32_t>(DensityFilter::kGaussian))
        return invalid("--pm-filter", "settings.photon_map.filter", "is not a filter");
    if (static_cast<uint32_t>(m.index) > static_cast<uint32_t>(PhotonIndex::kGrid))
        return invalid("--photon-index", "settings.photon_map.index", "is not a photon index");
    return absl::OkStatus();
}

BatchLayout ResolvedLayout(const JobSpec& spec, uint64_t pixels) {
    BatchLayout layout = spec.layout;
    const bool open = layout.photons_per_batch == 0 && layout.batches_per_epoch == 0;
    if (!TracesHitPointsEachEpoch(spec.integrator)) {
        if (layout.photons_per_batch == 0) layout.photons_per_batch = kDefaultPhotonsPerBatch;
        if (layout.batches_per_epoch == 0) layout.batches_per_epoch = kDefaultBatchesPerEpoch;
    } else {
        const uint64_t samples = std::max<uint64_t>(pixels, 1) * uint64_t(spec.samples_per_pixel);
        if (layout.batches_per_epoch == 0) {
            const uint64_t per_batch =
                layout.photons_per_batch > 0 ? layout.photons_per_batch : kSppmPhotonsPerBatch;
            layout.batches_per_epoch = static_cast<uint32_t>(std::clamp<uint64_t>(
                (samples + per_batch - 1) / per_batch,
                layout.photons_per_batch > 0 ? 1 : kDefaultBatchesPerEpoch, kMaxBatchesPerEpoch));
        }
        if (layout.photons_per_batch == 0)
            layout.photons_per_batch = static_cast<uint32_t>(std::clamp<uint64_t>(
                (samples + layout.batches_per_epoch - 1) / layout.batches_per_epoch, 1,
                kMaxPhotonsPerBatch));
    }
    if (layout.first_epoch_photons == 0)
        layout.first_epoch_photons = open && spec.integrator == Integrator::kPpm
                                         ? kFirstEpochPhotons
                                         : layout.PhotonsPerEpoch();
    layout.first_epoch_photons = std::min(layout.first_epoch_photons, layout.PhotonsPerEpoch());
    return layout;
}

namespace {

// ppm's camera samples a pixel for an epoch of `photons`.
int PpmSamplesPerPixel(uint64_t photons, uint64_t pixels) {
    const uint64_t per_pixel = photons / (2 * std::max<uint64_t>(pixels, 1));
    int samples = 1;
    while (samples < 64 && uint64_t(samples) * 2 <= per_pixel) samples *= 2;
    return samples;
}

}  // namespace

EpochSamples EpochCameraSamples(Integrator integrator, int samples_per_pixel,
                                const BatchLayout& layout, uint64_t pixels, uint64_t epoch) {
    if (TracesHitPointsEachEpoch(integrator))
        return {samples_per_pixel, (epoch >> 1) * uint64_t(samples_per_pixel)};
    const auto in = [&](uint64_t e) {
        return PpmSamplesPerPixel(layout.PhotonsInEpoch(e), pixels);
    };
    const uint64_t growing = layout.GrowingEpochs();
    EpochSamples samples{in(epoch), 0};
    // The earlier epochs of the same parity: the growing ones one by one, the full ones at once.
    for (uint64_t e = epoch & 1; e < std::min(epoch, growing); e += 2)
        samples.first += uint64_t(in(e));
    if (epoch > growing) samples.first += (epoch - growing) / 2 * uint64_t(in(growing));
    return samples;
}

EpochSamples EpochCameraSamples(const JobSpec& spec, uint64_t epoch) {
    const uint64_t pixels = uint64_t(spec.width) * uint64_t(spec.height);
    return EpochCameraSamples(spec.integrator, spec.samples_per_pixel, ResolvedLayout(spec, pixels),
                              pixels, epoch);
}

int MaxEpochSamplesPerPixel(const JobSpec& spec) {
    const uint64_t pixels = uint64_t(spec.width) * uint64_t(spec.height);
    const BatchLayout layout = ResolvedLayout(spec, pixels);
    return EpochCameraSamples(spec.integrator, spec.samples_per_pixel, layout, pixels,
                              layout.GrowingEpochs())
        .per_pixel;
}

uint64_t PhotonSeed(const JobSpec& spec) {
    constexpr uint64_t kPhotonStreams = 0x73747265616d73ull;
    return spec.photon_stream == 0 ? spec.seed
                                   : HashSeed(spec.seed, kPhotonStreams, spec.photon_stream);
}

double BudgetFraction(const JobSpec& spec, uint64_t photons, uint64_t epochs, double seconds,
                      std::optional<double> estimated_error) {
    const double by_photons =
        spec.photon_budget > 0 ? double(photons) / double(spec.photon_budget) : 0.0;
    const double by_epochs =
        spec.epoch_budget > 0 ? double(epochs) / double(spec.epoch_budget) : 0.0;
    const double by_time = spec.seconds_budget > 0 ? seconds / spec.seconds_budget : 0.0;
    double by_error = 0.0;
    if (spec.target_error > 0 && estimated_error) {
        const double ratio = spec.target_error / *estimated_error;
        by_error = *estimated_error <= spec.target_error ? 1.0 : ratio * ratio;
    }
    return std::min(1.0, std::max({by_photons, by_epochs, by_time, by_error}));
}

}  // namespace pf
