// The one ray-casting interface the core algorithms use; a backend (Embree on the CPU)
// implements it. Implementations must be safe to call from many threads at once.
#pragma once

#include "core/geometry/ray.h"

namespace pf {

class Tracer {
public:
    virtual ~Tracer() = default;
    // Closest hit along ray in (0, ray.t_max); false if none.
    virtual bool Intersect(const Ray& ray, RayHit* hit) const = 0;
    // True if anything lies along ray in (0, ray.t_max).
    virtual bool Occluded(const Ray& ray) const = 0;
};

}  // namespace pf
