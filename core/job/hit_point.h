// A hit point: where a camera path first reached a diffuse surface (Hachisuka et al. 2008,
// section 4.1), or, for reverse photon mapping, where a final-gather ray from one landed.
// Created by the camera pass: once for ppm, every epoch for sppm and rpm.
#pragma once

#include <cstdint>

#include "core/math/vec3.h"
#include "core/shared/photon_kinds.h"

namespace pf {

// A hit point on a diffuse surface under no coat.
inline constexpr uint32_t kNoCoat = 0xffffffffu;

// How a photon came to land where it did, and which kinds a hit point gathers
// (HitPoint::gathers): core/shared/photon_kinds.h.
using gpu::kAllPhotons;
using gpu::kCausticPhoton;
using gpu::kDiffusePhoton;
using gpu::kDirectPhoton;
using gpu::kScatteredPhotons;

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
