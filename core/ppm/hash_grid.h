// A spatial hash grid over hit points for the photon gather: each hit point is stored in every
// cell its search sphere overlaps, so a photon looks in exactly one cell. The cell size is
// twice the largest current radius, so a sphere overlaps at most 2x2x2 cells. (Cells of one
// radius would cut the candidates a photon inspects by about (3/4)^2 on a surface, but store
// each hit point in 27 cells: measured end to end, 2x cells are faster and take a third of
// the memory.) Rebuilt once per epoch; read-only, and so thread-safe, while batches run.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "core/math/morton.h"
#include "core/math/vec3.h"
#include "core/ppm/hit_point.h"

namespace pf {

class HashGrid {
public:
    // radius_sq[i] is hit point i's squared search radius (world units^2); hit points with a
    // zero radius or a black weight are left out, since no photon can change their estimate.
    void Build(std::span<const HitPoint> hit_points, std::span<const float> radius_sq);

    // Calls visit(index) for every hit point whose search sphere contains p and whose surface
    // faces a photon arriving along `direction` (photons from behind are rejected), in a
    // fixed order.
    template <typename Visit>
    void ForEachGathering(const Vec3& p, const Vec3& direction, Visit&& visit) const {
        if (entries_.empty()) return;
        const uint32_t bucket = Bucket(CellOf(p.x), CellOf(p.y), CellOf(p.z));
        for (uint32_t e = bucket_begin_[bucket]; e < bucket_begin_[bucket + 1]; ++e) {
            const Sphere& sphere = spheres_[entries_[e]];
            if (LengthSquared(sphere.center - p) <= sphere.radius_sq && Dot(sphere.normal, direction) < 0)
                visit(entries_[e]);
        }
    }
    // The bucket a photon at p looks in; photons sorted by it share memory traffic.
    uint32_t BucketOf(const Vec3& p) const {
        return entries_.empty() ? 0 : Bucket(CellOf(p.x), CellOf(p.y), CellOf(p.z));
    }
    // The number of hit points inspected for a photon at p (for tests and statistics).
    size_t CandidateCount(const Vec3& p) const {
        if (entries_.empty()) return 0;
        const uint32_t bucket = BucketOf(p);
        return bucket_begin_[bucket + 1] - bucket_begin_[bucket];
    }

    // Buckets are numbered below 2^BucketBits().
    int BucketBits() const { return std::bit_width(bucket_mask_); }
    float CellSize() const { return cell_size_; }
    size_t EntryCount() const { return entries_.size(); }

private:
    int64_t CellOf(float coordinate) const {
        return static_cast<int64_t>(std::floor(coordinate * inverse_cell_size_));
    }
    // Cells are grouped in blocks of 4x4x4: a block's 64 cells take 64 consecutive buckets in
    // Morton order, and blocks are spread over the table by the hash of Teschner et al. 2003
    // ("Optimized Spatial Hashing for Collision Detection"). Neighbouring cells thus share
    // cache lines, which photons sorted by bucket exploit; distinct blocks still scatter.
    uint32_t Bucket(int64_t x, int64_t y, int64_t z) const {
        const uint64_t within = SpreadBits3(uint64_t(x) & 3) | SpreadBits3(uint64_t(y) & 3) << 1 |
                                SpreadBits3(uint64_t(z) & 3) << 2;
        const auto block = static_cast<uint64_t>((x >> 2) * 73856093) ^ static_cast<uint64_t>((y >> 2) * 19349663) ^
                           static_cast<uint64_t>((z >> 2) * 83492791);
        return static_cast<uint32_t>((block << 6 | within) & bucket_mask_);
    }
    // The distinct buckets of the cells that the sphere (center, radius) overlaps; returns count.
    int OverlappedBuckets(const Vec3& center, float radius, uint32_t buckets[8]) const;

    // All a lookup reads of a hit point, packed in 32 bytes so candidates (adjacent in memory
    // thanks to the camera pass's Morton order) share cache lines.
    struct alignas(32) Sphere {
        Vec3 center;
        float radius_sq;
        Vec3 normal;
    };

    std::vector<Sphere> spheres_;         // per hit point
    float cell_size_ = 0, inverse_cell_size_ = 0;
    uint64_t bucket_mask_ = 0;
    std::vector<uint32_t> bucket_begin_;  // CSR offsets, size buckets + 1
    std::vector<uint32_t> entries_;       // hit point indices, grouped by bucket
};

}  // namespace pf
