// Colour-space matrices and chromatic adaptation.
#include "core/film/color_space.h"

namespace pf {

ColorMatrix Multiply(const ColorMatrix& a, const ColorMatrix& b) {
    ColorMatrix c{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k) c[i][j] += a[i][k] * b[k][j];
    return c;
}

ColorMatrix Inverse(const ColorMatrix& m) {
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    ColorMatrix inverse{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            // The cofactor of (j, i) over the determinant.
            const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
            inverse[i][j] = (m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]) / det;
        }
    return inverse;
}

Vec3d Transformed(const ColorMatrix& m, const Vec3d& v) {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
            m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}

Vec3d WhiteXyz(const std::array<double, 2>& xy) {
    return {xy[0] / xy[1], 1.0, (1 - xy[0] - xy[1]) / xy[1]};
}

ColorMatrix BradfordAdaptation(const Vec3d& from, const Vec3d& to) {
    constexpr ColorMatrix kLmsFromXyz = {
        {{0.8951, 0.2664, -0.1614}, {-0.7502, 1.7135, 0.0367}, {0.0389, -0.0685, 1.0296}}};
    const Vec3d source = Transformed(kLmsFromXyz, from), target = Transformed(kLmsFromXyz, to);
    const ColorMatrix scale = {
        {{target.x / source.x, 0, 0}, {0, target.y / source.y, 0}, {0, 0, target.z / source.z}}};
    return Multiply(Inverse(kLmsFromXyz), Multiply(scale, kLmsFromXyz));
}

}  // namespace pf
