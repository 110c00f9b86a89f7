// Per-thread scratch that sums a chunk's photon contributions (or a batch's chunk tallies)
// densely, then hands them out as a sparse, sorted Tally. Sums for each hit point are added
// in photon (or chunk) order, so a batch's tally is bit-identical however batches and chunks
// are scheduled. Not thread-safe: one per thread.
// The hot loop adds raw photon flux in float (20 bytes a hit point);
// the hit point's constant BSDF weight is applied once per hit point by the merge. Float is
// ample within one batch: at most 2^26 photons, each sum's relative error below 2^-24 x the
// number of its terms.
#pragma once

#include <cstdint>
#include <vector>

#include "core/job/batch.h"

namespace pf {

class TallyAccumulator {
public:
    void Resize(size_t hit_point_count);
    // `inner`: the photon also lies within R / sqrt(2) (HashGrid::ForEachGathering).
    void Add(uint32_t hit_point, const Rgb& flux, bool inner) {
        Sum& sum = sums_[hit_point];
        if (sum.photons++ == 0) touched_.push_back(hit_point);
        sum.inner_photons += inner;
        sum.flux += flux;
    }
    // `count` photons at once, `flux` their sum (a chain's state held for `count` steps).
    void Add(uint32_t hit_point, const Rgb& flux, bool inner, uint32_t count) {
        Sum& sum = sums_[hit_point];
        if (sum.photons == 0) touched_.push_back(hit_point);
        sum.photons += count;
        sum.inner_photons += inner ? count : 0;
        sum.flux += flux;
    }
    // Adds a chunk's tally entry by entry: chunks added in chunk order give the same sums
    // whoever ran them.
    void Add(const Tally& tally) {
        for (size_t e = 0; e < tally.Size(); ++e) {
            Sum& sum = sums_[tally.hit_point[e]];
            if (sum.photons == 0) touched_.push_back(tally.hit_point[e]);
            sum.photons += tally.photons[e];
            sum.inner_photons += tally.inner_photons[e];
            sum.flux += tally.flux[e];
        }
    }
    // Moves the sums out as a tally and leaves the accumulator empty.
    Tally Extract();

private:
    struct Sum {
        Rgb flux;
        uint32_t photons;
        uint32_t inner_photons;
    };
    std::vector<Sum> sums_;
    std::vector<uint32_t> touched_;
};

}  // namespace pf
