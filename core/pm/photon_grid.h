// A uniform grid over photons, hashed (cells are cubes of one size; only cells that hold
// photons take memory), for the k-nearest search by expanding radius: look in the cells
// within r of the point, and if fewer than k photons lie within r, double r, up to the
// search's limit. The first source document compares exactly this against the kd-tree.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/pm/photon_map.h"

namespace pf {

class PhotonGrid final : public PhotonLookup {
public:
    // `cell_size`: world units, > 0; best about the radius that holds k photons.
    PhotonGrid(std::vector<StoredPhoton> photons, float cell_size);
    void Nearest(const Vec3& p, uint32_t k, float max_distance_sq,
                 NearestPhotons& out) const override;
    float CellSize() const { return cell_size_; }
    // Each bucket's first photon in Photons(), and one past the last bucket's last: the
    // buckets are hashed cells (Teschner et al. 2003), bucket_mask + 1 of them, a power of two.
    std::span<const uint32_t> BucketBegin() const { return bucket_begin_; }
    uint64_t BucketMask() const { return bucket_mask_; }
    uint64_t Bytes() const override {
        return photons_.size() * sizeof(StoredPhoton) + bucket_begin_.size() * sizeof(uint32_t);
    }

private:
    struct Cell {
        int64_t x, y, z;
        bool operator==(const Cell&) const = default;
    };
    Cell CellOf(const Vec3& p) const;
    uint64_t Bucket(const Cell& cell) const;
    // Offers every photon of the cells overlapping the sphere (p, radius).
    void Visit(const Vec3& p, float radius, NearestPhotons& out) const;

    float cell_size_ = 1, inverse_cell_size_ = 1;
    uint64_t bucket_mask_ = 0;
    std::vector<uint32_t> bucket_begin_;  // CSR offsets into photons_, sorted by bucket
};

// The cell size for a grid over `photons` stored on `surface_area` (world units^2): the
// radius of a disc that holds k photons on average, but at least max_radius / 8, so an
// expanding search looks in at most 17^3 cells.
float GridCellSize(uint64_t photons, double surface_area, uint32_t k, float max_radius);

}  // namespace pf
