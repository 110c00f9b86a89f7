// What a render asks for, the same for `photonfarm render` and a farm job: film size, hit
// points per pixel, seed, estimator settings, batch layout, budget. With the checks and the
// defaults derived from the scene, in one place for both.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/job/batch.h"
#include "core/job/integrator.h"
#include "core/scene/scene.h"

namespace pf {

// The radius-reduction ratio alpha where bias and noise balance: the asymptotically optimal
// 2/3 derived by Kaplanyan & Dachsbacher 2013 ("Adaptive Progressive Photon Mapping",
// section 5).
inline constexpr double kDefaultAlpha = 2.0 / 3.0;

struct JobSpec {
    Integrator integrator = Integrator::kPpm;
    int width = 0, height = 0;  // 0: 512 wide, or derived from the other and the camera's aspect
    // k: hit points per pixel (ppm), per pixel and epoch (sppm), camera samples per pixel and
    // epoch (path, pm).
    int samples_per_pixel = 4;
    uint64_t seed = 1;  // the same seed and layout give the same image
    // Renders with the same seed and another photon stream share their hit points (the camera
    // pass) but trace independent photons and light samples: how a reference for the error
    // against run time is made (docs/convergence.md). 0: the stream of `seed` itself.
    uint64_t photon_stream = 0;
    // ppm, sppm: the radius-reduction ratio of every epoch, in (0, 1]; 0 (the default):
    // balanced, each epoch's chosen from the estimated bias and noise about kDefaultAlpha
    // (EstimateSettings::balanced).
    double alpha = 0;
    // ppm, sppm: auto is resolved by the coordinator before any worker sees the job.
    PhotonTracing photon_tracing = PhotonTracing::kAuto;
    double initial_radius = 0;  // R0, world units, for all; 0: each its own (DensityInitialRadii)
    BatchLayout layout;
    uint64_t photon_budget = 0;  // stop after the epoch that reaches it (0: no limit); ppm, sppm
    uint64_t epoch_budget = 0;   // stop after this many epochs (0: no limit)
    double seconds_budget = 0;   // stop after the epoch that reaches it (0: no limit)
    // Stop after the epoch whose estimated relative error (ErrorEstimate::RelativeError) is
    // at most this (0: no target).
    double target_error = 0;
    // No budget: the job runs until it is cancelled (or the render stopped). A job with no
    // budget must say so here, so that no budget is never a slip.
    bool until_cancelled = false;
    PhotonMapSettings photon_map;  // pm only
    // An environment light in place of the scene's own; `environment.file` names a file of
    // the scene's bundle (BundleEnvironment puts it there).
    EnvironmentSettings environment;
    // Which of the scene's cameras renders: its number (scene order) or name; empty: the first.
    std::string camera;
    // The most surfaces a path may scatter at, as pbrt's maxdepth counts them: a camera path
    // scatters at most this many times (the light it then meets still counts), a photon
    // reaches at most this many surfaces. 0: no limit but Russian roulette (unbiased).
    int max_depth = 0;
};

// The depth limit `max_depth` puts on a loop whose own limit is `hard_limit`.
inline int DepthLimit(int max_depth, int hard_limit) {
    return max_depth > 0 && max_depth < hard_limit ? max_depth : hard_limit;
}
// The most a job's max_depth may be.
inline constexpr int kMaxDepthSetting = 1 << 16;

// Hit points cost about this much memory each across the estimate (~140 bytes, 72 more for
// the even half-estimate of the error, 56 for the bias estimate's counts, 60 for ppm's shares
// of their pixels and 36 for how far their surfaces reach), the epoch's gather regions (12
// bytes, and 8 in the grid), the grid (8 entries of 24 bytes) and one tally accumulator per
// thread (20 bytes): 2^25 of them (4K at 4 hit points per pixel) take ~20 GB.
inline constexpr uint64_t kMaxHitPoints = uint64_t{1} << 25;
inline constexpr uint64_t kBytesPerHitPoint = 608;

// Limits on the batch layout: a batch's photon count fits the wire's uint32 with room to
// spare; an epoch's batches are slots the coordinator tracks one by one.
inline constexpr uint32_t kMaxPhotonsPerBatch = 1u << 26;
inline constexpr uint32_t kMaxBatchesPerEpoch = 1u << 16;

// The largest budgets a job may ask for: past them a budget is a mistake (a negative count
// read as unsigned), not a render; a job that should run on says --until-cancelled.
inline constexpr uint64_t kMaxPhotonBudget = 1'000'000'000'000'000;  // 1000T: months of a farm
inline constexpr uint64_t kMaxEpochBudget = uint64_t{1} << 40;
inline constexpr double kMaxSecondsBudget = 1e8;  // three years
// A farm job's priority (higher runs first) lies in [-kMaxJobPriority, kMaxJobPriority].
inline constexpr int kMaxJobPriority = 1'000'000;
// How errors name a setting: as `photonfarm render`'s flags or as the farm's message fields.
enum class SettingNames { kFlags, kFields };

// Limits on classic photon mapping's settings (memory is checked apart, PhotonMapBytes).
inline constexpr uint64_t kMaxMapPhotons = uint64_t{1} << 34;
inline constexpr uint32_t kMaxNearestPhotons = 4096;
inline constexpr uint32_t kMaxFinalGatherRays = 4096;

// Every field in range and a budget given (or until_cancelled, and then none); errors name the
// flag or field and its range.
absl::Status CheckJobSpec(const JobSpec& spec, SettingNames names = SettingNames::kFlags);
absl::Status CheckPhotonMapSettings(const PhotonMapSettings& settings, SettingNames names);
absl::Status CheckEnvironmentSettings(const EnvironmentSettings& settings, SettingNames names);
// ppm's first epoch where its layout is left open: 2^18 photons, a sixteenth of a full epoch
// (a tenth of a second on two cores), so that the first image comes soon; epochs then double
// up to the full 2^22.
inline constexpr uint64_t kFirstEpochPhotons = uint64_t{1} << 18;

// The layout of `spec`'s epochs on a film of `pixels`, where its counts are left open (0):
//   sppm, rpm: one photon per camera sample of the epoch (pixels x k), in batches of 2^15
//         photons (at least the default 8 of them); pbrt-v4's sppm also shoots about one photon
//         a pixel an iteration. On cornell-box at 256x256, 20 s on two cores: RMSE 0.0033 at
//         k = 4, 0.0028 at k = 16, where 2^22 photons an epoch (the ppm default) gave 0.0060.
//         rpm at 128x128, 10 s: relative error 1.4% against a path-traced reference, where
//         2^22 photons an epoch gave 4.4% (its epochs' gather rays average the photons' noise
//         over each hemisphere: camera samples, not photons, are what it lacks).
//   the others: 2^19 photons a batch, 8 batches an epoch; ppm's first epochs grow from
//         kFirstEpochPhotons where both counts are left open.
// first_epoch_photons left open is otherwise a full epoch (no growing epochs), and is at most
// one. A count given stays; the result has every count in range.
BatchLayout ResolvedLayout(const JobSpec& spec, uint64_t pixels);

// The camera samples of an epoch's pass in a photon mapper: per pixel, and the index of the
// first in each pixel's sequence of the epoch's parity (PixelSampler::InEpoch: the even
// epochs' samples and the odd epochs' are two sequences, each counting on over its epochs).
// sppm's pass traces the epoch's k hit points a pixel; ppm's passes (its emission, and the
// slots where workers sample direct light) take the power of two nearest below one per two
// photons of the epoch, in [1, 64], since ppm's k are the fixed hit points photons gather at:
// a growing epoch takes fewer. Sampled once a pixel an epoch, emission and direct light
// dominated ppm's error (cornell-box at 256x256, 20 s on two cores: RMSE 0.021, the light's
// edges 0.25 of it; 16 samples an epoch 0.0028, 64 0.0022). `layout` resolved.
struct EpochSamples {
    int per_pixel = 1;
    uint64_t first = 0;
};
EpochSamples EpochCameraSamples(Integrator integrator, int samples_per_pixel,
                                const BatchLayout& layout, uint64_t pixels, uint64_t epoch);
// The same for a job whose film size is resolved.
EpochSamples EpochCameraSamples(const JobSpec& spec, uint64_t epoch);
// The most camera samples a pixel any epoch of the job takes (a full epoch's).
int MaxEpochSamplesPerPixel(const JobSpec& spec);
// The slots each camera sample of a photon mapper's epoch pass keeps (batches' direct-light
// slices index them): one, and rpm's gather rays besides (RpmGatherRays).
inline uint64_t SlotsPerCameraSample(const JobSpec& spec) {
    return spec.integrator == Integrator::kRpm ? 1 + uint64_t(RpmGatherRays(spec.photon_map)) : 1;
}

// The seed of the photon pass and direct light: `seed` itself for stream 0.
uint64_t PhotonSeed(const JobSpec& spec);
// The share of the budget spent, in [0, 1]; 1 ends the render after the current epoch.
// `estimated_error`: the current relative error estimate, if known yet. Toward a target error
// the share is (target / error)^2, since the squared error falls as 1 / photons.
double BudgetFraction(const JobSpec& spec, uint64_t photons, uint64_t epochs, double seconds,
                      std::optional<double> estimated_error);

}  // namespace pf
