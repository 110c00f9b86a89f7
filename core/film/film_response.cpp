// The film's response: imaging ratio and white balance.
#include "core/film/film_response.h"

namespace pf {
namespace {

using Matrix = std::array<std::array<double, 3>, 3>;

Matrix Multiply(const Matrix& a, const Matrix& b) {
    Matrix c{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k) c[i][j] += a[i][k] * b[k][j];
    return c;
}

Matrix Inverse(const Matrix& m) {
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    Matrix inverse{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            // The cofactor of (j, i) over the determinant.
            const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
            inverse[i][j] = (m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]) / det;
        }
    return inverse;
}

std::array<double, 3> Transformed(const Matrix& m, const std::array<double, 3>& v) {
    return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
            m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
            m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

// XYZ of chromaticity (x, y) at luminance 1.
std::array<double, 3> WhiteXyz(const std::array<double, 2>& xy) {
    return {xy[0] / xy[1], 1.0, (1 - xy[0] - xy[1]) / xy[1]};
}

// Linear sRGB (D65) to CIE XYZ (IEC 61966-2-1), and Bradford's cone space from XYZ.
constexpr Matrix kXyzFromSrgb = {{{0.4124564, 0.3575761, 0.1804375},
                                  {0.2126729, 0.7151522, 0.0721750},
                                  {0.0193339, 0.1191920, 0.9503041}}};
constexpr Matrix kLmsFromXyz = {
    {{0.8951, 0.2664, -0.1614}, {-0.7502, 1.7135, 0.0367}, {0.0389, -0.0685, 1.0296}}};
constexpr std::array<double, 2> kD65 = {0.3127, 0.3290};

}  // namespace

std::array<double, 2> DaylightChromaticity(double kelvin) {
    const double t = kelvin, t2 = t * t, t3 = t2 * t;
    const double x = t <= 7000 ? -4.6070e9 / t3 + 2.9678e6 / t2 + 0.09911e3 / t + 0.244063
                               : -2.0064e9 / t3 + 1.9018e6 / t2 + 0.24748e3 / t + 0.237040;
    return {x, -3.0 * x * x + 2.870 * x - 0.275};
}

FilmResponse FilmResponse::Make(double imaging_ratio, double white_balance_kelvin) {
    Matrix m = {{{imaging_ratio, 0, 0}, {0, imaging_ratio, 0}, {0, 0, imaging_ratio}}};
    if (white_balance_kelvin > 0) {
        const std::array<double, 3> source =
            Transformed(kLmsFromXyz, WhiteXyz(DaylightChromaticity(white_balance_kelvin)));
        const std::array<double, 3> target = Transformed(kLmsFromXyz, WhiteXyz(kD65));
        const Matrix scale = {{{target[0] / source[0], 0, 0},
                               {0, target[1] / source[1], 0},
                               {0, 0, target[2] / source[2]}}};
        const Matrix adapt = Multiply(Inverse(kLmsFromXyz), Multiply(scale, kLmsFromXyz));
        m = Multiply(Inverse(kXyzFromSrgb), Multiply(adapt, Multiply(kXyzFromSrgb, m)));
    }
    FilmResponse response;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) response.matrix[3 * i + j] = static_cast<float>(m[i][j]);
    return response;
}

}  // namespace pf
