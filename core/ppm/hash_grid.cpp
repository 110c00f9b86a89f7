// Building the hit-point hash grid into CSR arrays: a parallel counting sort by bucket.
#include "core/ppm/hash_grid.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <memory>
#include <numeric>

#include "core/util/check.h"

namespace pf {
namespace {

// Hit points (or buckets) a task.
constexpr size_t kGrain = 4096;

}  // namespace

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

void HashGrid::Build(std::span<const HitPoint> hit_points, std::span<const float> radius_sq,
                     std::span<const uint64_t> edges) {
    PF_CHECK(hit_points.size() == radius_sq.size());
    PF_CHECK(edges.empty() || edges.size() == hit_points.size());
    // Kept only where some surface ends within its radius.
    edges_.clear();
    if (std::any_of(edges.begin(), edges.end(),
                    [](uint64_t e) { return e != gpu::kUnboundedEdges; }))
        edges_.assign(edges.begin(), edges.end());
    // Kept only where some hit point gathers other photons than ppm's.
    gathers_.clear();
    if (std::any_of(hit_points.begin(), hit_points.end(),
                    [](const HitPoint& h) { return h.gathers != kScatteredPhotons; })) {
        gathers_.resize(hit_points.size());
        for (size_t i = 0; i < hit_points.size(); ++i)
            gathers_[i] = static_cast<uint8_t>(hit_points[i].gathers);
    }
    const size_t n = hit_points.size();
    // Search radii, 0 for the hit points left out (no radius, or a black weight).
    std::vector<float> radius(n);
    const float max_radius = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, n, kGrain), 0.0f,
        [&](const tbb::blocked_range<size_t>& r, float largest) {
            for (size_t i = r.begin(); i < r.end(); ++i) {
                const bool usable = radius_sq[i] > 0 && !IsBlack(hit_points[i].weight);
                radius[i] = usable ? std::sqrt(radius_sq[i]) : 0.0f;
                largest = std::max(largest, radius[i]);
            }
            return largest;
        },
        [](float a, float b) { return std::max(a, b); });
    for (auto* entries : {&entry_x_, &entry_y_, &entry_z_, &entry_radius_sq_}) entries->clear();
    entry_normal_.clear();
    entry_index_.clear();
    bucket_begin_.clear();
    if (!(max_radius > 0)) return;
    inverse_cell_size_ = 1.0f / (2.0f * max_radius);  // cells twice the largest radius wide
    const uint64_t bucket_count = std::bit_ceil(std::max<uint64_t>(2 * n, 64));
    bucket_mask_ = bucket_count - 1;

    // A counting sort by bucket, in parallel: the hit points of each bucket are counted, then
    // placed in any order, then each bucket's are sorted by index, so the layout (a bucket's
    // entries in hit-point order, which fixes the gather's order of sums) does not depend on
    // the threads. Each block of kGrain hit points keeps its hit points' buckets, packed, for
    // the second pass (about 13 bytes a hit point, where computing them again cost the build a
    // third more time), and what a hit point's entries copy is packed into one record, which
    // the last pass reads in bucket order.
    struct Entry {
        float x, y, z, radius_sq;
        uint32_t normal;
    };
    const auto entry = std::make_unique_for_overwrite<Entry[]>(n);
    std::vector<uint8_t> overlapped_count(n, 0);
    std::vector<std::vector<uint32_t>> overlapped((n + kGrain - 1) / kGrain);
    std::vector<uint32_t> cursor(bucket_count + 1, 0);
    tbb::parallel_for(size_t{0}, overlapped.size(), [&](size_t block) {
        std::vector<uint32_t>& kept = overlapped[block];
        for (size_t i = block * kGrain; i < std::min(n, (block + 1) * kGrain); ++i) {
            if (radius[i] == 0) continue;
            uint32_t buckets[8];
            const int count = OverlappedBuckets(hit_points[i].position, radius[i], buckets);
            overlapped_count[i] = static_cast<uint8_t>(count);
            kept.insert(kept.end(), buckets, buckets + count);
            const Vec3& p = hit_points[i].position;
            entry[i] = {p.x, p.y, p.z, radius_sq[i], EncodeOctahedral(hit_points[i].normal)};
            for (int k = 0; k < count; ++k)
                std::atomic_ref(cursor[buckets[k] + 1]).fetch_add(1, std::memory_order_relaxed);
        }
    });
    std::inclusive_scan(cursor.begin(), cursor.end(), cursor.begin());
    bucket_begin_ = cursor;
    const size_t entry_count = cursor[bucket_count];
    entry_index_.resize(entry_count);
    tbb::parallel_for(size_t{0}, overlapped.size(), [&](size_t block) {
        const uint32_t* buckets = overlapped[block].data();
        for (size_t i = block * kGrain; i < std::min(n, (block + 1) * kGrain); ++i)
            for (int k = 0; k < overlapped_count[i]; ++k) {
                const uint32_t e =
                    std::atomic_ref(cursor[*buckets++]).fetch_add(1, std::memory_order_relaxed);
                entry_index_[e] = static_cast<uint32_t>(i);
            }
        std::vector<uint32_t>().swap(overlapped[block]);
    });
    for (auto* entries : {&entry_x_, &entry_y_, &entry_z_, &entry_radius_sq_})
        entries->resize(entry_count + kEntryPadding);
    entry_normal_.resize(entry_count);
    tbb::parallel_for(tbb::blocked_range<uint64_t>(0, bucket_count, kGrain),
                      [&](const tbb::blocked_range<uint64_t>& r) {
                          for (uint64_t b = r.begin(); b < r.end(); ++b) {
                              const auto begin = entry_index_.begin() + bucket_begin_[b];
                              const auto end = entry_index_.begin() + bucket_begin_[b + 1];
                              std::sort(begin, end);
                              for (uint32_t e = bucket_begin_[b]; e < bucket_begin_[b + 1]; ++e) {
                                  const Entry& copied = entry[entry_index_[e]];
                                  entry_x_[e] = copied.x, entry_y_[e] = copied.y;
                                  entry_z_[e] = copied.z;
                                  entry_radius_sq_[e] = copied.radius_sq;
                                  entry_normal_[e] = copied.normal;
                              }
                          }
                      });
}

}  // namespace pf
