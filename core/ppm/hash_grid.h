// A spatial hash grid over hit points for the photon gather: each hit point is stored in every
// cell its search sphere overlaps, so a photon looks in exactly one cell. The cell size is
// twice the largest current radius, so a sphere overlaps at most 2x2x2 cells. (Cells of one
// radius would cut the candidates a photon inspects by about (3/4)^2 on a surface, but store
// each hit point in 27 cells: measured end to end, 2x cells are faster and take a third of
// the memory.) Each entry carries a copy of its hit point's centre, R^2 and packed normal,
// 24 bytes, so a lookup scans contiguous memory with a vectorised test and never follows an
// index into the hit points: faster end to end than 4-byte entries pointing at the hit points
// (2.54 M against 2.45 M photons/s with the normal still read through the index), for about
// 3x the grid's memory.
// Rebuilt once per epoch; read-only, and so thread-safe, while batches run.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "core/job/hit_point.h"
#include "core/math/morton.h"
#include "core/math/octahedral.h"
#include "core/math/vec3.h"
#include "core/shared/surface_edges.h"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace pf {

class HashGrid {
public:
    // radius_sq[i] is hit point i's squared search radius (world units^2); hit points with a
    // zero radius or a black weight are left out, since no photon can change their estimate.
    // edges[i] (gpu::WithinSurfaceEdges), where given, where hit point i's surface ends within
    // its radius; empty: every surface fills its disc.
    // Runs in parallel on the calling TBB arena; the grid, and so the order in which lookups
    // visit hit points (ascending index), does not depend on the thread count.
    void Build(std::span<const HitPoint> hit_points, std::span<const float> radius_sq,
               std::span<const uint64_t> edges = {});

    // Calls visit(index, inner, normal) for every hit point that gathers a photon of `kind`
    // (kDirectPhoton, ...: hit_point.h) at p arriving along `direction` onto a surface of
    // normal `landed` (turned toward the side it arrived from), in a fixed order: it gathers
    // that kind (HitPoint::gathers), p lies within its search sphere, its surface faces the
    // photon (photons from behind are rejected), and, where its surface ends within the
    // sphere, p is on that surface within its reach (gpu::WithinSurfaceEdges). `inner`: p also lies
    // within R / sqrt(2), the disc of half the area (for the estimate of the bias,
    // ProgressiveEstimate::EstimateError); `normal`: the hit point's, as stored (DecodeOctahedral:
    // not normalised).
    template <typename Visit>
    void ForEachGathering(const Vec3& p, const Vec3& direction, const Vec3& landed, uint32_t kind,
                          Visit&& visit) const {
        ScanInside(p, [&](uint32_t e) {
            const Vec3 normal = DecodeOctahedral(entry_normal_[e]);
            if (!Takes(e, normal, p, direction, landed, kind)) return false;
            const float dx = entry_x_[e] - p.x, dy = entry_y_[e] - p.y, dz = entry_z_[e] - p.z;
            visit(entry_index_[e], 2 * (dx * dx + dy * dy + dz * dz) <= entry_radius_sq_[e],
                  normal);
            return false;
        });
    }
    // Whether some hit point would gather that photon (ForEachGathering visits one): stops at
    // the first.
    bool Gathers(const Vec3& p, const Vec3& direction, const Vec3& landed, uint32_t kind) const {
        return ScanInside(p, [&](uint32_t e) {
            return Takes(e, DecodeOctahedral(entry_normal_[e]), p, direction, landed, kind);
        });
    }
    // The bucket a photon at p looks in; photons sorted by it share memory traffic.
    uint32_t BucketOf(const Vec3& p) const {
        return entry_index_.empty() ? 0 : Bucket(CellOf(p.x), CellOf(p.y), CellOf(p.z));
    }
    // Buckets are numbered below 2^BucketBits().
    int BucketBits() const { return std::bit_width(bucket_mask_); }

private:
    // Calls found(entry) for the entries of p's bucket whose sphere holds p, in order, until it
    // returns true; returns whether it did. Two phases: the distance test over the bucket's
    // contiguous coordinates, four entries at a time, gathering a bit mask; then only the few
    // that pass are looked at again.
    template <typename Found>
    bool ScanInside(const Vec3& p, Found&& found) const {
        if (entry_index_.empty()) return false;
        const uint32_t bucket = Bucket(CellOf(p.x), CellOf(p.y), CellOf(p.z));
        constexpr uint32_t kChunk = 64;
        for (uint32_t begin = bucket_begin_[bucket], end = bucket_begin_[bucket + 1]; begin < end;
             begin += kChunk) {
            const uint32_t count = std::min(end - begin, kChunk);
            uint64_t inside = InsideMask(begin, count, p);
            if (count < kChunk) inside &= (uint64_t{1} << count) - 1;
            for (; inside != 0; inside &= inside - 1)
                if (found(begin + static_cast<uint32_t>(std::countr_zero(inside)))) return true;
        }
        return false;
    }
    // Clamped so that radii shrinking toward zero or far-away photons cannot overflow the
    // conversion; clamped cells only merge, which costs candidates, never correctness.
    int64_t CellOf(float coordinate) const {
        constexpr float kLimit = 0x1p50f;
        return static_cast<int64_t>(
            std::floor(std::clamp(coordinate * inverse_cell_size_, -kLimit, kLimit)));
    }
    // Cells are grouped in blocks of 4x4x4: a block's 64 cells take 64 consecutive buckets in
    // Morton order, and blocks are spread over the table by the hash of Teschner et al. 2003
    // ("Optimized Spatial Hashing for Collision Detection"). Neighbouring cells thus share
    // cache lines, which photons sorted by bucket exploit; distinct blocks still scatter.
    uint32_t Bucket(int64_t x, int64_t y, int64_t z) const {
        const uint64_t within = SpreadBits3(uint64_t(x) & 3) | SpreadBits3(uint64_t(y) & 3) << 1 |
                                SpreadBits3(uint64_t(z) & 3) << 2;
        const uint64_t block = static_cast<uint64_t>(x >> 2) * 73856093u ^
                               static_cast<uint64_t>(y >> 2) * 19349663u ^
                               static_cast<uint64_t>(z >> 2) * 83492791u;
        return static_cast<uint32_t>((block << 6 | within) & bucket_mask_);
    }
    // Bit k set where entry begin + k (k < count rounded up to 4) holds p within its radius.
    // (Testing the normals here too, four at a time, is slower: most entries fail the
    // distance test, and decoding their normals costs more than the branch it saves.)
    uint64_t InsideMask(uint32_t begin, uint32_t count, const Vec3& p) const {
        const float* xs = entry_x_.data() + begin;
        const float* ys = entry_y_.data() + begin;
        const float* zs = entry_z_.data() + begin;
        const float* radii_sq = entry_radius_sq_.data() + begin;
        uint64_t inside = 0;
#if defined(__SSE2__)
        const __m128 px = _mm_set1_ps(p.x), py = _mm_set1_ps(p.y), pz = _mm_set1_ps(p.z);
        for (uint32_t k = 0; k < count; k += 4) {
            const __m128 dx = _mm_sub_ps(_mm_loadu_ps(xs + k), px);
            const __m128 dy = _mm_sub_ps(_mm_loadu_ps(ys + k), py);
            const __m128 dz = _mm_sub_ps(_mm_loadu_ps(zs + k), pz);
            const __m128 d2 =
                _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz));
            inside |= uint64_t(_mm_movemask_ps(_mm_cmple_ps(d2, _mm_loadu_ps(radii_sq + k)))) << k;
        }
#else
        for (uint32_t k = 0; k < count; ++k) {
            const float dx = xs[k] - p.x, dy = ys[k] - p.y, dz = zs[k] - p.z;
            inside |= uint64_t{dx * dx + dy * dy + dz * dz <= radii_sq[k]} << k;
        }
#endif
        return inside;
    }
    // Whether entry e, of hit point normal `normal`, whose sphere holds p, takes a photon there
    // (ForEachGathering).
    bool Takes(uint32_t e, const Vec3& normal, const Vec3& p, const Vec3& direction,
               const Vec3& landed, uint32_t kind) const {
        if (Dot(normal, direction) >= 0) return false;
        if (!gathers_.empty() && (gathers_[entry_index_[e]] & kind) == 0) return false;
        const uint64_t edges = edges_.empty() ? gpu::kUnboundedEdges : edges_[entry_index_[e]];
        return gpu::WithinSurfaceEdges(edges, normal, landed,
                                       p - Vec3(entry_x_[e], entry_y_[e], entry_z_[e]),
                                       entry_radius_sq_[e]);
    }
    // The distinct buckets of the cells that the sphere (center, radius) overlaps; returns count.
    int OverlappedBuckets(const Vec3& center, float radius, uint32_t buckets[8]) const;

    float inverse_cell_size_ = 0;
    uint64_t bucket_mask_ = 0;
    std::vector<uint32_t> bucket_begin_;  // CSR offsets into the entry arrays, size buckets + 1
    // Entries grouped by bucket, as structure of arrays: a hit point's centre, R^2 and normal
    // copied into every bucket it is stored in, so a lookup reads contiguous memory only.
    // The coordinates and radii are padded with unused entries, so that the vectorised
    // distance test may read a bucket's last group of four whole.
    static constexpr uint32_t kEntryPadding = 3;
    std::vector<float> entry_x_, entry_y_, entry_z_, entry_radius_sq_;
    std::vector<uint32_t> entry_normal_;  // octahedral, read only for those within their radius
    std::vector<uint32_t> entry_index_;   // the hit point of each entry
    // Per hit point, the photons it gathers (HitPoint::gathers); empty where every one gathers
    // kScatteredPhotons, all a ppm or sppm photon pass deposits.
    std::vector<uint8_t> gathers_;
    // Per hit point, where its surface ends (Build's edges), read only for the photons within
    // its sphere that face it; empty where none was given or every surface fills its disc.
    std::vector<uint64_t> edges_;
};

}  // namespace pf
