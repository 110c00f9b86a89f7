// Building and searching the balanced kd-tree.
#include "core/pm/photon_kdtree.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>

namespace pf {
namespace {

// Ranges smaller than this are built on one thread.
constexpr uint32_t kSerialBuild = 1 << 14;

float Coordinate(const Vec3& p, int axis) { return axis == 0 ? p.x : axis == 1 ? p.y : p.z; }

}  // namespace

PhotonKdTree::PhotonKdTree(std::vector<StoredPhoton> photons) {
    photons_ = std::move(photons);
    axis_.assign(photons_.size(), 0);
    Build(0, static_cast<uint32_t>(photons_.size()));
}

void PhotonKdTree::Build(uint32_t lo, uint32_t hi) {
    if (hi - lo <= 1) return;
    // Split across the widest extent of the range's photons, at the median.
    Vec3 lower(std::numeric_limits<float>::max()), upper(-std::numeric_limits<float>::max());
    for (uint32_t i = lo; i < hi; ++i)
        lower = Min(lower, photons_[i].position), upper = Max(upper, photons_[i].position);
    const Vec3 extent = upper - lower;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                     : extent.y >= extent.z                       ? 1
                                                                  : 2;
    const uint32_t middle = lo + (hi - lo) / 2;
    std::nth_element(photons_.begin() + lo, photons_.begin() + middle, photons_.begin() + hi,
                     [axis](const StoredPhoton& a, const StoredPhoton& b) {
                         return Coordinate(a.position, axis) < Coordinate(b.position, axis);
                     });
    axis_[middle] = static_cast<uint8_t>(axis);
    if (hi - lo < kSerialBuild) {
        Build(lo, middle);
        Build(middle + 1, hi);
    } else {
        tbb::parallel_invoke([&] { Build(lo, middle); }, [&] { Build(middle + 1, hi); });
    }
}

void PhotonKdTree::Search(const Vec3& p, uint32_t lo, uint32_t hi, NearestPhotons& out) const {
    while (hi > lo) {
        const uint32_t middle = lo + (hi - lo) / 2;
        const StoredPhoton& photon = photons_[middle];
        const int axis = axis_[middle];
        const float delta = Coordinate(p, axis) - Coordinate(photon.position, axis);
        // The near side first; the far side only if the split plane is within reach, after.
        const bool left_first = delta < 0;
        if (left_first)
            Search(p, lo, middle, out);
        else
            Search(p, middle + 1, hi, out);
        const float distance_sq = LengthSquared(photon.position - p);
        if (distance_sq < out.max_distance_sq) out.Offer(distance_sq, middle);
        if (!(delta * delta < out.max_distance_sq)) return;
        if (left_first)
            lo = middle + 1;
        else
            hi = middle;
    }
}

void PhotonKdTree::Nearest(const Vec3& p, uint32_t k, float max_distance_sq,
                           NearestPhotons& out) const {
    out.Reset(k, max_distance_sq);
    Search(p, 0, static_cast<uint32_t>(photons_.size()), out);
}

}  // namespace pf
