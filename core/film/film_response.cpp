// The film's response: imaging ratio and white balance.
#include "core/film/film_response.h"

#include "core/film/color_space.h"

namespace pf {

std::array<double, 2> DaylightChromaticity(double kelvin) {
    const double t = kelvin, t2 = t * t, t3 = t2 * t;
    const double x = t <= 7000 ? -4.6070e9 / t3 + 2.9678e6 / t2 + 0.09911e3 / t + 0.244063
                               : -2.0064e9 / t3 + 1.9018e6 / t2 + 0.24748e3 / t + 0.237040;
    return {x, -3.0 * x * x + 2.870 * x - 0.275};
}

FilmResponse FilmResponse::Make(double imaging_ratio, double white_balance_kelvin) {
    ColorMatrix m = {{{imaging_ratio, 0, 0}, {0, imaging_ratio, 0}, {0, 0, imaging_ratio}}};
    if (white_balance_kelvin > 0) {
        const ColorMatrix adapt = BradfordAdaptation(
            WhiteXyz(DaylightChromaticity(white_balance_kelvin)), WhiteXyz(kD65Chromaticity));
        m = Multiply(kSrgbFromXyz, Multiply(adapt, Multiply(kXyzFromSrgb, m)));
    }
    FilmResponse response;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) response.matrix[3 * i + j] = static_cast<float>(m[i][j]);
    return response;
}

}  // namespace pf
