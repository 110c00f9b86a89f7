// Spectra as scenes give them (pbrt's sampled spectra, named illuminants, black bodies),
// turned into the linear sRGB photonfarm renders with. Colour matching is CIE 1931's 2-degree
// observer in Wyman, Sloan & Shirley's multi-lobe fit (JCGT 2013), within about 1% of the
// tables over the visible band.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "absl/status/statusor.h"
#include "core/math/vec3.h"

namespace pf {

// What a spectrum stands for decides how it becomes RGB.
enum class SpectrumUse {
    // A reflectance or transmittance: its colour under an equal-energy light, adapted to D65
    // (Bradford), so a flat spectrum of value v is the grey (v, v, v).
    kReflectance,
    // A light's emission: its colour at luminance 1, as pbrt-v4 normalises light spectra
    // (the light's "scale" and "power" set its brightness).
    kIlluminant,
    // An unbounded quantity (an index of refraction, an absorption coefficient): its values at
    // the sRGB primaries' dominant wavelengths, 611, 549 and 464 nm.
    kUnbounded,
};

// A piecewise-linear spectrum over wavelengths in nm, ascending; zero outside them, as pbrt's
// PiecewiseLinearSpectrum.
struct SampledSpectrum {
    std::vector<double> lambda, value;

    double At(double nm) const;
};

// (wavelength, value) pairs as pbrt writes them: at least two pairs, wavelengths strictly
// ascending within [100, 2000] nm, values within kMaxSpectrumValue (and not negative, but for
// kUnbounded), so every colour made from them is finite in float. Errors say which rule broke.
inline constexpr double kMaxSpectrumValue = 1e30;
absl::StatusOr<SampledSpectrum> MakeSampledSpectrum(std::span<const double> pairs, SpectrumUse use);

// CIE 1931 colour matching functions x-bar, y-bar, z-bar at `nm`.
Vec3d CieMatching(double nm);
// The spectrum's colour (see SpectrumUse). Zero for an illuminant with no luminance.
Rgb SpectrumToRgb(const SampledSpectrum& spectrum, SpectrumUse use);
// A black body at `kelvin` as a light's colour (luminance 1), from Planck's law.
Rgb BlackbodyRgb(double kelvin);
// pbrt-v4's named light spectra ("stdillum-A", "stdillum-D50", "stdillum-D65",
// "stdillum-F1" ... "stdillum-F12", "illum-acesD60") as a light's colour, luminance 1; nullopt
// for any other name.
std::optional<Rgb> NamedIlluminantRgb(std::string_view name);

}  // namespace pf
