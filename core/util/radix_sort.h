// Stable least-significant-digit radix sort of 64-bit keys by a bit range, for sorting many
// small keys in linear time (std::sort's n log n comparisons showed up at ~8% of a render).
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace pf {

// Sorts `keys` stably by bits [first_bit, first_bit + bit_count) of each key; `scratch` is
// working memory (resized as needed). Keys equal in those bits keep their relative order.
inline void RadixSortBits(std::vector<uint64_t>& keys, std::vector<uint64_t>& scratch,
                          int first_bit, int bit_count) {
    constexpr int kDigitBits = 11;
    constexpr size_t kRadix = size_t{1} << kDigitBits;
    scratch.resize(keys.size());
    for (int shift = first_bit; shift < first_bit + bit_count; shift += kDigitBits) {
        std::array<size_t, kRadix> offsets{};
        for (uint64_t key : keys) ++offsets[(key >> shift) & (kRadix - 1)];
        size_t running = 0;
        for (size_t& offset : offsets) running += std::exchange(offset, running);
        for (uint64_t key : keys) scratch[offsets[(key >> shift) & (kRadix - 1)]++] = key;
        keys.swap(scratch);
    }
}

}  // namespace pf
