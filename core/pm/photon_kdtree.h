// A balanced kd-tree over photons (Jensen 2001, section 6.3): the photons stored in the order
// of a median-split recursion, so node [lo, hi) has its split photon at (lo + hi) / 2 and its
// children are the two halves; one byte per photon names the split axis. No pointers, and a
// k-nearest search visits O(log n + k) nodes.
#pragma once

#include <cstdint>
#include <vector>

#include "core/pm/photon_map.h"

namespace pf {

class PhotonKdTree final : public PhotonLookup {
public:
    // Builds in parallel on the calling TBB arena; the order does not depend on the thread count.
    explicit PhotonKdTree(std::vector<StoredPhoton> photons);
    void Nearest(const Vec3& p, uint32_t k, float max_distance_sq,
                 NearestPhotons& out) const override;
    uint64_t Bytes() const override {
        return photons_.size() * (sizeof(StoredPhoton) + sizeof(uint8_t));
    }

private:
    void Build(uint32_t lo, uint32_t hi);
    void Search(const Vec3& p, uint32_t lo, uint32_t hi, NearestPhotons& out) const;

    std::vector<uint8_t> axis_;  // per node: the split axis
};

}  // namespace pf
