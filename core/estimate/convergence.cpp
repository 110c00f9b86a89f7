// Convergence log: slopes and the CSV.
#include "core/estimate/convergence.h"

#include <cmath>
#include <vector>

#include "absl/strings/str_format.h"
#include "core/util/file_io.h"

namespace pf {
namespace {

std::string Cell(const std::optional<double>& value) {
    return value ? absl::StrFormat("%.9g", *value) : "";
}

}  // namespace

void ConvergenceLog::Add(const ConvergencePoint& point) {
    if (latest_off_stride_) points_.pop_back();
    points_.push_back(point);
    latest_off_stride_ = point.epochs % stride_ != 0;
    if (points_.size() - latest_off_stride_ <= kMaxPoints) return;
    stride_ *= 2;
    const ConvergencePoint latest = points_.back();
    std::erase_if(points_, [&](const ConvergencePoint& p) { return p.epochs % stride_ != 0; });
    latest_off_stride_ = latest.epochs % stride_ != 0;
    if (latest_off_stride_) points_.push_back(latest);
}

std::optional<PowerLaw> FitPowerLaw(std::span<const double> x, std::span<const double> y) {
    double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (size_t i = 0; i < std::min(x.size(), y.size()); ++i) {
        if (!(x[i] > 0 && y[i] > 0 && std::isfinite(x[i]) && std::isfinite(y[i]))) continue;
        const double lx = std::log(x[i]), ly = std::log(y[i]);
        n += 1;
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
    }
    const double denominator = n * sxx - sx * sx;
    if (n < 2 || !(denominator > 1e-12 * n * sxx)) return std::nullopt;
    const double slope = (n * sxy - sx * sy) / denominator;
    return PowerLaw{slope, (sy - slope * sx) / n};
}

bool WorkIsCameraSamples(std::span<const ConvergencePoint> points) {
    return !points.empty() && points.front().photons == points.back().photons &&
           (points.back().photons == 0 || points.size() > 1);
}

ConvergenceFits FitConvergence(std::span<const ConvergencePoint> points) {
    std::vector<double> seconds, photons, measured, estimated;
    const bool samples = WorkIsCameraSamples(points);
    for (const ConvergencePoint& point : points) {
        if (point.epochs <= kFitSkipEpochs) continue;
        seconds.push_back(point.seconds);
        photons.push_back(static_cast<double>(samples ? point.camera_samples : point.photons));
        measured.push_back(point.measured ? point.measured->rmse : 0.0);  // 0: left out of the fit
        estimated.push_back(point.estimated ? point.estimated->rmse : 0.0);
    }
    return {FitPowerLaw(seconds, measured), FitPowerLaw(photons, measured),
            FitPowerLaw(seconds, estimated), FitPowerLaw(photons, estimated)};
}

std::string ConvergenceCsv(std::span<const ConvergencePoint> points) {
    std::string csv =
        "seconds,epochs,photons,estimated_rmse,estimated_rel_error,estimated_bias_rmse,reference_"
        "rmse,"
        "reference_rel_mse,reference_rel_error,reference_nonfinite_fraction,camera_samples\n";
    for (const ConvergencePoint& p : points) {
        std::optional<double> estimated_rmse, estimated_rel, estimated_bias, rmse, rel_mse, rel,
            nonfinite;
        if (p.estimated) {
            estimated_rmse = p.estimated->rmse;
            estimated_rel = p.estimated->RelativeError();
            estimated_bias = p.estimated->bias_rmse;
        }
        if (p.measured) {
            rmse = p.measured->rmse;
            rel_mse = p.measured->rel_mse;
            rel = std::sqrt(p.measured->rel_mse);
            nonfinite =
                p.pixels > 0 ? double(p.measured->nonfinite_pixels) / double(p.pixels) : 0.0;
        }
        csv += absl::StrFormat("%.6f,%d,%d,%s,%s,%s,%s,%s,%s,%s,%d\n", p.seconds, p.epochs,
                               p.photons, Cell(estimated_rmse), Cell(estimated_rel),
                               Cell(estimated_bias), Cell(rmse), Cell(rel_mse), Cell(rel),
                               Cell(nonfinite), p.camera_samples);
    }
    return csv;
}

absl::Status WriteConvergenceCsv(const std::string& path,
                                 std::span<const ConvergencePoint> points) {
    return WriteFileAtomically(path, ConvergenceCsv(points));
}

}  // namespace pf
