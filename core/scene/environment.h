// An environment light: radiance arriving from infinitely far away, in every direction, either
// one colour (pbrt-v4's uniform "infinite" light, `--environment-color`) or an image over the
// sphere of directions (pbrt-v4's equal-area octahedral square, or a latitude-longitude map
// for glTF scenes and the command line). Camera rays that escape the scene see it; direct
// light samples it in proportion to radiance times solid angle (EnvironmentSampler); photons
// leave it from a disk as wide as the scene (Emitters). With a portal (pbrt-v4's), it shines
// in through that rectangle alone, and photons and light samples go through it.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
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

// pbrt-v4's portal (PortalImageInfiniteLight): a rectangle of the scene, in world space (a
// window), through which alone the environment is seen. A ray finds the environment only
// where it leaves through the rectangle toward its outer side; photons enter through it and
// light samples aim at it, so an interior lit through a window wastes neither.
struct EnvironmentPortal {
    Vec3 corner;          // pbrt's portal[0]
    Vec3 edge_u, edge_v;  // portal[1] - portal[0], portal[3] - portal[0]: perpendicular
    Vec3 normal;          // unit, toward the environment: pbrt-v4's portal frame z, p03 x p01

    float Area() const { return Length(edge_u) * Length(edge_v); }
    // The distance along unit `toward` at which a ray from `origin` leaves through the portal
    // toward the environment; nullopt where it does not (it misses the rectangle, runs
    // parallel to it or inward, or starts outside).
    std::optional<float> Exit(const Vec3& origin, const Vec3& toward) const;
    // The portal's four corners in pbrt's order, each within 1e-3 of a rectangle (pbrt-v4's
    // check): an error naming what is wrong otherwise.
    static absl::StatusOr<EnvironmentPortal> FromCorners(const std::array<Vec3, 4>& p);
};

struct Environment {
    EnvironmentMapping mapping = EnvironmentMapping::kUniform;
    Rgb scale{1.0f};  // W/(m^2 sr): a uniform light's radiance, or each texel's multiplier
    Texture image;    // linear RGB, row 0 at the top; empty for kUniform
    // World directions into the map's frame: an orthogonal matrix, row-major (its transpose
    // maps back).
    std::array<float, 9> to_map{1, 0, 0, 0, 1, 0, 0, 0, 1};
    std::string name;  // where it came from, for messages
    std::optional<EnvironmentPortal> portal;

    // The radiance arriving from unit world direction `toward` (pointing away from the scene,
    // toward the environment): the nearest texel, as pbrt-v4 looks its maps up.
    Rgb Radiance(const Vec3& toward) const;
    // What a ray from `origin` toward `toward` that escapes the scene finds: Radiance, or 0
    // where a portal does not let it out.
    Rgb RadianceFrom(const Vec3& origin, const Vec3& toward) const {
        return !portal || portal->Exit(origin, toward) ? Radiance(toward) : Rgb(0.0f);
    }
    Vec3 ToMap(const Vec3& world) const;
    Vec3 ToWorld(const Vec3& map) const;
    // The texel a map-frame direction falls in, as y * width + x.
    uint32_t TexelOf(const Vec3& map_direction) const;
    // The solid angle of one texel of row y (sr); 4 pi for a uniform environment.
    float TexelSolidAngle(int y) const;
    // The integral of the radiance over the sphere, per channel: W/m^2 through any plane,
    // times pi R^2 the power that crosses a disk of radius R.
    Rgbd RadianceIntegral() const;
    // The irradiance on a plane facing unit `normal`, the integral of the radiance times the
    // cosine over the hemisphere around it (at each texel's centre): W/m^2, times a portal's
    // area the power that comes in through it.
    Rgbd Irradiance(const Vec3& normal) const;
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
//
// Facing a direction n (the photons of a portal, which need only the hemisphere around n and
// weigh each direction by its cosine to n), each texel's weight is also times its largest
// cosine to n (bounded from its centre's), so the texels wholly behind are never drawn, and a
// uniform environment is sampled by the cosine about n.
class EnvironmentSampler {
public:
    EnvironmentSampler() = default;
    explicit EnvironmentSampler(const Environment& environment,
                                std::optional<Vec3> facing = std::nullopt);

    struct Sample {
        Vec3 toward;    // unit world direction, toward the environment
        Rgb radiance;   // arriving from it
        float pdf = 0;  // solid angle
    };
    // Maps (u1, u2) in [0, 1)^2 to a direction; never one of zero radiance (unless all are).
    Sample Draw(float u1, float u2) const;
    // The density in solid angle with which Draw returns world direction `toward`.
    float Pdf(const Vec3& toward) const;

    // Facing n: the largest radiance x cosine to n / pdf of any direction Draw returns, in any
    // channel (a portal's photon carries at most this times its area).
    float FacingFluxBound() const { return facing_flux_bound_; }
    // The tables, for upload: rows + 1 entries of the rows' cumulative sums, and for each row
    // width + 1 entries of its texels' (0 and 1 at both ends); each texel's probability.
    const std::vector<float>& RowCdf() const { return row_cdf_; }
    const std::vector<float>& TexelCdf() const { return texel_cdf_; }
    const std::vector<float>& TexelProbability() const { return probability_; }

private:
    const Environment* environment_ = nullptr;
    std::optional<Vec3> facing_;
    float facing_flux_bound_ = 0;
    std::vector<float> row_cdf_, texel_cdf_, probability_;
};

}  // namespace pf
