// Building the hit-point hash grid in two passes (count, then fill) into CSR arrays.
#include "core/ppm/hash_grid.h"

#include <algorithm>
#include <bit>

#include "core/util/check.h"

namespace pf {

int HashGrid::OverlappedBuckets(const Vec3& center, float radius, uint32_t buckets[8]) const {
    // 2 radius <= cell size, so the sphere spans at most 2 cells an axis; the clamp only
    // guards against rounding at cell borders.
    const int64_t x0 = CellOf(center.x - radius), x1 = std::min(CellOf(center.x + radius), x0 + 1);
    const int64_t y0 = CellOf(center.y - radius), y1 = std::min(CellOf(center.y + radius), y0 + 1);
    const int64_t z0 = CellOf(center.z - radius), z1 = std::min(CellOf(center.z + radius), z0 + 1);
    int count = 0;
    for (int64_t x = x0; x <= x1; ++x)
        for (int64_t y = y0; y <= y1; ++y)
            for (int64_t z = z0; z <= z1; ++z) {
                // Different cells can share a bucket: store the hit point there once only.
                const uint32_t bucket = Bucket(x, y, z);
                if (std::find(buckets, buckets + count, bucket) == buckets + count)
                    buckets[count++] = bucket;
            }
    return count;
}

void HashGrid::Build(std::span<const HitPoint> hit_points, std::span<const float> radius_sq) {
    PF_CHECK(hit_points.size() == radius_sq.size());
    auto usable = [&](size_t i) { return radius_sq[i] > 0 && !IsBlack(hit_points[i].weight); };
    std::vector<float> radius(hit_points.size());
    float max_radius = 0;
    for (size_t i = 0; i < hit_points.size(); ++i) {
        radius[i] = std::sqrt(radius_sq[i]);
        if (usable(i)) max_radius = std::max(max_radius, radius[i]);
    }
    for (auto* entries : {&entry_x_, &entry_y_, &entry_z_, &entry_radius_sq_}) entries->clear();
    entry_normal_.clear();
    entry_index_.clear();
    bucket_begin_.clear();
    if (!(max_radius > 0)) return;
    inverse_cell_size_ = 1.0f / (2.0f * max_radius);  // cells twice the largest radius wide
    const uint64_t bucket_count = std::bit_ceil(std::max<uint64_t>(2 * hit_points.size(), 64));
    bucket_mask_ = bucket_count - 1;

    std::vector<uint32_t> counts(bucket_count + 1, 0);
    uint32_t buckets[8];
    for (size_t i = 0; i < hit_points.size(); ++i) {
        if (!usable(i)) continue;
        const int n = OverlappedBuckets(hit_points[i].position, radius[i], buckets);
        for (int k = 0; k < n; ++k) ++counts[buckets[k] + 1];
    }
    for (uint64_t b = 0; b < bucket_count; ++b) counts[b + 1] += counts[b];
    bucket_begin_ = counts;
    const size_t entry_count = counts[bucket_count];
    for (auto* entries : {&entry_x_, &entry_y_, &entry_z_, &entry_radius_sq_})
        entries->resize(entry_count + kEntryPadding);
    entry_normal_.resize(entry_count);
    entry_index_.resize(entry_count);
    // Second pass: the buckets are computed again rather than kept from the first, which
    // would take 33 bytes a hit point of scratch for a few float operations saved.
    for (size_t i = 0; i < hit_points.size(); ++i) {
        if (!usable(i)) continue;
        const int n = OverlappedBuckets(hit_points[i].position, radius[i], buckets);
        const Vec3& p = hit_points[i].position;
        const uint32_t normal = EncodeOctahedral(hit_points[i].normal);
        for (int k = 0; k < n; ++k) {
            const uint32_t e = counts[buckets[k]]++;
            entry_x_[e] = p.x, entry_y_[e] = p.y, entry_z_[e] = p.z;
            entry_radius_sq_[e] = radius_sq[i];
            entry_normal_[e] = normal;
            entry_index_[e] = static_cast<uint32_t>(i);
        }
    }
}

}  // namespace pf
