// Spectra to linear sRGB.
#include "core/film/spectrum.h"

#include <cmath>

#include "absl/strings/str_cat.h"
#include "core/film/color_space.h"

namespace pf {
namespace {

// The visible band integrated over, nm, in steps of 1 nm.
constexpr int kFirstNm = 360, kLastNm = 830;

// One lobe of the fit: a Gaussian with a width on each side of its peak.
double Lobe(double nm, double mean, double below, double above) {
    const double t = (nm - mean) / (nm < mean ? below : above);
    return std::exp(-0.5 * t * t);
}

template <typename Spectrum>
Vec3d Integrate(const Spectrum& spectrum) {
    Vec3d xyz(0.0);
    for (int nm = kFirstNm; nm <= kLastNm; ++nm) xyz += CieMatching(nm) * spectrum(nm);
    return xyz;
}

Rgb ToRgb(const Vec3d& xyz) {
    const Vec3d rgb = Transformed(kSrgbFromXyz, xyz);
    return Rgb(static_cast<float>(rgb.x), static_cast<float>(rgb.y), static_cast<float>(rgb.z));
}

// A light's colour from its XYZ, at luminance 1.
Rgb IlluminantRgb(const Vec3d& xyz) { return xyz.y > 0 ? ToRgb(xyz / xyz.y) : Rgb(0.0f); }

}  // namespace

double SampledSpectrum::At(double nm) const {
    if (lambda.empty() || nm < lambda.front() || nm > lambda.back()) return 0;
    size_t i = 1;
    while (i + 1 < lambda.size() && lambda[i] < nm) ++i;
    const double t = (nm - lambda[i - 1]) / (lambda[i] - lambda[i - 1]);
    return value[i - 1] + t * (value[i] - value[i - 1]);
}

absl::StatusOr<SampledSpectrum> MakeSampledSpectrum(std::span<const double> pairs,
                                                    SpectrumUse use) {
    if (pairs.size() % 2 != 0 || pairs.size() < 4)
        return absl::InvalidArgumentError(absl::StrCat(
            "needs (wavelength, value) pairs, at least 2 of them; has ", pairs.size(), " numbers"));
    SampledSpectrum spectrum;
    for (size_t i = 0; i < pairs.size(); i += 2) {
        const double nm = pairs[i], value = pairs[i + 1];
        if (!std::isfinite(nm) || nm < 100 || nm > 2000)
            return absl::InvalidArgumentError(
                absl::StrCat("wavelength ", nm, " nm lies outside [100, 2000] nm"));
        if (!spectrum.lambda.empty() && !(nm > spectrum.lambda.back()))
            return absl::InvalidArgumentError(
                absl::StrCat("wavelengths must ascend: ", nm, " follows ", spectrum.lambda.back()));
        const double lowest = use == SpectrumUse::kUnbounded ? -kMaxSpectrumValue : 0.0;
        if (!(value >= lowest && value <= kMaxSpectrumValue))
            return absl::InvalidArgumentError(absl::StrCat("value ", value, " at ", nm,
                                                           " nm must lie in [", lowest, ", ",
                                                           kMaxSpectrumValue, "]"));
        spectrum.lambda.push_back(nm);
        spectrum.value.push_back(value);
    }
    return spectrum;
}

Vec3d CieMatching(double nm) {
    // Wyman, Sloan & Shirley 2013, "Simple Analytic Approximations to the CIE XYZ Color
    // Matching Functions", the multi-lobe fit of the 1931 observer.
    return {1.056 * Lobe(nm, 599.8, 37.9, 31.0) + 0.362 * Lobe(nm, 442.0, 16.0, 26.7) -
                0.065 * Lobe(nm, 501.1, 20.4, 26.2),
            0.821 * Lobe(nm, 568.8, 46.9, 40.5) + 0.286 * Lobe(nm, 530.9, 16.3, 31.1),
            1.217 * Lobe(nm, 437.0, 11.8, 36.0) + 0.681 * Lobe(nm, 459.0, 26.0, 13.8)};
}

Rgb SpectrumToRgb(const SampledSpectrum& spectrum, SpectrumUse use) {
    const auto at = [&](double nm) { return spectrum.At(nm); };
    switch (use) {
        case SpectrumUse::kIlluminant:
            return IlluminantRgb(Integrate(at));
        case SpectrumUse::kUnbounded:
            return Rgb(static_cast<float>(spectrum.At(611)), static_cast<float>(spectrum.At(549)),
                       static_cast<float>(spectrum.At(464)));
        case SpectrumUse::kReflectance:
            break;
    }
    // Under the equal-energy light (the fit's own white), adapted to sRGB's white (the
    // matrices' own D65), so that flat spectra stay grey.
    static const Vec3d kEqualEnergy = Integrate([](double) { return 1.0; });
    static const ColorMatrix kToD65 =
        BradfordAdaptation(kEqualEnergy / kEqualEnergy.y, Transformed(kXyzFromSrgb, Vec3d(1.0)));
    return ToRgb(Transformed(kToD65, Integrate(at) / kEqualEnergy.y));
}

Rgb BlackbodyRgb(double kelvin) {
    // Planck's law; constants cancel in the normalisation but for c2 = hc / k.
    constexpr double kC2 = 1.4387769e7;  // nm K
    return IlluminantRgb(Integrate([&](double nm) {
        return 1.0 / (std::pow(nm, 5) * (std::exp(kC2 / (nm * kelvin)) - 1.0));
    }));
}

std::optional<Rgb> NamedIlluminantRgb(std::string_view name) {
    // CIE 1931 chromaticities of the standard illuminants (CIE 15:2004, table T.8 for the
    // fluorescent ones) and of ACES' D60 white.
    static constexpr std::pair<std::string_view, std::array<double, 2>> kWhites[] = {
        {"stdillum-D50", {0.34567, 0.35850}},  {"stdillum-D65", {0.31272, 0.32903}},
        {"stdillum-F1", {0.31310, 0.33727}},   {"stdillum-F2", {0.37208, 0.37529}},
        {"stdillum-F3", {0.40910, 0.39430}},   {"stdillum-F4", {0.44018, 0.40329}},
        {"stdillum-F5", {0.31379, 0.34531}},   {"stdillum-F6", {0.37790, 0.38835}},
        {"stdillum-F7", {0.31292, 0.32933}},   {"stdillum-F8", {0.34588, 0.35875}},
        {"stdillum-F9", {0.37417, 0.37281}},   {"stdillum-F10", {0.34609, 0.35986}},
        {"stdillum-F11", {0.38052, 0.37713}},  {"stdillum-F12", {0.43695, 0.40441}},
        {"illum-acesD60", {0.32168, 0.33767}},
    };
    if (name == "stdillum-A") return BlackbodyRgb(2856);  // CIE A is Planckian at 2856 K
    for (const auto& [illuminant, xy] : kWhites)
        if (illuminant == name) return ToRgb(WhiteXyz(xy));
    return std::nullopt;
}

}  // namespace pf
