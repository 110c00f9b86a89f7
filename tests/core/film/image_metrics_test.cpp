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
    EXPECT_NEAR(d->psnr, 20 * std::log10(1.0 / d->rmse), 1e-9);
    EXPECT_EQ(d->nonfinite_pixels, 0u);
}

TEST(ImageMetricsTest, CountNonFinitePixelsApartAndSkipThem) {
    Image reference(3, 1), image(3, 1);
    reference.pixels = {Rgb(1.0f), Rgb(1.0f), Rgb(1.0f)};
    image.pixels = {Rgb(1.0f), Rgb(std::numeric_limits<float>::quiet_NaN(), 1.0f, 1.0f),
                    Rgb(1.0f, std::numeric_limits<float>::infinity(), 1.0f)};
    const absl::StatusOr<ImageDifference> d = CompareImages(image, reference);
    ASSERT_TRUE(d.ok());
    EXPECT_EQ(d->nonfinite_pixels, 2u);
    EXPECT_EQ(d->rmse, 0.0);
    EXPECT_TRUE(std::isinf(d->psnr));
}

TEST(ImageMetricsTest, DifferentSizesAreAnErrorNamingBoth) {
    const absl::StatusOr<ImageDifference> d = CompareImages(Image(4, 2), Image(2, 4));
    ASSERT_FALSE(d.ok());
    EXPECT_NE(std::string(d.status().message()).find("4x2 against 2x4"), std::string::npos)
        << d.status();
}

}  // namespace
}  // namespace pf
