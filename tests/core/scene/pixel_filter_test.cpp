// Where a pixel's filter puts its camera samples (core/scene/pixel_filter.h): for each of
// pbrt-v4's filters, the samples' weighted density over the pixel's neighbourhood is the
// filter's own, normalised -- each strip's share of the weights against the filter's integral
// over the strip, integrated by Simpson's rule from the formulas written out here; positive
// filters give every sample weight 1, Mitchell's outer lobes negative weights; bad parameters
// are refused.
#include "core/scene/pixel_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace pf {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The filters along one axis, written from pbrt-v4's definitions (pbrt-v4 book, 8.8).
double Filter(const PixelFilter& filter, double x, double r) {
    if (std::abs(x) > r) return 0;
    const auto gaussian = [&](double t) {
        return std::exp(-t * t / (2 * filter.sigma * filter.sigma)) /
               std::sqrt(2 * kPi * filter.sigma * filter.sigma);
    };
    const auto sinc = [](double t) { return t == 0 ? 1.0 : std::sin(kPi * t) / (kPi * t); };
    switch (filter.kind) {
        case FilterKind::kBox:
            return 1;
        case FilterKind::kTriangle:
            return r - std::abs(x);
        case FilterKind::kGaussian:
            return std::max(0.0, gaussian(x) - gaussian(r));
        case FilterKind::kMitchell: {
            const double t = std::abs(2 * x / r), b = filter.b, c = filter.c;
            if (t <= 1)
                return ((12 - 9 * b - 6 * c) * t * t * t + (-18 + 12 * b + 6 * c) * t * t +
                        (6 - 2 * b)) /
                       6;
            return ((-b - 6 * c) * t * t * t + (6 * b + 30 * c) * t * t + (-12 * b - 48 * c) * t +
                    (8 * b + 24 * c)) /
                   6;
        }
        case FilterKind::kSinc:
            return sinc(x) * sinc(x / filter.tau);
    }
    return 0;
}

double Integral(const PixelFilter& filter, double a, double b, double r) {
    constexpr int kSteps = 2000;  // even
    const double h = (b - a) / kSteps;
    double sum = Filter(filter, a, r) + Filter(filter, b, r);
    for (int i = 1; i < kSteps; ++i) sum += (i % 2 ? 4 : 2) * Filter(filter, a + i * h, r);
    return sum * h / 3;
}

double AbsoluteIntegral(const PixelFilter& filter, double r) {
    constexpr int kSteps = 20000;
    double sum = 0;
    for (int i = 0; i < kSteps; ++i)
        sum += std::abs(Filter(filter, -r + (i + 0.5) * 2 * r / kSteps, r));
    return sum * 2 * r / kSteps;
}

struct Case {
    std::string name;
    PixelFilter filter;
    double tolerance;  // of each strip's share
};

std::vector<Case> Cases() {
    PixelFilter box, wide_box, triangle, narrow_triangle, gaussian, wide_gaussian, mitchell, sinc;
    wide_box.radius_x = 1.2f, wide_box.radius_y = 0.7f;
    triangle.kind = narrow_triangle.kind = FilterKind::kTriangle;
    triangle.radius_x = triangle.radius_y = 2;
    narrow_triangle.radius_x = narrow_triangle.radius_y = 0.8f;
    gaussian.kind = wide_gaussian.kind = FilterKind::kGaussian;
    gaussian.radius_x = gaussian.radius_y = 1.5f;
    wide_gaussian.radius_x = wide_gaussian.radius_y = 3, wide_gaussian.sigma = 1;
    mitchell.kind = FilterKind::kMitchell;
    mitchell.radius_x = mitchell.radius_y = 2;
    sinc.kind = FilterKind::kSinc;
    sinc.radius_x = sinc.radius_y = 4, sinc.tau = 3;
    // Exact inversions to the float offsets; tabulated ones to their 64 bins a pixel.
    return {{"box", box, 1e-5},           {"box 1.2", wide_box, 1e-5},
            {"triangle", triangle, 1e-5}, {"triangle 0.8", narrow_triangle, 1e-5},
            {"gaussian", gaussian, 1e-5}, {"gaussian 3/1", wide_gaussian, 1e-5},
            {"mitchell", mitchell, 2e-4}, {"sinc", sinc, 2e-4}};
}

TEST(PixelFilterTest, SamplesFollowTheFiltersDensityWithTheirWeights) {
    constexpr int kSamples = 1 << 18, kStrips = 24;
    for (const Case& c : Cases()) {
        ASSERT_FALSE(FilterProblem(c.filter)) << c.name;
        const FilterSampler sampler(c.filter);
        for (const int axis : {0, 1}) {
            const double r = axis == 0 ? c.filter.radius_x : c.filter.radius_y;
            std::vector<double> share(kStrips, 0.0);
            double mean_weight = 0;
            bool negative = false;
            for (int i = 0; i < kSamples; ++i) {
                // Stratified along the axis under test, the other at the filter's centre.
                const double u = (i + 0.5) / kSamples;
                const FilterSample s =
                    sampler.Sample(axis == 0 ? Point2{float(u), 0.5f} : Point2{0.5f, float(u)});
                const double x = axis == 0 ? s.offset.x : s.offset.y;
                ASSERT_TRUE(std::abs(x) <= r) << c.name << " offset " << x;
                ASSERT_NEAR(axis == 0 ? s.offset.y : s.offset.x, 0.0, 0.05) << c.name;
                const int strip = std::min(kStrips - 1, int((x + r) / (2 * r) * kStrips));
                share[strip] += s.weight / kSamples;
                mean_weight += s.weight / kSamples;
                negative |= s.weight < 0;
            }
            // The other axis, held at its centre, weighs every sample by its own scale: the
            // integral of |f| over that of f.
            const double other = axis == 0 ? c.filter.radius_y : c.filter.radius_x;
            const double scale =
                AbsoluteIntegral(c.filter, other) / Integral(c.filter, -other, other, other);
            const double total = Integral(c.filter, -r, r, r) / scale;
            for (int k = 0; k < kStrips; ++k) {
                const double a = -r + 2 * r * k / kStrips, b = -r + 2 * r * (k + 1) / kStrips;
                EXPECT_NEAR(share[k], Integral(c.filter, a, b, r) / total, c.tolerance)
                    << c.name << ", axis " << axis << ", strip [" << a << ", " << b << ")";
            }
            // Over both axes the weights' mean is 1: this axis's mean is 1, times the other's.
            EXPECT_NEAR(mean_weight / scale, 1.0, 5 * c.tolerance) << c.name;
            EXPECT_EQ(negative,
                      c.filter.kind == FilterKind::kMitchell || c.filter.kind == FilterKind::kSinc)
                << c.name << ": only filters with negative lobes give negative weights";
        }
    }
}

TEST(PixelFilterTest, PositiveFiltersWeighEverySampleOne) {
    for (const Case& c : Cases()) {
        if (c.filter.kind == FilterKind::kMitchell || c.filter.kind == FilterKind::kSinc) continue;
        const FilterSampler sampler(c.filter);
        for (int i = 0; i < 1000; ++i) {
            const float u = (i + 0.5f) / 1000, v = std::fmod(u * 7.31f, 1.0f);
            EXPECT_EQ(sampler.Sample({u, v}).weight, 1.0f) << c.name;
        }
    }
}

TEST(PixelFilterTest, TheBoxOfOnePixelIsThePixelItself) {
    // What glTF scenes take: a sample at u lies u - 1/2 from the centre, as before filters.
    const FilterSampler sampler{PixelFilter{}};
    for (const float u : {0.0f, 0.125f, 0.5f, 0.999f}) {
        const FilterSample s = sampler.Sample({u, 1 - u});
        EXPECT_FLOAT_EQ(s.offset.x, u - 0.5f);
        EXPECT_FLOAT_EQ(s.offset.y, 0.5f - u);
    }
}

TEST(PixelFilterTest, BadParametersAreNamed) {
    PixelFilter filter;
    filter.radius_x = 0;
    EXPECT_NE(FilterProblem(filter)->find("radius 0"), std::string::npos);
    filter.radius_x = 17;
    EXPECT_NE(FilterProblem(filter)->find("radius 17"), std::string::npos);
    filter.radius_x = std::nanf("");
    EXPECT_TRUE(FilterProblem(filter));
    filter = PixelFilter{FilterKind::kGaussian, 1.5f, 1.5f, -1.0f};
    EXPECT_NE(FilterProblem(filter)->find("sigma"), std::string::npos);
    filter = PixelFilter{FilterKind::kSinc, 4, 4, 0.5f, 0, 0, 0};
    EXPECT_NE(FilterProblem(filter)->find("tau"), std::string::npos);
    filter = PixelFilter{FilterKind::kMitchell, 2, 2, 0.5f, 0, 11, 3};
    EXPECT_NE(FilterProblem(filter)->find("\"B\" and \"C\""), std::string::npos);
    filter.kind = static_cast<FilterKind>(9);
    EXPECT_TRUE(FilterProblem(filter));
}

}  // namespace
}  // namespace pf
