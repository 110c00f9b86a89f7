// Whether light reaches diffuse surfaces through chains of specular bounces (caustic paths,
// L S+ D in Heckbert's notation): a probe of light paths traced from the emitters, run once per
// job. A scene without specular materials has none and runs no probe.
#pragma once

#include <cstdint>

#include "core/geometry/tracer.h"
#include "core/scene/emitters.h"
#include "core/scene/scene.h"

namespace pf {

struct CausticProbe {
    uint32_t paths = 0;    // light paths traced
    uint32_t caustic = 0;  // of them, reaching a diffuse surface after one or more specular bounces

    double Fraction() const { return paths > 0 ? double(caustic) / paths : 0.0; }
};

// Traces `paths` light paths (seeded by `seed`) until their first diffuse hit. A positive
// answer is certain; a caustic carried by fewer than about 1 path in `paths` can be missed.
CausticProbe ProbeCaustics(const Scene& scene, const Emitters& emitters, const Tracer& tracer,
                           uint64_t seed, uint32_t paths = 1u << 14);

}  // namespace pf
