// A progressive estimate saved and restored bit for bit, for the coordinator's checkpoints.
#include <cmath>

#include "absl/strings/str_cat.h"
#include "core/estimate/progressive_estimate.h"
#include "core/job/job_spec.h"

namespace pf {
namespace {

constexpr uint32_t kMagic = 0x53455046;  // "PFES" in a little-endian file
constexpr uint32_t kVersion = 2;

absl::Status Corrupt(const std::string& what) {
    return absl::DataLossError(absl::StrCat("estimate state: ", what));
}

}  // namespace

void ProgressiveEstimate::Save(ByteWriter& out) const {
    out.Value(kMagic);
    out.Value(kVersion);
    out.Array(std::span<const HitPoint>(*hit_points_));
    out.Value(settings_.alpha);
    out.Value(settings_.initial_radius);
    out.Value(settings_.samples_per_pixel);
    out.Value(settings_.layout.photons_per_batch);
    out.Value(settings_.layout.batches_per_epoch);
    out.Value(settings_.min_radius);
    out.Value(static_cast<uint8_t>(settings_.stochastic));
    out.Value(emission_.width);
    out.Value(emission_.height);
    out.Array(std::span<const Rgb>(emission_.pixels));
    if (settings_.stochastic) {
        out.Array(std::span<const Rgbd>(emission_sum_));
        out.Array(std::span<const Rgbd>(emission_even_));
        out.Array(std::span<const Rgb>(epoch_emission_.pixels));
    }
    out.Array(std::span<const PointEstimate>(points_));
    out.Array(std::span<const Rgbd>(direct_sum_));
    out.Array(std::span<const Rgbd>(flux_even_));
    out.Array(std::span<const Rgbd>(direct_even_));
    out.Array(std::span<const GatherCounts>(counts_));
    for (uint64_t value : {epoch_, photons_emitted_, photons_emitted_even_, nonfinite_discarded_})
        out.Value(value);
    out.Value(static_cast<uint8_t>(light_reached_));
    out.Value(static_cast<uint8_t>(epoch_light_reached_));
    out.Value(batches_folded_);
    out.Array(std::span<const uint64_t>(epoch_photons_));
    out.Array(std::span<const uint64_t>(epoch_inner_photons_));
    out.Array(std::span<const Rgbd>(epoch_flux_));
    out.Array(std::span<const Rgbd>(epoch_flux_even_));
    out.Array(std::span<const Rgb>(epoch_direct_));
    for (uint64_t value :
         {epoch_photons_emitted_, epoch_photons_emitted_even_, epoch_nonfinite_discarded_})
        out.Value(value);
}

absl::StatusOr<std::unique_ptr<ProgressiveEstimate>> ProgressiveEstimate::Load(ByteReader& in) {
    std::unique_ptr<ProgressiveEstimate> estimate(new ProgressiveEstimate());
    ProgressiveEstimate& e = *estimate;
    uint32_t magic = 0, version = 0;
    if (!in.Value(&magic) || magic != kMagic) return Corrupt("not an estimate");
    if (!in.Value(&version) || version != kVersion)
        return Corrupt(
            absl::StrCat("format version ", version, "; this build reads version ", kVersion));
    auto hit_points = std::make_shared<std::vector<HitPoint>>();
    if (!in.Array(hit_points.get(), kMaxHitPoints)) return Corrupt("hit points");
    EstimateSettings& settings = e.settings_;
    uint8_t stochastic = 0;
    if (!(in.Value(&settings.alpha) && in.Value(&settings.initial_radius) &&
          in.Value(&settings.samples_per_pixel) && in.Value(&settings.layout.photons_per_batch) &&
          in.Value(&settings.layout.batches_per_epoch) && in.Value(&settings.min_radius) &&
          in.Value(&stochastic)))
        return Corrupt("truncated settings");
    settings.stochastic = stochastic != 0;
    if (!(settings.alpha > 0 && settings.alpha <= 1 && settings.initial_radius > 0 &&
          std::isfinite(settings.initial_radius) && settings.min_radius >= 0 &&
          settings.min_radius <= settings.initial_radius && settings.samples_per_pixel > 0 &&
          settings.layout.photons_per_batch >= 1 &&
          settings.layout.photons_per_batch <= kMaxPhotonsPerBatch &&
          settings.layout.batches_per_epoch >= 1 &&
          settings.layout.batches_per_epoch <= kMaxBatchesPerEpoch))
        return Corrupt("settings out of range");
    if (!(in.Value(&e.emission_.width) && in.Value(&e.emission_.height)) || e.emission_.width < 1 ||
        e.emission_.height < 1 || e.emission_.width > 32768 || e.emission_.height > 32768)
        return Corrupt("image size");
    const uint64_t pixels = uint64_t(e.emission_.width) * e.emission_.height;
    if (!in.Array(&e.emission_.pixels, pixels) || e.emission_.pixels.size() != pixels)
        return Corrupt("emission");
    if (settings.stochastic) {
        e.epoch_emission_ = Image(e.emission_.width, e.emission_.height);
        if (!in.Array(&e.emission_sum_, pixels) || !in.Array(&e.emission_even_, pixels) ||
            !in.Array(&e.epoch_emission_.pixels, pixels) || e.emission_sum_.size() != pixels ||
            e.emission_even_.size() != pixels || e.epoch_emission_.pixels.size() != pixels)
            return Corrupt("emission sums");
    }
    for (const HitPoint& hit_point : *hit_points)
        if (hit_point.pixel >= pixels) return Corrupt("a hit point lies outside the image");
    const uint64_t n = hit_points->size();
    const auto array = [&](auto* values, const char* what) -> absl::Status {
        if (!in.Array(values, n) || values->size() != n)
            return Corrupt(absl::StrCat(what, ": not one per hit point"));
        return absl::OkStatus();
    };
    for (absl::Status status :
         {array(&e.points_, "N, R, tau"), array(&e.direct_sum_, "direct sums"),
          array(&e.flux_even_, "even flux"), array(&e.direct_even_, "even direct sums"),
          array(&e.counts_, "gather counts")})
        if (!status.ok()) return status;
    uint8_t light_reached = 0, epoch_light_reached = 0;
    if (!(in.Value(&e.epoch_) && in.Value(&e.photons_emitted_) &&
          in.Value(&e.photons_emitted_even_) && in.Value(&e.nonfinite_discarded_) &&
          in.Value(&light_reached) && in.Value(&epoch_light_reached) &&
          in.Value(&e.batches_folded_)))
        return Corrupt("truncated counters");
    e.light_reached_ = light_reached != 0;
    e.epoch_light_reached_ = epoch_light_reached != 0;
    if (e.batches_folded_ >= settings.layout.batches_per_epoch)
        return Corrupt("more batches folded than an epoch has");
    for (absl::Status status :
         {array(&e.epoch_photons_, "epoch photons"),
          array(&e.epoch_inner_photons_, "epoch inner photons"),
          array(&e.epoch_flux_, "epoch flux"), array(&e.epoch_flux_even_, "epoch even flux"),
          array(&e.epoch_direct_, "epoch direct light")})
        if (!status.ok()) return status;
    if (!(in.Value(&e.epoch_photons_emitted_) && in.Value(&e.epoch_photons_emitted_even_) &&
          in.Value(&e.epoch_nonfinite_discarded_)))
        return Corrupt("truncated epoch counters");
    e.hit_points_ = std::move(hit_points);
    return estimate;
}

}  // namespace pf
