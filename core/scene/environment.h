// An environment light: radiance arriving from infinitely far away, in every direction, either
// one colour (pbrt-v4's uniform "infinite" light, `--environment-color`) or an image over the
// sphere of directions (pbrt-v4's equal-area octahedral square, or a latitude-longitude map
// for glTF scenes and the command line). Camera rays that escape the scene see it; direct
// light samples it in proportion to radiance times solid angle (EnvironmentSampler); photons
// leave it from a disk as wide as the scene (Emitters).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/math/point2.h"
#include "core/math/vec3.h"
#include "core/scene/texture.h"
#include "core/shared/environment_map.h"

namespace pf {

enum class EnvironmentMapping : uint32_t {
    kUniform = gpu::kMappingUniform,      // radiance `scale` from every direction; no image
    kEqualArea = gpu::kMappingEqualArea,  // pbrt-v4's equal-area octahedral square, z up
    kLatLong = gpu::kMappingLatLong,      // y up: u = 1/2 + atan2(x, -z) / 2 pi, v = acos(y) / pi
};

struct Environment {
    EnvironmentMapping mapping = EnvironmentMapping::kUniform;
    Rgb scale{1.0f};  // W/(m^2 sr): a uniform light's radiance, or each texel's multiplier
    Texture image;    // linear RGB, row 0 at the top; empty for kUniform
    // World directions into the map's frame: an orthogonal matrix, row-major (its transpose
    // maps back).
    std::array<float, 9> to_map{1, 0, 0, 0, 1, 0, 0, 0, 1};
    std::string name;  // where it came from, for messages

    // The radiance arriving from unit world direction `toward` (pointing away from the scene,
    // toward the environment): the nearest texel, as pbrt-v4 looks its maps up.
    Rgb Radiance(const Vec3& toward) const;
    Vec3 ToMap(const Vec3& world) const;
    Vec3 ToWorld(const Vec3& map) const;
    // The texel a map-frame direction falls in, as y * width + x.
    uint32_t TexelOf(const Vec3& map_direction) const;
    // The solid angle of one texel of row y (sr); 4 pi for a uniform environment.
    float TexelSolidAngle(int y) const;
    // The integral of the radiance over the sphere, per channel: W/m^2 through any plane,
    // times pi R^2 the power that crosses a disk of radius R.
    Rgbd RadianceIntegral() const;
};

// An environment a render asks for in place of the scene's own (glTF has none; a pbrt scene's
// "infinite" light is replaced): `photonfarm render|submit --environment FILE` or
// `--environment-color R,G,B`, with `--environment-scale` and `--environment-rotate`.
struct EnvironmentSettings {
    std::string file;           // a latitude-longitude image, a path inside the scene's bundle
    std::optional<Rgb> color;   // or a uniform radiance, W/(m^2 sr)
    double scale = 1;           // multiplies either
    double rotate_degrees = 0;  // turns the map about world +y (the up of glTF)

    bool Given() const { return !file.empty() || color.has_value(); }
    bool operator==(const EnvironmentSettings&) const = default;
};
// The largest --environment-scale, far past any real light yet far from overflowing a sum.
inline constexpr double kMaxEnvironmentScale = 1e12;

// The maps between the unit square and the sphere (core/shared/environment_map.h).
using gpu::EqualAreaSphereToSquare;
using gpu::EqualAreaSquareToSphere;
using gpu::LatLongFromSphere;
using gpu::LatLongToSphere;

// A rotation by `degrees` about world +y (the up of glTF and of latitude-longitude maps), as
// an Environment::to_map: `--environment-rotate` turns the map this much.
std::array<float, 9> RotationAboutUp(double degrees);

// Importance sampling of an environment's directions, in proportion to each texel's average
// radiance times its solid angle, so that texel's pdf in solid angle is constant over it and
// radiance / pdf is near constant across the map: a piecewise-constant 2D distribution (rows
// by their sums, then a texel within the row) with float cumulative tables the Vulkan kernels
// read as they are. Uniform environments sample the sphere uniformly.
class EnvironmentSampler {
public:
    EnvironmentSampler() = default;
    explicit EnvironmentSampler(const Environment& environment);

    struct Sample {
        Vec3 toward;    // unit world direction, toward the environment
        Rgb radiance;   // arriving from it
        float pdf = 0;  // solid angle
    };
    // Maps (u1, u2) in [0, 1)^2 to a direction; never one of zero radiance (unless all are).
    Sample Draw(float u1, float u2) const;
    // The density in solid angle with which Draw returns world direction `toward`.
    float Pdf(const Vec3& toward) const;

    // The tables, for upload: rows + 1 entries of the rows' cumulative sums, and for each row
    // width + 1 entries of its texels' (0 and 1 at both ends); each texel's probability.
    const std::vector<float>& RowCdf() const { return row_cdf_; }
    const std::vector<float>& TexelCdf() const { return texel_cdf_; }
    const std::vector<float>& TexelProbability() const { return probability_; }

private:
    const Environment* environment_ = nullptr;
    std::vector<float> row_cdf_, texel_cdf_, probability_;
};

}  // namespace pf
