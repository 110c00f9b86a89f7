#include "core/scene/pixel_filter.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "core/util/check.h"

namespace pf {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMaxRadius = 16;  // pixels: wider filters blur more than any scene asks
constexpr int kBinsPerPixel = 64;  // tabulated filters: bins per pixel of radius
constexpr double kSolveTolerance = 1e-9;
constexpr double kNewtonClose = 1e-5;
constexpr int kGaussianTable = 256;  // intervals of u the Gaussian's inverse is tabulated at
constexpr int kNewtonIntervals = 2;  // at each end, where the spline would not do

double Gaussian(double x, double sigma) {
    return std::exp(-x * x / (2 * sigma * sigma)) / (sigma * std::sqrt(2 * kPi));
}
// The Gaussian's integral from -infinity to x.
double GaussianCdf(double x, double sigma) {
    return 0.5 * std::erfc(-x / (sigma * std::sqrt(2.0)));
}

// pbrt-v4's Mitchell1D over [-2, 2].
double Mitchell(double x, double b, double c) {
    x = std::abs(x);
    if (x <= 1)
        return ((12 - 9 * b - 6 * c) * x * x * x + (-18 + 12 * b + 6 * c) * x * x + (6 - 2 * b)) /
               6;
    if (x <= 2)
        return ((-b - 6 * c) * x * x * x + (6 * b + 30 * c) * x * x + (-12 * b - 48 * c) * x +
                (8 * b + 24 * c)) /
               6;
    return 0;
}

double Sinc(double x) {
    if (std::abs(x) < 1e-5) return 1 - kPi * kPi * x * x / 6;
    return std::sin(kPi * x) / (kPi * x);
}

bool Tabulated(FilterKind kind) {
    return kind == FilterKind::kMitchell || kind == FilterKind::kSinc;
}

int Bins(double radius) { return std::max(kBinsPerPixel, int(std::ceil(kBinsPerPixel * radius))); }

}  // namespace

double FilterSampler::Evaluate(const PixelFilter& filter, double x, double radius) {
    if (!(std::abs(x) <= radius)) return 0;
    switch (filter.kind) {
        case FilterKind::kBox:
            return 1;
        case FilterKind::kTriangle:
            return radius - std::abs(x);
        case FilterKind::kGaussian:
            return std::max(0.0, Gaussian(x, filter.sigma) - Gaussian(radius, filter.sigma));
        case FilterKind::kMitchell:
            return Mitchell(2 * x / radius, filter.b, filter.c);
        case FilterKind::kSinc:
            return Sinc(x) * Sinc(x / filter.tau);
    }
    return 0;
}

std::optional<std::string> FilterProblem(const PixelFilter& filter) {
    if (static_cast<uint32_t>(filter.kind) > static_cast<uint32_t>(FilterKind::kSinc))
        return "an unknown filter";
    for (const float radius : {filter.radius_x, filter.radius_y})
        if (!(radius > 0 && radius <= kMaxRadius))
            return absl::StrCat("radius ", radius, " is not in (0, ", kMaxRadius, "] pixels");
    if (filter.kind == FilterKind::kGaussian && !(filter.sigma > 0 && filter.sigma <= 1e3))
        return absl::StrCat("\"sigma\" ", filter.sigma, " is not in (0, 1000] pixels");
    if (filter.kind == FilterKind::kMitchell &&
        !(std::abs(filter.b) <= 10 && std::abs(filter.c) <= 10))
        return "\"B\" and \"C\" must lie in [-10, 10]";
    if (filter.kind == FilterKind::kSinc && !(filter.tau > 0 && filter.tau <= 1e3))
        return absl::StrCat("\"tau\" ", filter.tau, " is not in (0, 1000]");
    if (Tabulated(filter.kind)) {
        for (const double radius : {double(filter.radius_x), double(filter.radius_y)}) {
            const int bins = Bins(radius);
            double integral = 0;
            for (int i = 0; i < bins; ++i)
                integral +=
                    FilterSampler::Evaluate(filter, radius * (2 * (i + 0.5) / bins - 1), radius);
            if (!(integral > 0)) return "its integral is not positive (no pixel would be bright)";
        }
    }
    return std::nullopt;
}

FilterSampler::Axis FilterSampler::MakeAxis(const PixelFilter& filter, double radius) {
    Axis axis;
    axis.radius = radius;
    if (filter.kind == FilterKind::kGaussian) {
        axis.gaussian_floor = Gaussian(radius, filter.sigma);
        axis.gaussian_base = GaussianCdf(-radius, filter.sigma);
        axis.gaussian_total = GaussianCdf(radius, filter.sigma) -
                              GaussianCdf(-radius, filter.sigma) - 2 * radius * axis.gaussian_floor;
    }
    if (!Tabulated(filter.kind)) return axis;
    const int bins = Bins(radius);
    std::vector<double> value(bins);
    double absolute = 0, integral = 0;
    for (int i = 0; i < bins; ++i) {
        value[i] = Evaluate(filter, radius * (2 * (i + 0.5) / bins - 1), radius);
        absolute += std::abs(value[i]);
        integral += value[i];
    }
    PF_CHECK(integral > 0);
    const double scale = absolute / integral;  // the mean weight is then 1
    axis.cdf.assign(bins + 1, 0.0);
    axis.sign.resize(bins);
    for (int i = 0; i < bins; ++i) {
        axis.cdf[i + 1] = axis.cdf[i] + std::abs(value[i]) / absolute;
        axis.sign[i] = static_cast<float>(value[i] < 0 ? -scale : scale);
    }
    axis.cdf[bins] = 1;
    return axis;
}

double FilterSampler::SolveGaussian(const Axis& axis, double u, double lo, double hi,
                                    double x) const {
    // CDF(x) = u for the density g(x) - g(r): Newton's steps kept inside the bracket that
    // bisection keeps. A step under kNewtonClose of the radius leaves an error near its square.
    const double sigma = filter_.sigma, r = axis.radius;
    for (int step = 0; step < 64; ++step) {
        const double cdf =
            (GaussianCdf(x, sigma) - axis.gaussian_base - axis.gaussian_floor * (x + r)) /
            axis.gaussian_total;
        if (cdf < u)
            lo = x;
        else
            hi = x;
        const double density = (Gaussian(x, sigma) - axis.gaussian_floor) / axis.gaussian_total;
        double next = density > 0 ? x - (cdf - u) / density : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        const bool done = std::abs(next - x) <= kNewtonClose * r;
        x = next;
        if (done || hi - lo <= kSolveTolerance * r) break;
    }
    return x;
}

FilterSampler::FilterSampler(const PixelFilter& filter)
    : filter_(filter),
      x_(MakeAxis(filter, filter.radius_x)),
      y_(MakeAxis(filter, filter.radius_y)) {
    PF_CHECK(!FilterProblem(filter));
    if (filter.kind != FilterKind::kGaussian) return;
    for (Axis* axis : {&x_, &y_}) {
        const double r = axis->radius;
        axis->inverse.assign(kGaussianTable + 1, 0.0);
        axis->inverse[0] = -r, axis->inverse[kGaussianTable] = r;
        for (int i = 1; i < kGaussianTable; ++i) {
            const double u = double(i) / kGaussianTable;
            axis->inverse[i] = SolveGaussian(*axis, u, axis->inverse[i - 1], r, (2 * u - 1) * r);
        }
        axis->slope.assign(kGaussianTable + 1, 0.0);  // dx/du; the ends' (infinite) unused
        for (int i = 1; i < kGaussianTable; ++i)
            axis->slope[i] = axis->gaussian_total /
                             (Gaussian(axis->inverse[i], filter.sigma) - axis->gaussian_floor);
    }
}

double FilterSampler::SampleAxis(const Axis& axis, double u, float* weight) const {
    const double r = axis.radius;
    switch (filter_.kind) {
        case FilterKind::kBox:
            return (2 * u - 1) * r;
        case FilterKind::kTriangle:
            return u < 0.5 ? r * (std::sqrt(2 * u) - 1) : r * (1 - std::sqrt(2 * (1 - u)));
        case FilterKind::kGaussian: {
            // The inverse CDF between the table's nodes: a cubic Hermite spline through their
            // x and dx/du = 1 / density (error of order h^4); in the outer intervals, where the
            // density falls to zero and x(u) turns like a square root, Newton's steps.
            const int last = static_cast<int>(axis.inverse.size()) - 1;
            const double at = u * last;
            const int i = std::clamp(static_cast<int>(at), 0, last - 1);
            const double* x = axis.inverse.data() + i;
            if (i < kNewtonIntervals || i >= last - kNewtonIntervals)
                return SolveGaussian(axis, u, x[0], x[1], x[0] + (x[1] - x[0]) * (at - i));
            const double t = at - i, t2 = t * t, t3 = t2 * t, h = 1.0 / last;
            const double* slope = axis.slope.data() + i;
            return (2 * t3 - 3 * t2 + 1) * x[0] + (t3 - 2 * t2 + t) * h * slope[0] +
                   (-2 * t3 + 3 * t2) * x[1] + (t3 - t2) * h * slope[1];
        }
        case FilterKind::kMitchell:
        case FilterKind::kSinc: {
            const auto bins = static_cast<int>(axis.sign.size());
            const int i = std::clamp(
                int(std::upper_bound(axis.cdf.begin(), axis.cdf.end(), u) - axis.cdf.begin()) - 1,
                0, bins - 1);
            const double width = axis.cdf[i + 1] - axis.cdf[i];
            const double within = width > 0 ? std::clamp((u - axis.cdf[i]) / width, 0.0, 1.0) : 0.5;
            *weight *= axis.sign[i];
            return r * (2 * (i + within) / bins - 1);
        }
    }
    return 0;
}

FilterSample FilterSampler::Sample(Point2 u) const {
    FilterSample sample;
    const double x = SampleAxis(x_, u.x, &sample.weight);
    const double y = SampleAxis(y_, u.y, &sample.weight);
    sample.offset = {static_cast<float>(x), static_cast<float>(y)};
    return sample;
}

}  // namespace pf
