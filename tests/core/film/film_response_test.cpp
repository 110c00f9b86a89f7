// The film's response as pbrt-v4's cie1931 PixelSensor: the imaging ratio scales, and a white
// balance for temperature T maps the daylight white of T to the output's white (grey).
#include "core/film/film_response.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pf {
namespace {

TEST(FilmResponseTest, IdentityByDefaultAndTheImagingRatioScales) {
    EXPECT_TRUE(FilmResponse{}.IsIdentity());
    EXPECT_TRUE(FilmResponse::Make(1.0, 0.0).IsIdentity());
    const FilmResponse doubled = FilmResponse::Make(2.0, 0.0);
    EXPECT_EQ(doubled.Apply(Rgb(0.25f, 1.0f, 3.0f)), Rgb(0.5f, 2.0f, 6.0f));  // exactly
    EXPECT_FLOAT_EQ(doubled.Gain(), 2.0f);
}

TEST(FilmResponseTest, WhiteBalanceMakesTheDaylightWhiteGrey) {
    // The daylight locus against its tabled points (CIE 15: D50 and D75).
    EXPECT_NEAR(DaylightChromaticity(5003)[0], 0.3457, 2e-4);
    EXPECT_NEAR(DaylightChromaticity(7504)[1], 0.31485, 2e-4);
    for (double kelvin : {4000.0, 5000.0, 6500.0, 9000.0, 20000.0}) {
        // Linear sRGB of the daylight white at luminance 1, through the inverse of sRGB's
        // XYZ matrix (IEC 61966-2-1).
        const auto [x, y] = DaylightChromaticity(kelvin);
        const double X = x / y, Y = 1, Z = (1 - x - y) / y;
        const Rgb white(float(3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z),
                        float(-0.9692660 * X + 1.8760108 * Y + 0.0415560 * Z),
                        float(0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z));
        const Rgb balanced = FilmResponse::Make(3.0, kelvin).Apply(white);
        // Grey, at the imaging ratio times luminance 1 (Bradford keeps Y of a white nearly).
        EXPECT_NEAR(balanced.x / balanced.y, 1.0f, 2e-3f) << kelvin;
        EXPECT_NEAR(balanced.z / balanced.y, 1.0f, 2e-3f) << kelvin;
        EXPECT_NEAR(balanced.y, 3.0f, 0.1f) << kelvin;
    }
    // A warm white balance (4000 K) cools the picture: grey comes out bluer.
    const Rgb grey = FilmResponse::Make(1.0, 4000).Apply(Rgb(1.0f));
    EXPECT_GT(grey.z, grey.x);
}

}  // namespace
}  // namespace pf
