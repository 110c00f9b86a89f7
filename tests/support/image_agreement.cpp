// The bound: A and B are renders with the same seed (so the same hit points), photon budget
// and batch layout, each with its own photon stream; V is the image under test. If V samples
// the same estimator, the three are independent draws of one random image: the same
// expectation (bias included) and per-pixel variance s^2. So
//  - spread: each pair's mean squared pixel difference estimates 2 s^2. Over P pixels of
//    which about P/4 are independent (a photon reaches the hit points of a few neighbouring
//    pixels), one such mean has a relative spread of sqrt(2 / (P/4)), 9% at 32x32; we require
//    (MSE(V,A) + MSE(V,B)) / 2 <= 1.5 MSE(A,B), over four of those spreads.
//  - mean: the image mean's variance is at most 4 s^2 / P (the same correlation), so
//    mean(V) - (mean(A) + mean(B)) / 2 has variance at most 1.5 x 4 s^2 / P with
//    s^2 = MSE(A,B) / 2; we require it within 4 of its standard deviations. At the budgets of
//    our tests that is about 1% of the image mean: an image 2% too bright or dark fails.
#include "tests/support/image_agreement.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pf::testing {
namespace {

double Mean(const Image& image) {
    double sum = 0;
    for (const Rgb& pixel : image.pixels) sum += Average(pixel);
    return sum / image.pixels.size();
}

}  // namespace

double MeanSquaredDifference(const Image& a, const Image& b) {
    double sum = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        const double d = Average(a.pixels[i]) - Average(b.pixels[i]);
        sum += d * d;
    }
    return sum / a.pixels.size();
}

void ExpectSameEstimator(const Image& image, const Image& a, const Image& b) {
    ASSERT_FALSE(a.pixels.empty());
    ASSERT_EQ(image.pixels.size(), a.pixels.size());
    ASSERT_EQ(b.pixels.size(), a.pixels.size());
    const double pixels = static_cast<double>(a.pixels.size());
    const double reference_spread = MeanSquaredDifference(a, b);
    const double spread = (MeanSquaredDifference(image, a) + MeanSquaredDifference(image, b)) / 2;
    EXPECT_LE(spread, 1.5 * reference_spread)
        << "the image strays further from the references than they do from each other";
    const double mean_sigma = std::sqrt(1.5 * 4 * (reference_spread / 2) / pixels);
    EXPECT_NEAR(Mean(image), (Mean(a) + Mean(b)) / 2, 4 * mean_sigma)
        << "reference means " << Mean(a) << ", " << Mean(b) << "; spread " << spread << " against "
        << reference_spread;
}

}  // namespace pf::testing
