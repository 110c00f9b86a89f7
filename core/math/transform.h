// 4x4 affine transforms in double precision, for composing a scene's node hierarchy.
#pragma once

#include <array>
#include <cmath>

#include "core/math/vec3.h"

namespace pf {

// Row-major 4x4 matrix; points are column vectors (p' = M p).
struct Transform {
    std::array<std::array<double, 4>, 4> m{{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};

    static Transform FromColumnMajor(const double* values) {
        Transform t;
        for (int column = 0; column < 4; ++column)
            for (int row = 0; row < 4; ++row) t.m[row][column] = values[column * 4 + row];
        return t;
    }
    // glTF's T * R * S with rotation as a unit quaternion (x, y, z, w).
    static Transform FromTrs(const Vec3d& translation, const double rotation[4], const Vec3d& scale) {
        const double x = rotation[0], y = rotation[1], z = rotation[2], w = rotation[3];
        const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                                {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                                {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
        Transform t;
        for (int row = 0; row < 3; ++row) {
            for (int column = 0; column < 3; ++column) t.m[row][column] = r[row][column] * scale[column];
            t.m[row][3] = translation[row];
        }
        return t;
    }

    Transform operator*(const Transform& o) const {
        Transform result;
        for (int row = 0; row < 4; ++row)
            for (int column = 0; column < 4; ++column) {
                double sum = 0;
                for (int k = 0; k < 4; ++k) sum += m[row][k] * o.m[k][column];
                result.m[row][column] = sum;
            }
        return result;
    }

    Vec3d ApplyPoint(const Vec3d& p) const {
        return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
                m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
                m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
    }
    Vec3d ApplyVector(const Vec3d& v) const {
        return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
    }
    // Normals transform by the inverse transpose of the linear part; the cofactor matrix is
    // that up to a positive or negative scale, which normalisation and Determinant's sign undo.
    Vec3d ApplyNormal(const Vec3d& n) const {
        const Vec3d c0{m[0][0], m[1][0], m[2][0]}, c1{m[0][1], m[1][1], m[2][1]},
            c2{m[0][2], m[1][2], m[2][2]};
        const Vec3d r0 = Cross(c1, c2), r1 = Cross(c2, c0), r2 = Cross(c0, c1);
        const Vec3d out = r0 * n.x + r1 * n.y + r2 * n.z;
        return Determinant() < 0 ? -out : out;
    }
    double Determinant() const {
        return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
               m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    }
    bool IsFinite() const {
        for (const auto& row : m)
            for (double v : row)
                if (!std::isfinite(v)) return false;
        return true;
    }
};

}  // namespace pf
