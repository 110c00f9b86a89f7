// A hit point: where a camera path first reached a diffuse surface (Hachisuka et al. 2008,
// section 4.1). Created once by the camera pass and fixed for the whole render.
#pragma once

#include <cstdint>

#include "core/math/vec3.h"

namespace pf {

// A hit point on a diffuse surface under no coat.
inline constexpr uint32_t kNoCoat = 0xffffffffu;

// How a photon came to land where it did, as one bit (PhotonDeposit::kind); a hit point
// gathers the kinds its mask names (HitPoint::gathers).
inline constexpr uint32_t kDirectPhoton = 1;   // at its first surface: direct light
inline constexpr uint32_t kCausticPhoton = 2;  // after specular and rough bounces alone
inline constexpr uint32_t kDiffusePhoton = 4;  // after a diffuse bounce (or a coat's return)
// ppm's and sppm's hit points: every photon but direct light, which is sampled apart.
inline constexpr uint32_t kScatteredPhotons = kCausticPhoton | kDiffusePhoton;
// rpm's gather hits: all light leaving the surface, as classic photon mapping's global map
// holds it for final gathering.
inline constexpr uint32_t kAllPhotons = kDirectPhoton | kCausticPhoton | kDiffusePhoton;

struct HitPoint {
    Vec3 position;   // world space
    Vec3 normal;     // unit shading normal, turned toward the camera path's side
    Rgb weight;      // camera-path throughput x diffuse BSDF (albedo / pi), 1/sr
    uint32_t pixel;  // y * width + x
    // The material whose coat covers the surface (light reaching the hit point crosses it:
    // core/shared/coat.h), or kNoCoat.
    uint32_t coat = kNoCoat;
    // The photons it gathers: kScatteredPhotons but for rpm, whose camera hit points take
    // caustics alone (kCausticPhoton: direct light is sampled, the rest comes through the
    // gather hits) and whose gather hits take kAllPhotons.
    uint32_t gathers = kScatteredPhotons;
};

}  // namespace pf
