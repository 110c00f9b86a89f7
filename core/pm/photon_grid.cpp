// Building and searching the hashed uniform photon grid.
#include "core/pm/photon_grid.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace pf {

float GridCellSize(uint64_t photons, double surface_area, uint32_t k, float max_radius) {
    double size = max_radius;
    if (photons > 0 && surface_area > 0)
        size = std::sqrt(double(k) * surface_area / (kPiD * double(photons)));
    return static_cast<float>(std::clamp(size, double(max_radius) / 8, double(max_radius)));
}

PhotonGrid::PhotonGrid(std::vector<StoredPhoton> photons, float cell_size)
    : cell_size_(cell_size), inverse_cell_size_(1.0f / cell_size) {
    const uint64_t buckets = std::bit_ceil(std::max<uint64_t>(2 * photons.size(), 64));
    bucket_mask_ = buckets - 1;
    // A counting sort by bucket, stable, so the order is the map's own within a bucket.
    std::vector<uint32_t> counts(buckets + 1, 0);
    std::vector<uint32_t> bucket_of(photons.size());
    for (size_t i = 0; i < photons.size(); ++i) {
        bucket_of[i] = static_cast<uint32_t>(Bucket(CellOf(photons[i].position)));
        ++counts[bucket_of[i] + 1];
    }
    for (uint64_t b = 0; b < buckets; ++b) counts[b + 1] += counts[b];
    bucket_begin_ = counts;
    photons_.resize(photons.size());
    for (size_t i = 0; i < photons.size(); ++i) photons_[counts[bucket_of[i]]++] = photons[i];
}

PhotonGrid::Cell PhotonGrid::CellOf(const Vec3& p) const {
    // Clamped so far-off points cannot overflow; clamped cells only merge.
    const auto cell = [&](float c) {
        return static_cast<int64_t>(std::floor(std::clamp(c * inverse_cell_size_, -1e15f, 1e15f)));
    };
    return {cell(p.x), cell(p.y), cell(p.z)};
}

uint64_t PhotonGrid::Bucket(const Cell& cell) const {
    // Teschner et al. 2003, "Optimized Spatial Hashing for Collision Detection".
    const uint64_t h = (uint64_t(cell.x) * 73856093u) ^ (uint64_t(cell.y) * 19349663u) ^
                       (uint64_t(cell.z) * 83492791u);
    return h & bucket_mask_;
}

void PhotonGrid::Visit(const Vec3& p, float radius, NearestPhotons& out) const {
    const Cell low = CellOf(p - Vec3(radius)), high = CellOf(p + Vec3(radius));
    for (int64_t x = low.x; x <= high.x; ++x)
        for (int64_t y = low.y; y <= high.y; ++y)
            for (int64_t z = low.z; z <= high.z; ++z) {
                const Cell cell{x, y, z};
                const uint64_t bucket = Bucket(cell);
                for (uint32_t i = bucket_begin_[bucket]; i < bucket_begin_[bucket + 1]; ++i) {
                    const StoredPhoton& photon = photons_[i];
                    const float distance_sq = LengthSquared(photon.position - p);
                    // Other cells may share the bucket: each photon counts in its own cell only.
                    if (distance_sq < out.max_distance_sq && CellOf(photon.position) == cell)
                        out.Offer(distance_sq, i);
                }
            }
}

void PhotonGrid::Nearest(const Vec3& p, uint32_t k, float max_distance_sq,
                         NearestPhotons& out) const {
    for (float radius = cell_size_;; radius *= 2) {
        const float radius_sq = std::min(radius * radius, max_distance_sq);
        out.Reset(k, radius_sq);
        Visit(p, std::sqrt(radius_sq), out);
        // k photons within the radius are the k nearest anywhere; otherwise look wider.
        if (out.entries.size() == k || radius_sq >= max_distance_sq) return;
    }
}

}  // namespace pf
