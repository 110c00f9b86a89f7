// Averaging pixel samples over epochs, and saving that state for checkpoints.
#include "core/estimate/pixel_estimate.h"

#include <algorithm>

#include "absl/strings/str_cat.h"
#include "core/job/job_spec.h"
#include "core/util/check.h"
#include "core/util/packed_arrays.h"

namespace pf {
namespace {

constexpr uint32_t kMagic = kPixelEstimateMagic;
// 2: settings and counters first, then the arrays packed (core/util/packed_arrays.h).
constexpr uint32_t kVersion = 2;

absl::Status Corrupt(const std::string& what) {
    return absl::DataLossError(absl::StrCat("pixel estimate: ", what));
}

}  // namespace

PixelEstimate::PixelEstimate(const PixelEstimateSettings& settings) : settings_(settings) {
    PF_CHECK(settings.width > 0 && settings.height > 0 && settings.samples_per_pixel > 0 &&
             settings.batches_per_epoch > 0);
    const size_t pixels = size_t(settings.width) * size_t(settings.height);
    sum_.assign(pixels, Rgbd(0.0));
    sum_even_.assign(pixels, Rgbd(0.0));
    epoch_samples_.assign(pixels, Rgb(0.0f));
}

std::shared_ptr<const std::vector<HitPoint>> PixelEstimate::SharedHitPoints() const {
    static const auto none = std::make_shared<const std::vector<HitPoint>>();
    return none;
}

std::vector<BatchSpec> PixelEstimate::EpochBatches() const {
    const BatchLayout layout{0, settings_.batches_per_epoch};
    std::vector<BatchSpec> specs;
    for (uint32_t j = 0; j < settings_.batches_per_epoch; ++j)
        specs.push_back(MakeBatchSpec(layout, epoch_, j, static_cast<uint32_t>(sum_.size())));
    return specs;
}

void PixelEstimate::FoldBatch(const BatchResult& result) {
    const BatchSpec expected = MakeBatchSpec({0, settings_.batches_per_epoch}, epoch_,
                                             batches_folded_, static_cast<uint32_t>(sum_.size()));
    PF_CHECK(result.spec.index == expected.index &&
             result.spec.sample_begin == expected.sample_begin &&
             result.spec.sample_end == expected.sample_end &&
             result.samples.size() == expected.sample_end - expected.sample_begin);
    std::copy(result.samples.begin(), result.samples.end(),
              epoch_samples_.begin() + expected.sample_begin);
    epoch_nonfinite_discarded_ += result.nonfinite_discarded;
    ++batches_folded_;
}

void PixelEstimate::FinishEpoch() {
    PF_CHECK(batches_folded_ == settings_.batches_per_epoch);
    const bool even = epoch_ % 2 == 0;
    for (size_t p = 0; p < sum_.size(); ++p) {
        const Rgbd sample(epoch_samples_[p]);
        sum_[p] += sample;
        if (even) sum_even_[p] += sample;
        light_reached_ = light_reached_ || !IsBlack(epoch_samples_[p]);
        epoch_samples_[p] = Rgb(0.0f);
    }
    nonfinite_discarded_ += std::exchange(epoch_nonfinite_discarded_, 0);
    batches_folded_ = 0;
    ++epoch_;
}

Image PixelEstimate::Resolve() const {
    Image image(settings_.width, settings_.height);
    if (epoch_ == 0) return image;
    const double inverse_epochs = 1.0 / static_cast<double>(epoch_);
    for (size_t p = 0; p < sum_.size(); ++p) image.pixels[p] = Rgb(sum_[p] * inverse_epochs);
    return image;
}

ErrorEstimate PixelEstimate::EstimateError() const {
    ErrorEstimate error;
    const double even = static_cast<double>((epoch_ + 1) / 2),
                 odd = static_cast<double>(epoch_ / 2);
    if (!(odd > 0)) return error;
    const double all = even + odd;
    const double variance_scale = even * odd / (all * all);
    double squared = 0, relative = 0;
    for (size_t p = 0; p < sum_.size(); ++p)
        for (int c = 0; c < 3; ++c) {
            const double mean_even = sum_even_[p][c] / even,
                         mean_odd = (sum_[p][c] - sum_even_[p][c]) / odd;
            AddHalfVariance(sum_[p][c] / all, mean_even - mean_odd, variance_scale, &squared,
                            &relative);
        }
    const double samples = 3.0 * static_cast<double>(sum_.size());
    error.known = true;
    error.rmse = std::sqrt(squared / samples);
    error.rel_mse = relative / samples;
    return error;
}

void PixelEstimate::Save(ByteWriter& out, FixedPart /*fixed: it has none*/) const {
    out.Value(kMagic);
    out.Value(kVersion);
    out.Value(settings_.integrator);
    for (int value : {settings_.width, settings_.height, settings_.samples_per_pixel})
        out.Value(value);
    out.Value(settings_.batches_per_epoch);
    out.Value(settings_.map_photons);
    for (uint64_t value : {epoch_, nonfinite_discarded_, epoch_nonfinite_discarded_})
        out.Value(value);
    out.Value(batches_folded_);
    out.Value(static_cast<uint8_t>(light_reached_));
    const PackedArray arrays[] = {sum_, sum_even_, epoch_samples_};
    WritePacked(out, arrays);
}

absl::StatusOr<std::unique_ptr<PixelEstimate>> PixelEstimate::Load(ByteReader& in) {
    std::unique_ptr<PixelEstimate> estimate(new PixelEstimate());
    PixelEstimate& e = *estimate;
    uint32_t magic = 0, version = 0;
    if (!in.Value(&magic) || magic != kMagic) return Corrupt("not a pixel estimate");
    if (!in.Value(&version) || version != kVersion)
        return Corrupt(
            absl::StrCat("format version ", version, "; this build reads version ", kVersion));
    PixelEstimateSettings& s = e.settings_;
    if (!(in.Value(&s.integrator) && in.Value(&s.width) && in.Value(&s.height) &&
          in.Value(&s.samples_per_pixel) && in.Value(&s.batches_per_epoch) &&
          in.Value(&s.map_photons)))
        return Corrupt("truncated settings");
    if (!((s.integrator == Integrator::kPath || s.integrator == Integrator::kPm) && s.width >= 1 &&
          s.width <= 32768 && s.height >= 1 && s.height <= 32768 && s.samples_per_pixel >= 1 &&
          s.samples_per_pixel <= 1024 && s.batches_per_epoch >= 1 &&
          s.batches_per_epoch <= kMaxBatchesPerEpoch))
        return Corrupt("settings out of range");
    const uint64_t pixels = uint64_t(s.width) * uint64_t(s.height);
    if (pixels > kMaxHitPoints) return Corrupt("more pixels than a job may have");
    uint8_t light_reached = 0;
    if (!(in.Value(&e.epoch_) && in.Value(&e.nonfinite_discarded_) &&
          in.Value(&e.epoch_nonfinite_discarded_) && in.Value(&e.batches_folded_) &&
          in.Value(&light_reached)))
        return Corrupt("truncated counters");
    if (e.batches_folded_ >= s.batches_per_epoch)
        return Corrupt("more batches folded than an epoch has");
    e.light_reached_ = light_reached != 0;
    for (auto* values : {&e.sum_, &e.sum_even_})
        if (!ReadPacked(in, pixels, values)) return Corrupt("sums: not one per pixel");
    if (!ReadPacked(in, pixels, &e.epoch_samples_))
        return Corrupt("epoch samples: not one per pixel");
    return estimate;
}

}  // namespace pf
