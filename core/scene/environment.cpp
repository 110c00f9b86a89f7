// Environment lights: the maps between images and directions, lookups and sampling.
#include "core/scene/environment.h"

#include <algorithm>
#include <cmath>

#include "core/sampling/frame.h"
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

// The world direction at the centre of texel (x, y).
Vec3 TexelCentre(const Environment& environment, int x, int y) {
    return environment.ToWorld(gpu::EnvironmentDirectionInTexel(
        static_cast<uint32_t>(environment.mapping), environment.image.width,
        environment.image.height, uint32_t(x), uint32_t(y), 0.5f, 0.5f));
}

// More than any direction of a texel can turn from its centre's, in radians, so that a cosine
// to a direction over the texel is at most its centre's plus this.
float TexelSpread(const Environment& environment) {
    return 3 * kPi *
           (1.0f / float(environment.image.width) + 1.0f / float(environment.image.height));
}

}  // namespace

std::optional<float> EnvironmentPortal::Exit(const Vec3& origin, const Vec3& toward) const {
    float t = 0;
    if (!gpu::PortalExit(corner, edge_u, edge_v, normal, origin, toward, t)) return std::nullopt;
    return t;
}

absl::StatusOr<EnvironmentPortal> EnvironmentPortal::FromCorners(const std::array<Vec3, 4>& p) {
    for (const Vec3& corner : p)
        if (!IsFinite(corner)) return absl::InvalidArgumentError("a corner is not finite");
    const Vec3 sides[4] = {p[1] - p[0], p[2] - p[1], p[2] - p[3], p[3] - p[0]};
    for (const Vec3& side : sides)
        if (!(LengthSquared(side) > 0)) return absl::InvalidArgumentError("two corners coincide");
    const Vec3 p01 = Normalize(sides[0]), p12 = Normalize(sides[1]), p32 = Normalize(sides[2]),
               p03 = Normalize(sides[3]);
    // pbrt-v4's checks: opposite sides parallel, adjacent ones perpendicular.
    if (std::abs(Dot(p01, p32) - 1) > 1e-3f || std::abs(Dot(p12, p03) - 1) > 1e-3f ||
        std::abs(Dot(p01, p12)) > 1e-3f || std::abs(Dot(p12, p32)) > 1e-3f ||
        std::abs(Dot(p32, p03)) > 1e-3f || std::abs(Dot(p03, p01)) > 1e-3f)
        return absl::InvalidArgumentError(
            "its corners are not a rectangle, in order around it (pbrt-v4's portal is one)");
    return EnvironmentPortal{p[0], sides[0], sides[3], Normalize(Cross(p03, p01))};
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
    return gpu::EnvironmentTexel(static_cast<uint32_t>(mapping), image.width, image.height, d);
}

Rgb Environment::Radiance(const Vec3& toward) const {
    if (mapping == EnvironmentMapping::kUniform) return scale;
    return image.texels[TexelOf(ToMap(toward))] * scale;
}

float Environment::TexelSolidAngle(int y) const {
    if (mapping == EnvironmentMapping::kUniform) return 4 * kPi;
    return gpu::EnvironmentTexelSolidAngle(static_cast<uint32_t>(mapping), image.width,
                                           image.height, y);
}

Rgbd Environment::RadianceIntegral() const {
    if (mapping == EnvironmentMapping::kUniform) return Rgbd(scale) * (4 * kPiD);
    Rgbd sum(0.0);
    for (int y = 0; y < image.height; ++y) {
        Rgbd row(0.0);
        for (int x = 0; x < image.width; ++x)
            row += Rgbd(Max(image.texels[size_t(y) * image.width + x], Rgb(0.0f)));
        sum += row * double(TexelSolidAngle(y));
    }
    return sum * Rgbd(scale);
}

Rgbd Environment::Irradiance(const Vec3& normal) const {
    if (mapping == EnvironmentMapping::kUniform) return Rgbd(scale) * kPiD;
    Rgbd sum(0.0);
    for (int y = 0; y < image.height; ++y) {
        Rgbd row(0.0);
        for (int x = 0; x < image.width; ++x) {
            const double cosine = Dot(TexelCentre(*this, x, y), normal);
            if (cosine > 0)
                row += Rgbd(Max(image.texels[size_t(y) * image.width + x], Rgb(0.0f))) * cosine;
        }
        sum += row * double(TexelSolidAngle(y));
    }
    return sum * Rgbd(scale);
}

EnvironmentSampler::EnvironmentSampler(const Environment& environment, std::optional<Vec3> facing)
    : environment_(&environment), facing_(facing) {
    if (environment.mapping == EnvironmentMapping::kUniform) {
        facing_flux_bound_ = kPi * MaxComponent(environment.scale);  // L cos / (cos / pi)
        return;
    }
    const int width = environment.image.width, height = environment.image.height;
    const float spread = TexelSpread(environment);
    std::vector<double> rows(height);
    std::vector<std::vector<double>> weights(height);
    double total = 0;
    for (int y = 0; y < height; ++y) {
        const double solid_angle = environment.TexelSolidAngle(y);
        weights[y].resize(width);
        for (int x = 0; x < width; ++x) {
            const Rgb radiance =
                environment.image.texels[size_t(y) * width + x] * environment.scale;
            weights[y][x] = std::max(0.0, double(Average(radiance))) * solid_angle;
            if (facing)
                weights[y][x] *=
                    std::max(0.0f, Dot(TexelCentre(environment, x, y), *facing) + spread);
            rows[y] += weights[y][x];
        }
        total += rows[y];
    }
    AppendCdf(rows, total, &row_cdf_);
    probability_.reserve(size_t(width) * height);
    for (int y = 0; y < height; ++y) {
        AppendCdf(weights[y], rows[y], &texel_cdf_);
        for (int x = 0; x < width; ++x) {
            probability_.push_back(static_cast<float>(total > 0 ? weights[y][x] / total
                                                                : 1.0 / (double(width) * height)));
            if (!facing || !(weights[y][x] > 0)) continue;
            // A direction of the texel: cosine at most its centre's plus the spread.
            const float cosine =
                std::min(1.0f, Dot(TexelCentre(environment, x, y), *facing) + spread);
            const double pdf = probability_.back() / environment.TexelSolidAngle(y);
            const Rgb radiance =
                environment.image.texels[size_t(y) * width + x] * environment.scale;
            facing_flux_bound_ = std::max(
                facing_flux_bound_, static_cast<float>(MaxComponent(radiance) * cosine / pdf));
        }
    }
}

EnvironmentSampler::Sample EnvironmentSampler::Draw(float u1, float u2) const {
    const Environment& environment = *environment_;
    Sample sample;
    if (environment.mapping == EnvironmentMapping::kUniform) {
        sample.radiance = environment.scale;
        if (facing_) {
            const Vec3 local = SampleCosineHemisphere(u1, u2);
            sample.toward = ToWorld(FrameFromNormal(*facing_), local);
            sample.pdf = local.z / kPi;
            return sample;
        }
        sample.toward = SampleUniformSphere(u1, u2);
        sample.pdf = 1 / (4 * kPi);
        return sample;
    }
    const auto width = static_cast<uint32_t>(environment.image.width),
               height = static_cast<uint32_t>(environment.image.height);
    float fy = 0, fx = 0;
    const uint32_t y = FindInterval(row_cdf_.data(), height, u1, &fy);
    const uint32_t x = FindInterval(texel_cdf_.data() + size_t(y) * (width + 1), width, u2, &fx);
    const uint32_t texel = y * width + x;
    const Vec3 direction = gpu::EnvironmentDirectionInTexel(
        static_cast<uint32_t>(environment.mapping), environment.image.width,
        environment.image.height, x, y, fx, fy);
    sample.toward = environment.ToWorld(direction);
    sample.radiance = environment.image.texels[texel] * environment.scale;
    sample.pdf = static_cast<float>(probability_[texel] / environment.TexelSolidAngle(int(y)));
    return sample;
}

float EnvironmentSampler::Pdf(const Vec3& toward) const {
    const Environment& environment = *environment_;
    if (environment.mapping == EnvironmentMapping::kUniform)
        return facing_ ? std::max(0.0f, Dot(toward, *facing_)) / kPi : 1 / (4 * kPi);
    const uint32_t texel = environment.TexelOf(environment.ToMap(toward));
    const int y = static_cast<int>(texel / static_cast<uint32_t>(environment.image.width));
    return static_cast<float>(probability_[texel] / environment.TexelSolidAngle(y));
}

}  // namespace pf
