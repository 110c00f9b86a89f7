// Direct lighting at hit points by explicit light sampling with shadow rays. Taken once per
// hit point per epoch and averaged, so direct light converges like the photons do while the
// photons carry only indirect light.
#pragma once

#include <cstdint>
#include <span>

#include "core/geometry/tracer.h"
#include "core/ppm/hit_point.h"
#include "core/sampling/rng.h"
#include "core/scene/emitters.h"

namespace pf {

// One sample each of the light reflected at hit_points[first + i] toward its camera path,
// already multiplied by the hit point's weight (throughput x BSDF), in W/(m^2 sr), into
// out[i]. Hit point h's sample in `epoch` draws from a stream seeded by (seed, epoch, h)
// alone. Shadow rays are cast in packets. A sample that comes out NaN or Inf is set to 0;
// returns how many were.
// The streams of epoch `epoch`'s direct-light samples: hit point h draws from
// Rng(DirectLightSeeds(seed, epoch).Seed(h)), on every backend.
SeedFamily DirectLightSeeds(uint64_t seed, uint64_t epoch);

uint64_t SampleDirectLight(const Emitters& emitters, const Tracer& tracer, std::span<const HitPoint> hit_points,
                       uint32_t first, uint64_t seed, uint64_t epoch, std::span<Rgb> out);

}  // namespace pf
