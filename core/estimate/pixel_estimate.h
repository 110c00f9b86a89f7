// The estimate of the integrators that render pixels (path, pm): per pixel, the sum of one
// sample per epoch (each the mean of the pixel's camera samples), and the sum over even
// epochs for the error estimate. The image is the mean over merged epochs.
#pragma once

#include <cstdint>
#include <vector>

#include "core/estimate/estimate.h"
#include "core/math/vec3.h"

namespace pf {

// What a saved PixelEstimate starts with ("PFPX" in a little-endian file).
inline constexpr uint32_t kPixelEstimateMagic = 0x58504650;

struct PixelEstimateSettings {
    Integrator integrator = Integrator::kPath;
    int width = 0, height = 0;
    int samples_per_pixel = 1;       // camera samples per pixel per epoch
    uint32_t batches_per_epoch = 8;  // an epoch's pixels split into this many slices
    uint64_t map_photons = 0;        // pm: the photons its maps were built from, for the records
};

class PixelEstimate final : public Estimate {
public:
    explicit PixelEstimate(const PixelEstimateSettings& settings);

    const PixelEstimateSettings& Settings() const { return settings_; }

    Integrator Kind() const override { return settings_.integrator; }
    uint64_t ItemCount() const override { return sum_.size(); }
    uint64_t Epoch() const override { return epoch_; }
    uint64_t PhotonsEmitted() const override { return epoch_ > 0 ? settings_.map_photons : 0; }
    uint64_t CameraSamples() const override {
        return epoch_ * sum_.size() * uint64_t(settings_.samples_per_pixel);
    }
    uint64_t NonfiniteDiscarded() const override { return nonfinite_discarded_; }
    bool LightReachedAnything() const override { return light_reached_; }
    double InitialRadius() const override { return 0; }
    std::shared_ptr<const std::vector<HitPoint>> SharedHitPoints() const override;
    GatherRegions Regions() const override { return {}; }
    std::vector<BatchSpec> EpochBatches() const override;
    void FoldBatch(const BatchResult& result) override;
    uint32_t BatchesFolded() const override { return batches_folded_; }
    void FinishEpoch() override;
    Image Resolve() const override;
    // Variance from the even and odd epochs' halves; no bias term (the path tracer has none,
    // and classic photon mapping's, fixed by its maps, does not shrink with epochs: it is
    // measured against a reference, not estimated).
    ErrorEstimate EstimateError() const override;
    // No fixed part: every state is whole, whatever `fixed` asks.
    using Estimate::Save;
    void Save(ByteWriter& out, FixedPart fixed) const override;
    static absl::StatusOr<std::unique_ptr<PixelEstimate>> Load(ByteReader& in);

private:
    PixelEstimate() = default;

    PixelEstimateSettings settings_;
    std::vector<Rgbd> sum_, sum_even_;
    std::vector<Rgb> epoch_samples_;  // the current epoch's, apart until it is merged
    uint64_t epoch_ = 0;
    uint32_t batches_folded_ = 0;
    uint64_t nonfinite_discarded_ = 0, epoch_nonfinite_discarded_ = 0;
    bool light_reached_ = false;
};

}  // namespace pf
