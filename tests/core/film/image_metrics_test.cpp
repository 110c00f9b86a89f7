// The metrics of `photonfarm compare` on images whose answers are worked out by hand.
#include "core/film/image_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace pf {
namespace {

TEST(ImageMetricsTest, MatchTheDefinitions) {
    Image reference(2, 1), image(2, 1);
    reference.pixels = {Rgb(1.0f), Rgb(0.0f)};
    image.pixels = {Rgb(1.0f, 1.0f, 3.0f), Rgb(0.0f, 0.0f, 0.1f)};
    const absl::StatusOr<ImageDifference> d = CompareImages(image, reference);
    ASSERT_TRUE(d.ok()) << d.status();
    // Errors 0, 0, 2, 0, 0, 0.1 over six values.
    EXPECT_NEAR(d->rmse, std::sqrt((4.0 + 0.01) / 6), 1e-6);
    EXPECT_NEAR(d->rel_mse, (4.0 / 1.01 + 0.01 / 0.01) / 6, 1e-6);
    EXPECT_NEAR(d->max_abs, 2.0, 1e-6);
    // Peak 1 (the reference's largest value), MSE 4.01 / 6: PSNR = 10 log10(6 / 4.01) dB =
    // 1.75007 dB, worked out by hand rather than from the RMSE above.
    EXPECT_NEAR(d->psnr, 1.75007, 1e-5);
    EXPECT_EQ(d->nonfinite_pixels, 0u);
}

TEST(ImageMetricsTest, ConstantOffsetGivesTheClosedFormPsnr) {
    // A 4x3 reference of 0.5 everywhere but one pixel of 0.8 (the peak), and the image 0.1
    // above it in every value: MSE = 0.01, RMSE = 0.1, PSNR = 20 log10(0.8 / 0.1) = 20 log10 8
    // = 18.0618 dB; relative MSE = (11 x 0.01 / 0.26 + 0.01 / 0.65) / 12 = 0.0365385.
    Image reference(4, 3), image(4, 3);
    for (Rgb& pixel : reference.pixels) pixel = Rgb(0.5f);
    reference.pixels[7] = Rgb(0.8f);
    for (size_t p = 0; p < image.pixels.size(); ++p)
        image.pixels[p] = reference.pixels[p] + Rgb(0.1f);
    const absl::StatusOr<ImageDifference> d = CompareImages(image, reference);
    ASSERT_TRUE(d.ok()) << d.status();
    EXPECT_NEAR(d->rmse, 0.1, 1e-6);
    EXPECT_NEAR(d->psnr, 18.0618, 1e-4);
    EXPECT_NEAR(d->rel_mse, 0.0365385, 1e-6);
    EXPECT_NEAR(d->max_abs, 0.1, 1e-6);
}

TEST(ImageMetricsTest, CountNonFinitePixelsApartAndSkipThem) {
    Image reference(3, 1), image(3, 1);
    reference.pixels = {Rgb(1.0f), Rgb(1.0f), Rgb(1.0f)};
    image.pixels = {Rgb(1.0f), Rgb(std::numeric_limits<float>::quiet_NaN(), 1.0f, 1.0f),
                    Rgb(1.0f, std::numeric_limits<float>::infinity(), 1.0f)};
    const absl::StatusOr<ImageDifference> d = CompareImages(image, reference);
    ASSERT_TRUE(d.ok());
    EXPECT_EQ(d->nonfinite_pixels, 2u);
    EXPECT_FALSE(d->AllFinite());
    EXPECT_EQ(d->rmse, 0.0);
    EXPECT_TRUE(std::isinf(d->psnr));
}

// An image with nothing finite in it is not a perfect match: the metrics are NaN, so that a
// check on max_abs == 0 or rmse == 0 fails, and every pixel is counted.
TEST(ImageMetricsTest, AnAllNanImageMeasuresNothingAndMatchesNothing) {
    Image reference(2, 2), image(2, 2);
    reference.pixels.assign(4, Rgb(0.5f));
    image.pixels.assign(4, Rgb(std::numeric_limits<float>::quiet_NaN()));
    const absl::StatusOr<ImageDifference> d = CompareImages(image, reference);
    ASSERT_TRUE(d.ok());
    EXPECT_EQ(d->nonfinite_pixels, 4u);
    EXPECT_FALSE(d->AllFinite());
    EXPECT_TRUE(std::isnan(d->max_abs));
    EXPECT_TRUE(std::isnan(d->rmse));
    EXPECT_TRUE(std::isnan(d->rel_mse));
    EXPECT_TRUE(std::isnan(d->psnr));
    EXPECT_FALSE(d->max_abs == 0.0);
}

// A NaN or Inf in the reference is counted too (it used to be skipped without a word), and the
// pixel left out whole.
TEST(ImageMetricsTest, NonFiniteReferencePixelsAreCountedAndLeftOut) {
    Image reference(2, 1), image(2, 1);
    reference.pixels = {Rgb(1.0f, std::numeric_limits<float>::infinity(), 1.0f), Rgb(1.0f)};
    image.pixels = {Rgb(5.0f), Rgb(1.0f)};
    const absl::StatusOr<ImageDifference> d = CompareImages(image, reference);
    ASSERT_TRUE(d.ok());
    EXPECT_EQ(d->nonfinite_pixels, 0u);
    EXPECT_EQ(d->nonfinite_reference_pixels, 1u);
    EXPECT_FALSE(d->AllFinite());
    EXPECT_EQ(d->max_abs, 0.0) << "the finite channels of a pixel with an Inf are left out too";
    Image clean = reference;
    clean.pixels[0] = Rgb(1.0f);
    EXPECT_TRUE(CompareImages(image, clean)->AllFinite());
}

TEST(ImageMetricsTest, DifferentSizesAreAnErrorNamingBoth) {
    const absl::StatusOr<ImageDifference> d = CompareImages(Image(4, 2), Image(2, 4));
    ASSERT_FALSE(d.ok());
    EXPECT_NE(std::string(d.status().message()).find("4x2 against 2x4"), std::string::npos)
        << d.status();
}

}  // namespace
}  // namespace pf
