// Spectra to linear sRGB, against the colour science they come from: CIE 1931's observer, the
// chromaticities of the standard illuminants and Planck's law, and linearity.
#include "core/film/spectrum.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace pf {
namespace {

double Luminance(const Rgb& c) { return 0.2126729 * c.x + 0.7151522 * c.y + 0.0721750 * c.z; }

// CIE xy chromaticity of a linear sRGB colour.
std::array<double, 2> Chromaticity(const Rgb& c) {
    const double X = 0.4124564 * c.x + 0.3575761 * c.y + 0.1804375 * c.z;
    const double Y = Luminance(c);
    const double Z = 0.0193339 * c.x + 0.1191920 * c.y + 0.9503041 * c.z;
    return {X / (X + Y + Z), Y / (X + Y + Z)};
}

SampledSpectrum Make(const std::vector<double>& pairs, SpectrumUse use) {
    absl::StatusOr<SampledSpectrum> spectrum = MakeSampledSpectrum(pairs, use);
    EXPECT_TRUE(spectrum.ok()) << spectrum.status();
    return spectrum.ok() ? *spectrum : SampledSpectrum{};
}

TEST(SpectrumTest, TheObserverFitMatchesTheTables) {
    // CIE 1931 2-degree tables: y-bar(555) = 1.0000, x-bar(600) = 1.0622, z-bar(450) = 1.7721,
    // x-bar(450) = 0.3362; the fit is within a few percent of each.
    EXPECT_NEAR(CieMatching(555).y, 1.0000, 0.02);
    EXPECT_NEAR(CieMatching(600).x, 1.0622, 0.03);
    EXPECT_NEAR(CieMatching(450).z, 1.7721, 0.05);
    EXPECT_NEAR(CieMatching(450).x, 0.3362, 0.02);
    EXPECT_LT(CieMatching(830).y, 1e-3);
}

TEST(SpectrumTest, FlatReflectancesAreGreyAndColoursAddUp) {
    const Rgb half = SpectrumToRgb(Make({300, 0.5, 900, 0.5}, SpectrumUse::kReflectance),
                                   SpectrumUse::kReflectance);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(half[c], 0.5f, 1e-5f);
    // A red step and its complement add up to white: the conversion is linear.
    const Rgb red =
        SpectrumToRgb(Make({300, 0, 599.9, 0, 600, 1, 900, 1}, SpectrumUse::kReflectance),
                      SpectrumUse::kReflectance);
    const Rgb cyan =
        SpectrumToRgb(Make({300, 1, 599.9, 1, 600, 0, 900, 0}, SpectrumUse::kReflectance),
                      SpectrumUse::kReflectance);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(red[c] + cyan[c], 1.0f, 2e-3f);
    EXPECT_GT(red.x, 2 * red.y);
    EXPECT_GT(cyan.z, 2 * cyan.x);
}

TEST(SpectrumTest, LightsHaveLuminanceOneAndTheirIlluminantsWhite) {
    const Rgb d65 = *NamedIlluminantRgb("stdillum-D65");
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(d65[c], 1.0f, 2e-3f);
    for (const char* name : {"stdillum-A", "stdillum-D50", "stdillum-F2", "illum-acesD60"})
        EXPECT_NEAR(Luminance(*NamedIlluminantRgb(name)), 1.0, 1e-4) << name;
    EXPECT_FALSE(NamedIlluminantRgb("stdillum-Q").has_value());
    // CIE A is Planck's law at 2856 K: chromaticity (0.44757, 0.40745), here from the fit.
    const std::array<double, 2> a = Chromaticity(*NamedIlluminantRgb("stdillum-A"));
    EXPECT_NEAR(a[0], 0.44757, 3e-3);
    EXPECT_NEAR(a[1], 0.40745, 3e-3);
    // A black body at 6504 K lies near D65 (within the fit's and the locus' distance).
    const std::array<double, 2> d = Chromaticity(BlackbodyRgb(6504));
    EXPECT_NEAR(d[0], 0.3135, 4e-3);
    EXPECT_NEAR(d[1], 0.3237, 4e-3);
    EXPECT_NEAR(Luminance(BlackbodyRgb(1800)), 1.0, 1e-4);
    // Any light spectrum too: its colour at luminance 1, whatever its scale.
    const Rgb flat =
        SpectrumToRgb(Make({380, 7, 780, 7}, SpectrumUse::kIlluminant), SpectrumUse::kIlluminant);
    EXPECT_NEAR(Luminance(flat), 1.0, 1e-4);
    const std::array<double, 2> e = Chromaticity(flat);
    EXPECT_NEAR(e[0], 1.0 / 3, 5e-3);  // the equal-energy white, E
    EXPECT_NEAR(e[1], 1.0 / 3, 5e-3);
}

TEST(SpectrumTest, UnboundedValuesAreReadAtThePrimaries) {
    // A glass whose index falls linearly from 1.6 at 400 nm to 1.5 at 700 nm.
    const SampledSpectrum eta = Make({400, 1.6, 700, 1.5}, SpectrumUse::kUnbounded);
    const Rgb rgb = SpectrumToRgb(eta, SpectrumUse::kUnbounded);
    EXPECT_NEAR(rgb.x, 1.6 - 0.1 * (611 - 400) / 300.0, 1e-6);
    EXPECT_NEAR(rgb.y, 1.6 - 0.1 * (549 - 400) / 300.0, 1e-6);
    EXPECT_NEAR(rgb.z, 1.6 - 0.1 * (464 - 400) / 300.0, 1e-6);
    EXPECT_EQ(eta.At(399), 0.0);  // zero outside, as pbrt's piecewise-linear spectra
}

TEST(SpectrumTest, MalformedSpectraSayWhatIsWrong) {
    auto error = [](const std::vector<double>& pairs, SpectrumUse use = SpectrumUse::kReflectance) {
        absl::StatusOr<SampledSpectrum> spectrum = MakeSampledSpectrum(pairs, use);
        return spectrum.ok() ? std::string("ok") : std::string(spectrum.status().message());
    };
    EXPECT_EQ(error({400, 1, 500}),
              "needs (wavelength, value) pairs, at least 2 of them; has 3 numbers");
    EXPECT_EQ(error({400, 1}),
              "needs (wavelength, value) pairs, at least 2 of them; has 2 numbers");
    EXPECT_EQ(error({500, 1, 400, 1}), "wavelengths must ascend: 400 follows 500");
    EXPECT_EQ(error({400, 1, 5000, 1}), "wavelength 5000 nm lies outside [100, 2000] nm");
    EXPECT_EQ(error({400, -1, 500, 1}), "value -1 at 400 nm must lie in [0, 1e+30]");
    EXPECT_EQ(error({400, 1e39, 500, 1}), "value 1e+39 at 400 nm must lie in [0, 1e+30]");
    EXPECT_EQ(error({400, -1, 500, 1}, SpectrumUse::kUnbounded), "ok");
    EXPECT_EQ(error({400, std::nan(""), 500, 1}, SpectrumUse::kUnbounded),
              "value nan at 400 nm must lie in [-1e+30, 1e+30]");
}

}  // namespace
}  // namespace pf
