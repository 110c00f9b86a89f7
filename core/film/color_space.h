// Linear sRGB and CIE XYZ, and chromatic adaptation between whites: the colour science the
// film's white balance and the pbrt spectra share.
#pragma once

#include <array>

#include "core/math/vec3.h"

namespace pf {

using ColorMatrix = std::array<std::array<double, 3>, 3>;  // row-major, column vectors

ColorMatrix Multiply(const ColorMatrix& a, const ColorMatrix& b);
ColorMatrix Inverse(const ColorMatrix& m);
Vec3d Transformed(const ColorMatrix& m, const Vec3d& v);

// Linear sRGB (D65 white) to CIE XYZ, IEC 61966-2-1, and back.
inline constexpr ColorMatrix kXyzFromSrgb = {{{0.4124564, 0.3575761, 0.1804375},
                                              {0.2126729, 0.7151522, 0.0721750},
                                              {0.0193339, 0.1191920, 0.9503041}}};
inline constexpr ColorMatrix kSrgbFromXyz = {{{3.2404542, -1.5371385, -0.4985314},
                                              {-0.9692660, 1.8760108, 0.0415560},
                                              {0.0556434, -0.2040259, 1.0572252}}};
// The luminance (CIE Y) of a linear sRGB colour.
inline double SrgbLuminance(const Vec3d& rgb) {
    return kXyzFromSrgb[1][0] * rgb.x + kXyzFromSrgb[1][1] * rgb.y + kXyzFromSrgb[1][2] * rgb.z;
}

// sRGB's white, CIE D65, as a chromaticity (x, y).
inline constexpr std::array<double, 2> kD65Chromaticity = {0.3127, 0.3290};

// XYZ of chromaticity (x, y) at luminance Y = 1.
Vec3d WhiteXyz(const std::array<double, 2>& xy);
// The von Kries adaptation in Bradford's cone space that takes XYZ white `from` to XYZ white
// `to` (XYZ to XYZ).
ColorMatrix BradfordAdaptation(const Vec3d& from, const Vec3d& to);

}  // namespace pf
