// Three-component vectors for positions, directions and RGB colours. Vec3 is float (geometry,
// per-photon colours), Vec3d is double (sums that grow with the photon count).
#pragma once

#include <algorithm>
#include <cmath>

namespace pf {

template <typename T>
struct Vec3T {
    T x = 0, y = 0, z = 0;

    constexpr Vec3T() = default;
    constexpr Vec3T(T x_in, T y_in, T z_in) : x(x_in), y(y_in), z(z_in) {}
    constexpr explicit Vec3T(T s) : x(s), y(s), z(s) {}
    template <typename U>
    constexpr explicit Vec3T(const Vec3T<U>& v)
        : x(static_cast<T>(v.x)), y(static_cast<T>(v.y)), z(static_cast<T>(v.z)) {}

    constexpr T operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr T& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }

    constexpr Vec3T operator+(const Vec3T& o) const { return {x + o.x, y + o.y, z + o.z}; }
    constexpr Vec3T operator-(const Vec3T& o) const { return {x - o.x, y - o.y, z - o.z}; }
    constexpr Vec3T operator*(const Vec3T& o) const { return {x * o.x, y * o.y, z * o.z}; }
    constexpr Vec3T operator/(const Vec3T& o) const { return {x / o.x, y / o.y, z / o.z}; }
    constexpr Vec3T operator*(T s) const { return {x * s, y * s, z * s}; }
    constexpr Vec3T operator/(T s) const { return {x / s, y / s, z / s}; }
    constexpr Vec3T operator-() const { return {-x, -y, -z}; }
    constexpr Vec3T& operator+=(const Vec3T& o) { return *this = *this + o; }
    constexpr Vec3T& operator-=(const Vec3T& o) { return *this = *this - o; }
    constexpr Vec3T& operator*=(const Vec3T& o) { return *this = *this * o; }
    constexpr Vec3T& operator*=(T s) { return *this = *this * s; }
    constexpr Vec3T& operator/=(T s) { return *this = *this / s; }
    constexpr bool operator==(const Vec3T& o) const = default;
};

using Vec3 = Vec3T<float>;
using Vec3d = Vec3T<double>;
using Rgb = Vec3;    // linear RGB radiance, flux or reflectance
using Rgbd = Vec3d;  // linear RGB sums in double precision

template <typename T>
constexpr Vec3T<T> operator*(T s, const Vec3T<T>& v) {
    return v * s;
}
template <typename T>
constexpr T Dot(const Vec3T<T>& a, const Vec3T<T>& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <typename T>
constexpr Vec3T<T> Cross(const Vec3T<T>& a, const Vec3T<T>& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <typename T>
constexpr T LengthSquared(const Vec3T<T>& v) {
    return Dot(v, v);
}
template <typename T>
T Length(const Vec3T<T>& v) {
    return std::sqrt(Dot(v, v));
}
template <typename T>
Vec3T<T> Normalize(const Vec3T<T>& v) {
    return v / Length(v);
}
template <typename T>
constexpr Vec3T<T> Min(const Vec3T<T>& a, const Vec3T<T>& b) {
    return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
template <typename T>
constexpr Vec3T<T> Max(const Vec3T<T>& a, const Vec3T<T>& b) {
    return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
template <typename T>
constexpr Vec3T<T> Abs(const Vec3T<T>& v) {
    return {std::abs(v.x), std::abs(v.y), std::abs(v.z)};
}
template <typename T>
constexpr T MaxComponent(const Vec3T<T>& v) {
    return std::max(v.x, std::max(v.y, v.z));
}
template <typename T>
constexpr T MinComponent(const Vec3T<T>& v) {
    return std::min(v.x, std::min(v.y, v.z));
}
template <typename T>
constexpr T Average(const Vec3T<T>& v) {
    return (v.x + v.y + v.z) / T(3);
}
template <typename T>
bool IsFinite(const Vec3T<T>& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
template <typename T>
constexpr bool IsBlack(const Vec3T<T>& v) {
    return v.x == 0 && v.y == 0 && v.z == 0;
}

// Flips n to lie in the hemisphere of v.
template <typename T>
constexpr Vec3T<T> FaceForward(const Vec3T<T>& n, const Vec3T<T>& v) {
    return Dot(n, v) < 0 ? -n : n;
}

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr double kPiD = 3.14159265358979323846;

}  // namespace pf
