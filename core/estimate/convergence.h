// The convergence log of a render: where its error stood after every merged epoch, estimated
// from the half-estimates and, when a reference image was given, measured against it. What
// `--report DIR` turns into convergence.csv and a log-log plot (docs/convergence.md).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "core/estimate/progressive_estimate.h"
#include "core/film/image_metrics.h"

namespace pf {

struct ConvergencePoint {
    double seconds = 0;  // since the job was submitted, camera pass included
    uint64_t epochs = 0, photons = 0;
    std::optional<ErrorEstimate> estimated;   // from the half-estimates, once known
    std::optional<ImageDifference> measured;  // against the reference, when there is one
    uint64_t pixels = 0;                      // of the image, for the non-finite fraction
    uint64_t camera_samples = 0;              // camera paths traced (Estimate::CameraSamples)
};

// A job's points, bounded: past kMaxPoints it keeps every second one and records only every
// second epoch from then on (then every fourth, ...), so a job of any length holds at most
// kMaxPoints + 1 points, spread over its whole run, and always its latest epoch.
class ConvergenceLog {
public:
    static constexpr size_t kMaxPoints = 4096;
    void Add(const ConvergencePoint& point);
    const std::vector<ConvergencePoint>& Points() const { return points_; }

private:
    std::vector<ConvergencePoint> points_;
    uint64_t stride_ = 1;             // epochs between the points kept
    bool latest_off_stride_ = false;  // the last point is only there as the latest
};

// y = scale * x^slope, fitted by least squares on log(y) against log(x).
struct PowerLaw {
    double slope = 0, log_scale = 0;
};
// Over the pairs where both are > 0 and finite; none when fewer than two such pairs exist or
// every x is the same.
std::optional<PowerLaw> FitPowerLaw(std::span<const double> x, std::span<const double> y);

// The fits of one log: RMSE against seconds and against photons, measured (against the
// reference) and estimated, over the points past the first `kFitSkipEpochs` epochs.
struct ConvergenceFits {
    std::optional<PowerLaw> measured_vs_seconds, measured_vs_photons;
    std::optional<PowerLaw> estimated_vs_seconds, estimated_vs_photons;
};
inline constexpr uint64_t kFitSkipEpochs = 3;  // the estimate is unknown before epoch 2
// The "photons" fits are against camera samples for a log without photons (WorkIsCameraSamples).
ConvergenceFits FitConvergence(std::span<const ConvergencePoint> points);
// Whether a log's work is camera samples rather than photons: photons that do not grow from
// its first point to its last, as for the integrators that render pixels (path traces none,
// pm all of its maps' before the first epoch).
bool WorkIsCameraSamples(std::span<const ConvergencePoint> points);

// convergence.csv: one row per point; columns seconds, epochs, photons, estimated_rmse,
// estimated_rel_error, estimated_bias_rmse, reference_rmse, reference_rel_mse, reference_rel_error,
// reference_nonfinite_fraction (empty where unknown). Written to a temporary file and
// renamed, so a reader never sees half a file.
std::string ConvergenceCsv(std::span<const ConvergencePoint> points);
absl::Status WriteConvergenceCsv(const std::string& path, std::span<const ConvergencePoint> points);

}  // namespace pf
