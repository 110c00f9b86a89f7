// Arrays of fixed-size values kept compactly in a ByteWriter, for checkpoints: the values'
// bytes split into planes (byte 0 of every value, then byte 1, ...) and compressed with zstd,
// as wire/blob_codec.h does for what the farm sends (core may not include wire). The planes
// put the slowly varying sign and exponent bytes of floats and doubles together, apart from
// their noisy low mantissa bytes, which zstd alone would see interleaved with them.
//
// An array is its count, then its chunks of up to kPackedChunkBytes of values, each its
// packed size (8 bytes) and one zstd frame carrying its content size and checksum, so that an
// altered chunk is refused rather than read as other numbers. The frame holds a layout byte,
// then the values: as byte planes (1) or, where that packs smaller, as they are (0). Chunks
// are packed in parallel on the calling TBB arena; the bytes do not depend on the thread
// count. Lossless: unpacked values are bit-identical to those packed. Machine byte order,
// like byte_stream.h.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

#include "core/util/byte_stream.h"

namespace pf {

// The most bytes of values one chunk holds (a value is never split).
inline constexpr size_t kPackedChunkBytes = size_t{1} << 22;

// One array for WritePacked: `count` values of `value_size` bytes at `data`, borrowed.
struct PackedArray {
    template <typename T>
    PackedArray(const std::vector<T>& values)  // NOLINT: implicit, to list arrays in braces
        : data(values.data()), count(values.size()), value_size(sizeof(T)) {
        static_assert(std::is_trivially_copyable_v<T>);
    }
    const void* data;
    uint64_t count;
    size_t value_size;
};

// Appends the arrays in order, each as described above.
void WritePacked(ByteWriter& out, std::span<const PackedArray> arrays);

// Reads one array written so into `values` (count * value_size bytes). False when its count
// is not `count`, or a chunk is truncated, altered or of another size.
bool ReadPacked(ByteReader& in, uint64_t count, size_t value_size, void* values);

template <typename T>
bool ReadPacked(ByteReader& in, uint64_t count, std::vector<T>* values) {
    static_assert(std::is_trivially_copyable_v<T>);
    values->resize(count);
    return ReadPacked(in, count, sizeof(T), values->data());
}

}  // namespace pf
