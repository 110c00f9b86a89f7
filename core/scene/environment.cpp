// Environment lights: the maps between images and directions, lookups and sampling.
#include "core/scene/environment.h"

#include <algorithm>
#include <cmath>

#include "core/sampling/sampling.h"

namespace pf {
namespace {

// The first index i of cdf (ascending, cdf[0] = 0, cdf[n] = 1) with cdf[i] <= u < cdf[i + 1],
// which never lands on an empty interval; and u's position inside it, in [0, 1).
uint32_t FindInterval(const float* cdf, uint32_t n, float u, float* fraction) {
    const uint32_t i = static_cast<uint32_t>(std::upper_bound(cdf + 1, cdf + n + 1, u) - (cdf + 1));
    const uint32_t index = std::min(i, n - 1);
    const float width = cdf[index + 1] - cdf[index];
    *fraction = width > 0 ? std::clamp((u - cdf[index]) / width, 0.0f, 0x1.fffffep-1f) : 0.0f;
    return index;
}

// Cumulative sums of `weights` normalised to end at exactly 1 (all zero: uniform).
void AppendCdf(const std::vector<double>& weights, double total, std::vector<float>* cdf) {
    const size_t n = weights.size();
    double sum = 0;
    cdf->push_back(0.0f);
    for (size_t i = 0; i < n; ++i) {
        sum += total > 0 ? weights[i] : 1.0;
        cdf->push_back(static_cast<float>(sum / (total > 0 ? total : double(n))));
    }
    cdf->back() = 1.0f;
}

}  // namespace

Vec3 EqualAreaSquareToSphere(Point2 p) {
    const float u = 2 * p.x - 1, v = 2 * p.y - 1;
    const float up = std::abs(u), vp = std::abs(v);
    const float signed_distance = 1 - (up + vp);
    const float r = 1 - std::abs(signed_distance);
    const float phi = (r == 0 ? 1 : (vp - up) / r + 1) * kPi / 4;
    const float z = std::copysign(1 - r * r, signed_distance);
    const float sin_theta = r * std::sqrt(std::max(0.0f, 2 - r * r));
    return {std::copysign(std::cos(phi), u) * sin_theta,
            std::copysign(std::sin(phi), v) * sin_theta, z};
}

Point2 EqualAreaSphereToSquare(const Vec3& d) {
    const float x = std::abs(d.x), y = std::abs(d.y), z = std::abs(d.z);
    const float r = std::sqrt(std::max(0.0f, 1 - z));
    const float a = std::max(x, y), b = a == 0 ? 0 : std::min(x, y) / a;
    float phi = std::atan(b) * (2 / kPi);
    if (x < y) phi = 1 - phi;
    float v = phi * r, u = r - v;
    if (d.z < 0) {  // the lower hemisphere folds out over the square's corners
        std::swap(u, v);
        u = 1 - u, v = 1 - v;
    }
    u = std::copysign(u, d.x), v = std::copysign(v, d.y);
    return {0.5f * (u + 1), 0.5f * (v + 1)};
}

Vec3 LatLongToSphere(Point2 p) {
    const float phi = 2 * kPi * (p.x - 0.5f), theta = kPi * p.y;
    const float sin_theta = std::sin(theta);
    return {sin_theta * std::sin(phi), std::cos(theta), -sin_theta * std::cos(phi)};
}

Point2 LatLongFromSphere(const Vec3& d) {
    return {0.5f + std::atan2(d.x, -d.z) / (2 * kPi),
            std::acos(std::clamp(d.y, -1.0f, 1.0f)) / kPi};
}

std::array<float, 9> RotationAboutUp(double degrees) {
    // to_map turns world directions by -degrees, so the map turns by +degrees.
    const double a = -degrees * kPiD / 180;
    const auto c = static_cast<float>(std::cos(a)), s = static_cast<float>(std::sin(a));
    return {c, 0, s, 0, 1, 0, -s, 0, c};
}

Vec3 Environment::ToMap(const Vec3& w) const {
    const float* m = to_map.data();
    return Normalize(Vec3{m[0] * w.x + m[1] * w.y + m[2] * w.z,
                          m[3] * w.x + m[4] * w.y + m[5] * w.z,
                          m[6] * w.x + m[7] * w.y + m[8] * w.z});
}

Vec3 Environment::ToWorld(const Vec3& d) const {
    const float* m = to_map.data();
    return Normalize(Vec3{m[0] * d.x + m[3] * d.y + m[6] * d.z,
                          m[1] * d.x + m[4] * d.y + m[7] * d.z,
                          m[2] * d.x + m[5] * d.y + m[8] * d.z});
}

uint32_t Environment::TexelOf(const Vec3& d) const {
    const Point2 uv = mapping == EnvironmentMapping::kEqualArea ? EqualAreaSphereToSquare(d)
                                                                : LatLongFromSphere(d);
    const int x = std::clamp(static_cast<int>(uv.x * image.width), 0, image.width - 1);
    const int y = std::clamp(static_cast<int>(uv.y * image.height), 0, image.height - 1);
    return static_cast<uint32_t>(y) * static_cast<uint32_t>(image.width) + static_cast<uint32_t>(x);
}

Rgb Environment::Radiance(const Vec3& toward) const {
    if (mapping == EnvironmentMapping::kUniform) return scale;
    return image.texels[TexelOf(ToMap(toward))] * scale;
}

double Environment::TexelSolidAngle(int y) const {
    if (mapping == EnvironmentMapping::kUniform) return 4 * kPiD;
    if (mapping == EnvironmentMapping::kEqualArea)
        return 4 * kPiD / (double(image.width) * double(image.height));
    const double theta0 = kPiD * y / image.height, theta1 = kPiD * (y + 1) / image.height;
    return 2 * kPiD / image.width * (std::cos(theta0) - std::cos(theta1));
}

Rgbd Environment::RadianceIntegral() const {
    if (mapping == EnvironmentMapping::kUniform) return Rgbd(scale) * (4 * kPiD);
    Rgbd sum(0.0);
    for (int y = 0; y < image.height; ++y) {
        Rgbd row(0.0);
        for (int x = 0; x < image.width; ++x)
            row += Rgbd(Max(image.texels[size_t(y) * image.width + x], Rgb(0.0f)));
        sum += row * TexelSolidAngle(y);
    }
    return sum * Rgbd(scale);
}

EnvironmentSampler::EnvironmentSampler(const Environment& environment)
    : environment_(&environment) {
    if (environment.mapping == EnvironmentMapping::kUniform) return;
    const int width = environment.image.width, height = environment.image.height;
    std::vector<double> rows(height), texels(width);
    std::vector<std::vector<double>> weights(height);
    double total = 0;
    for (int y = 0; y < height; ++y) {
        const double solid_angle = environment.TexelSolidAngle(y);
        weights[y].resize(width);
        for (int x = 0; x < width; ++x) {
            const Rgb radiance =
                environment.image.texels[size_t(y) * width + x] * environment.scale;
            weights[y][x] = std::max(0.0, double(Average(radiance))) * solid_angle;
            rows[y] += weights[y][x];
        }
        total += rows[y];
    }
    AppendCdf(rows, total, &row_cdf_);
    probability_.reserve(size_t(width) * height);
    for (int y = 0; y < height; ++y) {
        AppendCdf(weights[y], rows[y], &texel_cdf_);
        for (int x = 0; x < width; ++x)
            probability_.push_back(static_cast<float>(total > 0 ? weights[y][x] / total
                                                                : 1.0 / (double(width) * height)));
    }
}

EnvironmentSampler::Sample EnvironmentSampler::Draw(float u1, float u2) const {
    const Environment& environment = *environment_;
    Sample sample;
    if (environment.mapping == EnvironmentMapping::kUniform) {
        sample.toward = SampleUniformSphere(u1, u2);
        sample.radiance = environment.scale;
        sample.pdf = 1 / (4 * kPi);
        return sample;
    }
    const auto width = static_cast<uint32_t>(environment.image.width),
               height = static_cast<uint32_t>(environment.image.height);
    float fy = 0, fx = 0;
    const uint32_t y = FindInterval(row_cdf_.data(), height, u1, &fy);
    const uint32_t x = FindInterval(texel_cdf_.data() + size_t(y) * (width + 1), width, u2, &fx);
    const uint32_t texel = y * width + x;
    // Uniform in solid angle within the texel: the equal-area square is so already; in a
    // latitude-longitude map, uniform in longitude and in the cosine of the polar angle.
    Vec3 direction;
    if (environment.mapping == EnvironmentMapping::kEqualArea) {
        direction = EqualAreaSquareToSphere({(x + fx) / width, (y + fy) / height});
    } else {
        const float cos0 = std::cos(kPi * y / height), cos1 = std::cos(kPi * (y + 1) / height);
        const float cos_theta = cos0 + fy * (cos1 - cos0);
        const float sin_theta = std::sqrt(std::max(0.0f, 1 - cos_theta * cos_theta));
        const float phi = 2 * kPi * ((x + fx) / width - 0.5f);
        direction = {sin_theta * std::sin(phi), cos_theta, -sin_theta * std::cos(phi)};
    }
    sample.toward = environment.ToWorld(direction);
    sample.radiance = environment.image.texels[texel] * environment.scale;
    sample.pdf = static_cast<float>(probability_[texel] / environment.TexelSolidAngle(int(y)));
    return sample;
}

float EnvironmentSampler::Pdf(const Vec3& toward) const {
    const Environment& environment = *environment_;
    if (environment.mapping == EnvironmentMapping::kUniform) return 1 / (4 * kPi);
    const uint32_t texel = environment.TexelOf(environment.ToMap(toward));
    const int y = static_cast<int>(texel / static_cast<uint32_t>(environment.image.width));
    return static_cast<float>(probability_[texel] / environment.TexelSolidAngle(y));
}

}  // namespace pf
