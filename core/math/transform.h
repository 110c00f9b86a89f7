// 4x4 affine transforms in double precision, for composing a scene's node hierarchy.
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <utility>

#include "core/math/vec3.h"

namespace pf {

// Row-major 4x4 matrix; points are column vectors (p' = M p).
struct Transform {
    std::array<std::array<double, 4>, 4> m{
        {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};

    static Transform FromColumnMajor(const double* values) {
        Transform t;
        for (int column = 0; column < 4; ++column)
            for (int row = 0; row < 4; ++row) t.m[row][column] = values[column * 4 + row];
        return t;
    }
    // glTF's T * R * S with rotation as a unit quaternion (x, y, z, w).
    static Transform FromTrs(const Vec3d& translation, const double rotation[4],
                             const Vec3d& scale) {
        const double x = rotation[0], y = rotation[1], z = rotation[2], w = rotation[3];
        const double r[3][3] = {
            {1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
            {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
            {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
        Transform t;
        for (int row = 0; row < 3; ++row) {
            for (int column = 0; column < 3; ++column)
                t.m[row][column] = r[row][column] * scale[column];
            t.m[row][3] = translation[row];
        }
        return t;
    }

    static Transform Translate(const Vec3d& delta) {
        Transform t;
        for (int row = 0; row < 3; ++row) t.m[row][3] = delta[row];
        return t;
    }
    static Transform Scale(const Vec3d& factors) {
        Transform t;
        for (int row = 0; row < 3; ++row) t.m[row][row] = factors[row];
        return t;
    }
    // Counter-clockwise by `degrees` about `axis` (normalised here), seen looking down the axis.
    static Transform Rotate(double degrees, const Vec3d& axis) {
        const Vec3d a = Normalize(axis);
        const double radians = degrees * (kPiD / 180.0), s = std::sin(radians),
                     c = std::cos(radians);
        Transform t;
        t.m[0] = {a.x * a.x + (1 - a.x * a.x) * c, a.x * a.y * (1 - c) - a.z * s,
                  a.x * a.z * (1 - c) + a.y * s, 0};
        t.m[1] = {a.x * a.y * (1 - c) + a.z * s, a.y * a.y + (1 - a.y * a.y) * c,
                  a.y * a.z * (1 - c) - a.x * s, 0};
        t.m[2] = {a.x * a.z * (1 - c) - a.y * s, a.y * a.z * (1 - c) + a.x * s,
                  a.z * a.z + (1 - a.z * a.z) * c, 0};
        return t;
    }

    // The inverse by Gauss-Jordan elimination with partial pivoting; nullopt when singular.
    std::optional<Transform> Inverse() const {
        std::array<std::array<double, 4>, 4> a = m;
        Transform inverse;
        for (int column = 0; column < 4; ++column) {
            int pivot = column;
            for (int row = column + 1; row < 4; ++row)
                if (std::abs(a[row][column]) > std::abs(a[pivot][column])) pivot = row;
            if (!(std::abs(a[pivot][column]) > 1e-300)) return std::nullopt;
            std::swap(a[pivot], a[column]);
            std::swap(inverse.m[pivot], inverse.m[column]);
            const double scale = 1.0 / a[column][column];
            for (int k = 0; k < 4; ++k) a[column][k] *= scale, inverse.m[column][k] *= scale;
            for (int row = 0; row < 4; ++row) {
                if (row == column) continue;
                const double factor = a[row][column];
                for (int k = 0; k < 4; ++k)
                    a[row][k] -= factor * a[column][k],
                        inverse.m[row][k] -= factor * inverse.m[column][k];
            }
        }
        if (!inverse.IsFinite()) return std::nullopt;
        return inverse;
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
        return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
                m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
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
