// An epoch's gather regions, one per hit point: what the coordinator sends its workers each
// epoch, and what their photon passes gather within.
#pragma once

#include <cstdint>
#include <vector>

namespace pf {

struct GatherRegions {
    std::vector<float> radius_sq;  // R^2, world units^2; 0 leaves the hit point out
    // Where each hit point's surface ends within R (gpu::WithinSurfaceEdges); empty: every
    // surface fills its disc.
    std::vector<uint64_t> edges;
};

}  // namespace pf
