// Final-gather rays (Jensen 1996): from a diffuse point, a ray follows specular and rough
// bounces to the first diffuse surface it reaches, whose outgoing light the caller reads there
// (classic photon mapping from its global map; reverse photon mapping keeps the landing as a
// hit point its photons gather at).
#pragma once

#include <cstdint>
#include <optional>

#include "core/geometry/ray.h"
#include "core/geometry/tracer.h"
#include "core/math/vec3.h"
#include "core/sampling/rng.h"
#include "core/scene/scattering.h"
#include "core/scene/scene.h"

namespace pf {

// Gather rays follow specular and rough bounces this far at most before giving up.
inline constexpr int kMaxGatherDepth = 16;

// What the radiance at a diffuse base is worth where a path reached it (ArriveAtCoat): 1
// uncoated; under a coat the weight of the way in times CoatInside.
inline float CoatedRadianceFactor(const Material& material, const CoatArrival& arrival) {
    if (!material.HasCoat()) return 1.0f;
    return arrival.weight * CoatInside(CoatOf(material));
}

// Where a gather ray landed on a diffuse surface.
struct DiffuseLanding {
    Vec3 position;
    Vec3 normal;  // unit shading normal of the side whose light goes back along the ray
    Rgb albedo;   // that side's (ChooseDiffuseSide: reflection, or transmission through)
    // The bounces' weights and transmittance on the way, times the coat's factor where a coat
    // covers the landing (CoatedRadianceFactor): the landing's outgoing radiance times it is
    // what comes back along the ray.
    Rgb weight;
    uint32_t coat;  // the material whose coat covers the landing, or kNoCoat (hit_point.h)
};

// Follows `ray` through specular and rough bounces (their emission left out: light through
// them is a caustic, which the caller counts apart) to its first diffuse surface, at most
// kMaxGatherDepth surfaces; none where it escapes, is absorbed or goes on too long. Thread-safe.
std::optional<DiffuseLanding> FollowToDiffuse(const Scene& scene, const Tracer& tracer, Ray ray,
                                              Rng& rng);

}  // namespace pf
