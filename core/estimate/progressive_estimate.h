// The coordinator-side state of one render: the hit points photons gather at and, per hit
// point, the progressive estimate (N, R, tau); per pixel, the running sums of emission and
// direct light, which every epoch samples afresh at the camera samples of its own camera pass
// (stratified across epochs: PixelSampler), so that what photons do not carry -- the emission
// the camera sees and direct light, with their sharp edges -- converges to the pixel's
// integral. Folds each epoch's batch results in batch-index order, one at a time as they
// become available, updates the estimate at the epoch's end and resolves the current image.
// Not thread-safe; its methods use the calling TBB arena for data-parallel loops,
// deterministically.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"
#include "core/camera/camera_pass.h"
#include "core/estimate/estimate.h"
#include "core/estimate/estimator.h"
#include "core/film/image.h"
#include "core/job/batch.h"
#include "core/job/job_spec.h"
#include "core/scene/scene.h"
#include "core/util/byte_stream.h"

namespace pf {

// The current epoch's photons at a hit point: all of them (M) and those within R / sqrt(2),
// and the same of the even-numbered batches alone (the bias estimate's two independent halves).
struct EpochPhotons {
    uint64_t all = 0, inner = 0, all_even = 0, inner_even = 0;
};

// A hit point's photon counts as EpochPhotons, over the merged epochs, shrunk with tau so that
// they count photons within the current radius.
struct GatherCounts {
    double all = 0, inner = 0, all_even = 0, inner_even = 0;

    // Adds an epoch's photons and shrinks the sums by the epoch's ratio R'^2 / R^2. The inner
    // photons count times `inner_scale`, the ratio of the surface within R to twice that within
    // R / sqrt(2) (1 on a surface that fills the disc), so that their expected share is 1/2
    // wherever the density is flat.
    void Fold(const EpochPhotons& epoch, double shrink, double inner_scale = 1.0) {
        all = (all + static_cast<double>(epoch.all)) * shrink;
        inner = (inner + static_cast<double>(epoch.inner) * inner_scale) * shrink;
        all_even = (all_even + static_cast<double>(epoch.all_even)) * shrink;
        inner_even = (inner_even + static_cast<double>(epoch.inner_even) * inner_scale) * shrink;
    }
};

// The bounds of a balanced estimate's ratio (EstimateSettings::balanced): below 1, so radii
// always shrink and the estimate stays consistent; not so far below alpha that an estimate
// that overrates its bias shrinks for good what it cannot grow back (0.4 did on caustic-glass,
// docs/integrators.md).
inline constexpr double kBalancedAlphaLeast = 0.55, kBalancedAlphaMost = 0.95;

struct EstimateSettings {
    double alpha = kDefaultAlpha;  // radius reduction ratio, (0, 1]
    // Each epoch's ratio chosen from the estimate's own error (BalancedAlpha), `alpha` where
    // bias and noise balance; otherwise `alpha` every epoch.
    bool balanced = false;
    double initial_radius = 0;  // R0, world units, > 0 (the median where each point has its own)
    int samples_per_pixel = 4;  // k: camera paths per pixel (the resolve divides by it)
    BatchLayout layout;
    double min_radius = 0;  // radii shrink no further (ShrinkRatio), world units, <= R0
    // Stochastic progressive photon mapping: photons gather at each epoch's camera pass (N, R,
    // tau kept per slot, pixel * k + sample). Otherwise (ppm) at one set of hit points for the
    // whole render, traced once, splitting at glass.
    bool stochastic = false;
    // Reverse photon mapping (stochastic, alpha 1): each camera sample's final-gather rays,
    // each a slot after the sample's own (CameraPassSettings::gather_rays). 0: none.
    uint32_t gather_rays = 0;
    // The slots a camera sample of an epoch's pass keeps.
    uint64_t SlotsPerSample() const { return 1 + uint64_t(gather_rays); }
};

// The estimator's settings, R0 from the scene (pbrt's sppm "radius") or else the camera pass
// where not given; sppm and rpm stochastic, rpm's alpha 1 with its gather rays. `scene_name` names
// the scene in the warning for a camera that sees no diffuse surface.
EstimateSettings EstimateFor(const JobSpec& spec, const CameraPassResult& camera_pass,
                             const Scene& scene, const std::string& scene_name);

class ProgressiveEstimate final : public Estimate {
public:
    // `camera_pass`: the hit points photons gather at (for sppm, epoch 0's pass); sppm's and
    // rpm's later passes come from `next_passes` (ppm's from its batches, BatchResult::emission:
    // none given). `initial_radii`: R0 of each hit point (sppm: of each slot), world units
    // (DensityInitialRadii), raised to the settings' min_radius; empty: the pass's radii (rpm's:
    // CameraPassResult::radius), else the settings' initial_radius for all.
    ProgressiveEstimate(CameraPassResult camera_pass, const EstimateSettings& settings,
                        EpochCameraPass next_passes, std::span<const float> initial_radii = {});
    // An sppm or rpm estimate restored by Load needs its camera passes again.
    void SetEpochCameraPass(EpochCameraPass next_passes) { next_passes_ = std::move(next_passes); }

    std::span<const HitPoint> HitPoints() const { return by_pixel_->points; }
    // The same hit points, shared with whoever needs them past this object's life.
    std::shared_ptr<const std::vector<HitPoint>> SharedHitPoints() const override {
        return by_pixel_->owner;
    }
    const PointEstimate& Point(size_t hit_point) const { return points_[hit_point]; }
    const EstimateSettings& Settings() const { return settings_; }
    Integrator Kind() const override {
        if (!settings_.stochastic) return Integrator::kPpm;
        return settings_.gather_rays > 0 ? Integrator::kRpm : Integrator::kSppm;
    }
    // The slots of the current epoch's camera pass (pixels x EpochCameraSamples x
    // SlotsPerSample), which the batches' direct-light slices index.
    uint64_t ItemCount() const override { return epoch_direct_.size(); }
    uint64_t Epoch() const override {
        return epoch_;
    }  // the next epoch to merge; also epochs merged
    uint64_t PhotonsEmitted() const override { return photons_emitted_; }  // over the merged epochs
    // Each epoch's pass, and ppm's fixed hit points' paths once.
    uint64_t CameraSamples() const override {
        const uint64_t fixed = settings_.stochastic ? 0 : uint64_t(settings_.samples_per_pixel);
        return direct_sum_.size() * (fixed + MergedSamples(0) + MergedSamples(1));
    }
    double InitialRadius() const override { return settings_.initial_radius; }
    // Photon paths and direct samples the batches dropped for NaN or Inf, over the merged
    // epochs (BatchResult::nonfinite_discarded); should be 0.
    uint64_t NonfiniteDiscarded() const override { return nonfinite_discarded_; }
    // Whether any photon or direct-light sample has reached any hit point in the merged epochs:
    // false for a light shut inside a closed object, or a camera that sees only what no light
    // reaches (the image is then emission only).
    bool LightReachedAnything() const override { return light_reached_; }

    // This epoch's squared search radii, one per hit point, and the edges of their surfaces
    // within them (SurfaceExtent::Edges; none where no pass probed them), for the photon pass.
    GatherRegions Regions() const override;
    // The batches of the current epoch, in batch-index order.
    std::vector<BatchSpec> EpochBatches() const override;
    // ppm: its SlicePixels of the epoch's pass and their fixed hit points.
    std::pair<uint64_t, uint64_t> EmissionShape(const BatchSpec& spec) const override;
    // Adds the next batch of the current epoch to the epoch's sums: batches must come in
    // batch-index order, so the sums are the same whoever ran them and whenever they arrived.
    // ppm's batches bring the epoch's emission pass too, each its pixels' (EmissionShape).
    void FoldBatch(const BatchResult& result) override;
    uint32_t BatchesFolded() const override { return batches_folded_; }
    // Once every batch of the epoch is folded: updates N, R, tau and starts the next epoch.
    void FinishEpoch() override;
    // The image as of the last merged epoch: per pixel, the mean emission and direct light
    // over the merged epochs' camera samples, and tau / (pi R^2 N_emitted) of each of its hit
    // points times its share of the pixel (Share: 1/k for sppm's).
    Image Resolve() const override;
    // The error of Resolve()'s image. Variance: from the even and odd half-estimates. Bias:
    // a disc estimate's bias grows as R^2 (radiance locally quadratic), so the estimate from
    // the inner disc of half the area has half the bias, and bias = 2 (L - L_inner), with
    // L_inner / L taken as the photon density ratio 2 inner / all (docs/convergence.md).
    ErrorEstimate EstimateError() const override;

    // The whole state, at an epoch's end or between folds, for a checkpoint: with the hit
    // points, or (FixedPart::kApart, ppm) without them, SaveFixed having saved them once. Load
    // restores it bit for bit, so folding the rest of the epochs gives the image an
    // uninterrupted render gives; DATA_LOSS naming what is wrong when the bytes cannot be such
    // a state, or `fixed` (SaveFixed's bytes, for a state without hit points) is missing or
    // not its own (estimate_state.cpp).
    using Estimate::Save;
    void Save(ByteWriter& out, FixedPart fixed) const override;
    bool SaveFixed(ByteWriter& out) const override;  // ppm's hit points and their extents
    static absl::StatusOr<std::unique_ptr<ProgressiveEstimate>> Load(ByteReader& in,
                                                                     ByteReader* fixed = nullptr);

private:
    ProgressiveEstimate() = default;

    // sppm, rpm: takes the epoch's pass as it begins, its hit points and emission.
    void BeginEpochPass(CameraPassResult camera_pass);
    // Holds `hit_points` and indexes them by pixel (by_pixel_).
    void SetHitPoints(std::shared_ptr<const std::vector<HitPoint>> hit_points);
    // rpm: each slot's radius for the epoch beginning (CameraPassResult::radius; 0 keeps it).
    // Its radius is not its own: the slot moved, and its place and kind call for another. A
    // slot's sums are rescaled to count what the new disc holds (tau R'^2 / R^2, as a shrink
    // does), so its estimate, tau / (pi R^2 N_emitted), is the sum of each epoch's photons
    // over that epoch's disc.
    void TakeSlotRadii(std::span<const float> radii);
    // Calls visit(i) for each hit point i of pixel p, in index order.
    template <typename Visit>
    void ForEachHitPointOf(size_t p, Visit&& visit) const {
        by_pixel_->ForEachOf(p, std::forward<Visit>(visit));
    }
    // Hit point i's share of its pixel, per channel, by which its photon estimate counts in
    // the pixel: for ppm, the weight of the merged epochs' camera samples it stands for
    // (`coverage`: coverage_sum_, or coverage_even_ for the even epochs) over those samples'
    // count `samples` and its own weight (CameraPassResult::coverage); 1/k for sppm's slots and
    // before the first epoch is merged.
    Rgbd Share(size_t i, const std::vector<Rgbd>& coverage, double samples) const;
    // Calls block(index, begin, end) for the pixels [begin, end) of each block of kPixelBlock,
    // in parallel: sums per pixel, and per block, are the same on any number of threads.
    template <typename Block>
    void ForEachPixelBlock(Block&& block) const;
    static constexpr size_t kPixelBlock = 1024;
    // The error estimate's sums over pixels and channels (samples: their count; 0 where
    // unknown): the squared error and its relative form, the photon part's alone, and the
    // squared bias (less its noise, not clamped) in both forms.
    struct ErrorSums {
        double squared = 0, relative = 0, photon_squared = 0, bias_squared = 0, bias_relative = 0,
               samples = 0;
    };
    ErrorSums SumErrors() const;
    // The ratio the epoch's photons shrink radii by. Balanced: a disc estimate's squared bias
    // grows as R^4 and its variance falls as 1 / R^2, so their sum is least where the squared
    // bias is half the variance. With r the merged epochs' estimated squared bias over half the
    // photon part's variance, summed over the image (emission and direct light do not depend
    // on R; absolute, not relative, so that r is the same for a light a billion times
    // brighter), alpha = 1 - (1 - settings.alpha) sqrt(r) within [kBalancedAlphaLeast,
    // kBalancedAlphaMost]: the settings' ratio at balance, which keeps it (at 2/3 both fall as
    // N^(-2/3): kDefaultAlpha), radii shrinking faster where bias weighs more and
    // slower where noise does. A function of the merged state alone, so a restored checkpoint
    // and every thread count choose alike. Unbalanced, or while the error is unknown (the first
    // two epochs): the settings' alpha.
    double BalancedAlpha() const;
    // Epoch `epoch`'s camera samples a pixel (EpochCameraSamples).
    EpochSamples EpochPass(uint64_t epoch) const;
    // Camera samples a pixel over the merged epochs of one parity (0: the even, 1: the odd).
    uint64_t MergedSamples(uint64_t parity) const;
    // Pixel p's mean emission and direct light over the merged epochs' camera samples.
    Rgbd EmissionAndDirect(size_t p) const;

    // The hit points photons gather at, by pixel; ppm's are given to its emission passes.
    std::shared_ptr<const PixelHitPoints> by_pixel_;
    // How far each hit point's surface reaches (CameraPassResult::extent): an epoch's photons
    // count over the area of that surface within R. Empty: every surface fills its disc.
    std::vector<SurfaceExtent> extent_;
    // ppm's, per fixed hit point: the weights of the camera samples it stands for, summed over
    // the merged epochs and over the even ones, and the current epoch's pass's apart
    // (CameraPassResult::coverage); empty for sppm.
    std::vector<Rgbd> coverage_sum_, coverage_even_;
    std::vector<Rgb> epoch_coverage_;
    // Per pixel, sums over the merged epochs' camera samples of the emission seen and of the
    // direct light, with those of the even epochs apart; the current epoch's emission and
    // direct samples (per slot) apart.
    std::vector<Rgbd> emission_sum_, emission_even_;
    std::vector<Rgbd> direct_sum_, direct_even_;
    Image epoch_emission_;
    EpochCameraPass next_passes_;
    EstimateSettings settings_;
    std::vector<PointEstimate> points_;
    // The even half-estimate: tau of the even-numbered batches' photons (shrunk with the same
    // ratios as tau); the odd half is the rest.
    std::vector<Rgbd> flux_even_;
    std::vector<GatherCounts> counts_;  // for the bias estimate
    uint64_t epoch_ = 0;
    uint64_t photons_emitted_ = 0;
    uint64_t photons_emitted_even_ = 0;
    uint64_t nonfinite_discarded_ = 0;
    bool light_reached_ = false, epoch_light_reached_ = false;
    uint32_t batches_folded_ = 0;  // of the current epoch
    // The current epoch's sums (M and Phi_M per hit point) and direct samples, apart from the
    // merged state so that Resolve() between folds shows the last merged epoch exactly.
    std::vector<EpochPhotons> epoch_photons_;
    std::vector<Rgbd> epoch_flux_;
    std::vector<Rgbd> epoch_flux_even_;
    std::vector<Rgb> epoch_direct_;  // per slot of the epoch's pass
    uint64_t epoch_photons_emitted_ = 0;
    uint64_t epoch_photons_emitted_even_ = 0;
    uint64_t epoch_nonfinite_discarded_ = 0;
};

}  // namespace pf
