// Direct lighting at a hit point by explicit light sampling with a shadow ray. Taken once per
// hit point per epoch and averaged, so direct light converges like the photons do while the
// photons carry only indirect light.
#pragma once

#include <cstdint>

#include "core/geometry/tracer.h"
#include "core/ppm/hit_point.h"
#include "core/sampling/rng.h"
#include "core/scene/emitters.h"


namespace pf {

// The random stream of hit point `hit_point`'s direct-light sample in `epoch`.
Rng DirectLightRng(uint64_t seed, uint64_t epoch, uint32_t hit_point);

// One sample of the light reflected at the hit point toward the camera path, already
// multiplied by the hit point's weight (throughput x BSDF), in W/(m^2 sr).
Rgb SampleDirectLight(const Emitters& emitters, const Tracer& tracer, const HitPoint& hit_point,
                      Rng rng);

}  // namespace pf
