// Dense-to-sparse extraction of a batch tally.
#include "core/ppm/tally_accumulator.h"

#include <algorithm>

#include "core/util/check.h"

namespace pf {

void TallyAccumulator::Resize(size_t hit_point_count) {
    if (sums_.size() == hit_point_count) return;
    sums_.assign(hit_point_count, Sum{Rgb(0.0f), 0, 0});
    touched_.clear();
}

Tally TallyAccumulator::Extract() {
    // Sorting costs O(T log T) for T touched points, a scan of the counts O(H): take the cheaper.
    if (touched_.size() * 16 > sums_.size()) {
        touched_.clear();
        for (uint32_t i = 0; i < sums_.size(); ++i)
            if (sums_[i].photons != 0) touched_.push_back(i);
    } else {
        std::sort(touched_.begin(), touched_.end());
    }
    Tally tally;
    tally.hit_point = touched_;
    tally.photons.reserve(touched_.size());
    tally.inner_photons.reserve(touched_.size());
    tally.flux.reserve(touched_.size());
    for (uint32_t index : touched_) {
        tally.photons.push_back(sums_[index].photons);
        tally.inner_photons.push_back(sums_[index].inner_photons);
        tally.flux.push_back(sums_[index].flux);
        sums_[index] = Sum{Rgb(0.0f), 0, 0};
    }
    touched_.clear();
    return tally;
}

}  // namespace pf
