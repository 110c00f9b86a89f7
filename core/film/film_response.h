// What a film makes of the radiance that reaches it, as pbrt-v4's PixelSensor does with its
// "cie1931" sensor: pixel = imaging ratio (exposure time x ISO / 100) x radiance, and with a
// white balance temperature a von Kries adaptation (in Bradford's cone space) from the CIE
// daylight illuminant of that temperature to the output's white, D65. The identity unless a
// scene's Film asks (docs/scenes.md); applied to every image a job shows, so images, snapshots
// and errors against a pbrt-v4 reference all read in pbrt's units.
#pragma once

#include <array>

#include "core/film/image.h"
#include "core/math/vec3.h"

namespace pf {

struct FilmResponse {
    // Linear sRGB in, linear sRGB out, row-major, the imaging ratio included.
    std::array<float, 9> matrix{1, 0, 0, 0, 1, 0, 0, 0, 1};

    // `white_balance_kelvin` 0: none; otherwise in [4000, 25000] (the CIE daylight locus).
    static FilmResponse Make(double imaging_ratio, double white_balance_kelvin);
    bool IsIdentity() const { return matrix == FilmResponse{}.matrix; }
    // How much brighter a grey comes out: the rows' sums averaged (the imaging ratio where
    // there is no white balance); what an absolute error in radiance becomes in the image.
    float Gain() const {
        float sum = 0;
        for (float m : matrix) sum += m;
        return sum / 3;
    }
    Rgb Apply(const Rgb& rgb) const {
        const float* m = matrix.data();
        return {m[0] * rgb.x + m[1] * rgb.y + m[2] * rgb.z,
                m[3] * rgb.x + m[4] * rgb.y + m[5] * rgb.z,
                m[6] * rgb.x + m[7] * rgb.y + m[8] * rgb.z};
    }
    void Apply(Image* image) const {
        if (IsIdentity()) return;
        for (Rgb& pixel : image->pixels) pixel = Apply(pixel);
    }
};

// The chromaticity (x, y) of the CIE daylight illuminant at `kelvin` (4000 to 25000 K).
std::array<double, 2> DaylightChromaticity(double kelvin);

}  // namespace pf
