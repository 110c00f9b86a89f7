// Where a pixel's filter puts its camera samples (filter importance sampling, as pbrt-v4 does):
// a sample's offset from the pixel's centre is drawn with density |f| (each axis on its own,
// the filters being separable) from the pixel's stratified numbers, so the pixel is the plain
// mean of its samples times their weights f / |f| x (integral of |f|) / (integral of f): 1
// wherever f is positive. Box and triangle are inverted in closed form, the truncated Gaussian
// by a cubic spline through its inverse CDF solved at 257 points (Newton's steps at the ends),
// every sample weighing 1; Mitchell's and the windowed sinc's densities are tabulated,
// piecewise constant, as pbrt-v4 tabulates every filter, their negative lobes giving negative
// weights.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/math/point2.h"
#include "core/scene/camera.h"

namespace pf {

// A camera sample's place relative to its pixel's centre, in pixels (x right, y down), and the
// weight its radiance takes in the pixel's mean.
struct FilterSample {
    Point2 offset;
    float weight = 1.0f;
};

// What is wrong with a filter's parameters (a radius not in (0, 16], a sigma, B, C or tau out
// of range, a tabulated integral that is not positive), or nothing.
std::optional<std::string> FilterProblem(const PixelFilter& filter);

class FilterSampler {
public:
    // The filter must have no FilterProblem.
    explicit FilterSampler(const PixelFilter& filter);

    // The sample for the point u in [0, 1)^2.
    FilterSample Sample(Point2 u) const;

    // f(x) along one axis (the filter is the product of both): exposed for tests.
    static double Evaluate(const PixelFilter& filter, double x, double radius);

private:
    // One axis: its radius and, for the tabulated filters, |f|'s cumulative distribution over
    // equal bins of [-radius, radius] with each bin's sign.
    struct Axis {
        double radius = 0.5;
        // Gaussian: the normalisation of g(x) - g(radius), g(radius), and the Gaussian's
        // integral below -radius.
        double gaussian_total = 0, gaussian_floor = 0, gaussian_base = 0;
        std::vector<double> inverse, slope;  // x and dx/du at u = i / (size - 1)
        std::vector<double> cdf;             // bins + 1 entries, 0 to 1
        std::vector<float> sign;  // +1 or -1 per bin, times (integral |f|) / (integral f)
    };
    static Axis MakeAxis(const PixelFilter& filter, double radius);
    double SampleAxis(const Axis& axis, double u, float* weight) const;
    double SolveGaussian(const Axis& axis, double u, double lo, double hi, double x) const;

    PixelFilter filter_;
    Axis x_, y_;
};

}  // namespace pf
