// A progressive estimate saved and restored bit for bit, for the coordinator's checkpoints: its
// arrays packed (core/util/packed_arrays.h), and a ppm estimate's hit points, which never
// change, apart on request so that a job's checkpoints keep them once.
#include <cmath>

#include "absl/strings/str_cat.h"
#include "core/estimate/progressive_estimate.h"
#include "core/job/job_spec.h"
#include "core/util/packed_arrays.h"

namespace pf {
namespace {

constexpr uint32_t kMagic = 0x53455046;       // "PFES" in a little-endian file
constexpr uint32_t kFixedMagic = 0x50485046;  // "PFHP": the hit points kept apart
// 4: settings and counters first, then the arrays packed (core/util/packed_arrays.h), the hit
// points among them or kept apart (SaveFixed); emission and direct light summed per pixel over
// each epoch's camera pass, for ppm too. 5: ppm's epoch passes take their own camera samples a
// pixel (EpochSamplesPerPixel), not its k. 6: small epochs first (the layout's
// first_epoch_photons), emission and direct light summed over camera samples, not epochs.
// 7: whether alpha is balanced (EstimateSettings::balanced). 8: the bias estimate's counts
// of the even batches (GatherCounts), and the epoch's counts in one array (EpochPhotons).
// 9: ppm's fixed hit points' shares of their pixels (CameraPassResult::coverage). 10: how far
// each hit point's surface reaches (SurfaceExtent), where probed, with the hit points.
// 11: the photons each hit point gathers (HitPoint::gathers), and rpm's gather rays.
constexpr uint32_t kVersion = 11;

absl::Status Corrupt(const std::string& what) {
    return absl::DataLossError(absl::StrCat("estimate state: ", what));
}

// A ppm estimate's hit points as SaveFixed wrote them, with their surfaces' extents: `count`
// of them (of the extents, `extents`), all of `fixed`.
absl::Status LoadFixedHitPoints(ByteReader& fixed, uint64_t count, uint64_t extents,
                                std::vector<HitPoint>* hit_points,
                                std::vector<SurfaceExtent>* extent) {
    uint32_t magic = 0, version = 0;
    if (!fixed.Value(&magic) || magic != kFixedMagic)
        return Corrupt("its hit points kept apart are not hit points");
    if (!fixed.Value(&version) || version != kVersion)
        return Corrupt(absl::StrCat("its hit points kept apart are of format version ", version,
                                    "; this build reads version ", kVersion));
    if (!ReadPacked(fixed, count, hit_points) || !ReadPacked(fixed, extents, extent) ||
        !fixed.AtEnd())
        return Corrupt(absl::StrCat("its hit points kept apart are not its ", count));
    return absl::OkStatus();
}

}  // namespace

void ProgressiveEstimate::Save(ByteWriter& out, FixedPart fixed) const {
    // A stochastic estimate's hit points change every epoch: nothing of it is fixed.
    const bool hit_points_here = settings_.stochastic || fixed == FixedPart::kIncluded;
    out.Value(kMagic);
    out.Value(kVersion);
    const std::vector<HitPoint>& hit_points = *by_pixel_->owner;
    out.Value<uint64_t>(hit_points.size());
    out.Value(static_cast<uint8_t>(hit_points_here));
    out.Value(static_cast<uint8_t>(!extent_.empty()));
    out.Value(settings_.alpha);
    out.Value(settings_.initial_radius);
    out.Value(settings_.samples_per_pixel);
    out.Value(settings_.layout.photons_per_batch);
    out.Value(settings_.layout.batches_per_epoch);
    out.Value(settings_.layout.first_epoch_photons);
    out.Value(settings_.min_radius);
    out.Value(static_cast<uint8_t>(settings_.stochastic));
    out.Value(static_cast<uint8_t>(settings_.balanced));
    out.Value(settings_.gather_rays);
    out.Value(epoch_emission_.width);
    out.Value(epoch_emission_.height);
    for (uint64_t value : {epoch_, photons_emitted_, photons_emitted_even_, nonfinite_discarded_})
        out.Value(value);
    out.Value(static_cast<uint8_t>(light_reached_));
    out.Value(static_cast<uint8_t>(epoch_light_reached_));
    out.Value(batches_folded_);
    for (uint64_t value :
         {epoch_photons_emitted_, epoch_photons_emitted_even_, epoch_nonfinite_discarded_})
        out.Value(value);
    std::vector<PackedArray> arrays;
    // The hit points and their surfaces' extents, or (ppm, kept apart) neither.
    if (hit_points_here) arrays.push_back(hit_points), arrays.push_back(extent_);
    for (PackedArray array :
         {PackedArray(emission_sum_), PackedArray(emission_even_), PackedArray(direct_sum_),
          PackedArray(direct_even_), PackedArray(epoch_emission_.pixels),
          PackedArray(epoch_direct_), PackedArray(points_), PackedArray(flux_even_),
          PackedArray(counts_), PackedArray(epoch_photons_), PackedArray(epoch_flux_),
          PackedArray(epoch_flux_even_), PackedArray(coverage_sum_), PackedArray(coverage_even_),
          PackedArray(epoch_coverage_)})
        arrays.push_back(array);
    WritePacked(out, arrays);
}

bool ProgressiveEstimate::SaveFixed(ByteWriter& out) const {
    if (settings_.stochastic) return false;
    out.Value(kFixedMagic);
    out.Value(kVersion);
    const PackedArray fixed[] = {*by_pixel_->owner, extent_};
    WritePacked(out, fixed);
    return true;
}

absl::StatusOr<std::unique_ptr<ProgressiveEstimate>> ProgressiveEstimate::Load(ByteReader& in,
                                                                               ByteReader* fixed) {
    std::unique_ptr<ProgressiveEstimate> estimate(new ProgressiveEstimate());
    ProgressiveEstimate& e = *estimate;
    uint32_t magic = 0, version = 0;
    if (!in.Value(&magic) || magic != kMagic) return Corrupt("not an estimate");
    if (!in.Value(&version) || version != kVersion)
        return Corrupt(
            absl::StrCat("format version ", version, "; this build reads version ", kVersion));
    uint64_t n = 0;  // hit points
    uint8_t hit_points_here = 0, probed = 0;
    if (!in.Value(&n) || n > kMaxHitPoints || !in.Value(&hit_points_here) || !in.Value(&probed))
        return Corrupt("hit points");
    EstimateSettings& settings = e.settings_;
    uint8_t stochastic = 0, balanced = 0;
    if (!(in.Value(&settings.alpha) && in.Value(&settings.initial_radius) &&
          in.Value(&settings.samples_per_pixel) && in.Value(&settings.layout.photons_per_batch) &&
          in.Value(&settings.layout.batches_per_epoch) &&
          in.Value(&settings.layout.first_epoch_photons) && in.Value(&settings.min_radius) &&
          in.Value(&stochastic) && in.Value(&balanced) && in.Value(&settings.gather_rays)))
        return Corrupt("truncated settings");
    settings.stochastic = stochastic != 0;
    settings.balanced = balanced != 0;
    if (!(settings.alpha > 0 && settings.alpha <= 1 && settings.initial_radius > 0 &&
          std::isfinite(settings.initial_radius) && settings.min_radius >= 0 &&
          settings.min_radius <= settings.initial_radius && settings.samples_per_pixel > 0 &&
          settings.layout.photons_per_batch >= 1 &&
          settings.layout.photons_per_batch <= kMaxPhotonsPerBatch &&
          settings.layout.batches_per_epoch >= 1 &&
          settings.layout.batches_per_epoch <= kMaxBatchesPerEpoch &&
          settings.layout.first_epoch_photons <= settings.layout.PhotonsPerEpoch() &&
          settings.gather_rays <= kMaxFinalGatherRays &&
          (settings.gather_rays == 0 || settings.stochastic)))
        return Corrupt("settings out of range");
    int width = 0, height = 0;
    if (!(in.Value(&width) && in.Value(&height)) || width < 1 || height < 1 || width > 32768 ||
        height > 32768)
        return Corrupt("image size");
    const uint64_t pixels = uint64_t(width) * uint64_t(height);
    uint8_t light_reached = 0, epoch_light_reached = 0;
    if (!(in.Value(&e.epoch_) && in.Value(&e.photons_emitted_) &&
          in.Value(&e.photons_emitted_even_) && in.Value(&e.nonfinite_discarded_) &&
          in.Value(&light_reached) && in.Value(&epoch_light_reached) &&
          in.Value(&e.batches_folded_) && in.Value(&e.epoch_photons_emitted_) &&
          in.Value(&e.epoch_photons_emitted_even_) && in.Value(&e.epoch_nonfinite_discarded_)))
        return Corrupt("truncated counters");
    e.light_reached_ = light_reached != 0;
    e.epoch_light_reached_ = epoch_light_reached != 0;
    if (e.batches_folded_ >= settings.layout.batches_per_epoch)
        return Corrupt("more batches folded than an epoch has");
    // The current epoch's camera samples (sppm: its hit points; ppm: its direct-light slots).
    const uint64_t slots = pixels *
                           uint64_t(EpochCameraSamples(e.Kind(), settings.samples_per_pixel,
                                                       settings.layout, pixels, e.epoch_)
                                        .per_pixel) *
                           (1 + uint64_t(settings.gather_rays));
    if (slots > kMaxHitPoints) return Corrupt("more camera samples than a job may have");

    auto hit_points = std::make_shared<std::vector<HitPoint>>();
    if (hit_points_here == 0 && settings.stochastic)
        return Corrupt("a stochastic estimate's hit points kept apart");
    if (hit_points_here != 0 && fixed != nullptr)
        return Corrupt("hit points given apart to a state that holds its own");
    if (hit_points_here == 0 && fixed == nullptr)
        return Corrupt("its hit points are kept apart (SaveFixed) and were not given");
    const uint64_t extents = probed != 0 ? n : 0;
    if (hit_points_here != 0) {
        if (!ReadPacked(in, n, hit_points.get())) return Corrupt("hit points");
        if (!ReadPacked(in, extents, &e.extent_)) return Corrupt("surface extents");
    } else if (absl::Status status =
                   LoadFixedHitPoints(*fixed, n, extents, hit_points.get(), &e.extent_);
               !status.ok()) {
        return status;
    }
    for (const HitPoint& hit_point : *hit_points) {
        if (hit_point.pixel >= pixels) return Corrupt("a hit point lies outside the image");
        if (hit_point.gathers == 0 || (hit_point.gathers & ~kAllPhotons) != 0)
            return Corrupt("a hit point gathers no known photons");
    }
    if (settings.stochastic && n != slots)
        return Corrupt(
            "a stochastic estimate's hit points are not one per camera sample and gather ray");
    e.epoch_emission_ = Image(width, height);
    const uint64_t covered = settings.stochastic ? 0 : n;  // ppm's shares of pixels
    const auto array = [&](uint64_t count, const char* per, auto* values,
                           const char* what) -> absl::Status {
        if (!ReadPacked(in, count, values))
            return Corrupt(absl::StrCat(what, ": not one per ", per));
        return absl::OkStatus();
    };
    for (absl::Status status :
         {array(pixels, "pixel", &e.emission_sum_, "emission sums"),
          array(pixels, "pixel", &e.emission_even_, "even emission sums"),
          array(pixels, "pixel", &e.direct_sum_, "direct sums"),
          array(pixels, "pixel", &e.direct_even_, "even direct sums"),
          array(pixels, "pixel", &e.epoch_emission_.pixels, "epoch emission"),
          array(slots, "camera sample", &e.epoch_direct_, "epoch direct light"),
          array(n, "hit point", &e.points_, "N, R, tau"),
          array(n, "hit point", &e.flux_even_, "even flux"),
          array(n, "hit point", &e.counts_, "gather counts"),
          array(n, "hit point", &e.epoch_photons_, "epoch photon counts"),
          array(n, "hit point", &e.epoch_flux_, "epoch flux"),
          array(n, "hit point", &e.epoch_flux_even_, "epoch even flux"),
          array(covered, "fixed hit point", &e.coverage_sum_, "coverage"),
          array(covered, "fixed hit point", &e.coverage_even_, "even coverage"),
          array(covered, "fixed hit point", &e.epoch_coverage_, "epoch coverage")})
        if (!status.ok()) return status;
    e.SetHitPoints(std::move(hit_points));
    return estimate;
}

}  // namespace pf
