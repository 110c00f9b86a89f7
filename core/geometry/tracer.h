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

    // Closest hits of up to kPacketSize independent rays at once (faster than one by one where
    // the backend has packet traversal): for each i with active[i], found[i] tells whether
    // rays[i] hit and hits[i] where. Entries not active are left alone.
    static constexpr int kPacketSize = 8;
    virtual void IntersectPacket(const Ray (&rays)[kPacketSize], const bool (&active)[kPacketSize],
                                 RayHit (&hits)[kPacketSize], bool (&found)[kPacketSize]) const = 0;
    // Occluded() for up to kPacketSize rays at once; entries not active are left alone.
    virtual void OccludedPacket(const Ray (&rays)[kPacketSize], const bool (&active)[kPacketSize],
                                bool (&occluded)[kPacketSize]) const = 0;
};

}  // namespace pf
