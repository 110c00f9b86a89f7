// Byte planes and zstd frames for the arrays of checkpoints.
#include "core/util/packed_arrays.h"

#include <tbb/parallel_for.h>
#include <zstd.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <utility>

#include "core/util/check.h"

namespace pf {
namespace {

// zstd level 1: a checkpoint is packed under the job's estimate lock. Level 3 packs a ppm
// state 6% smaller between folds (1% at an epoch's end) but takes a third longer
// (bench/checkpoint_bench, cornell-box at 512x512x4).
constexpr int kZstdLevel = 1;

uint64_t ChunkValues(size_t value_size) {
    return std::max<uint64_t>(1, kPackedChunkBytes / value_size);
}

// Byte p of value i goes to planes[p * count + i].
void SplitPlanes(const uint8_t* values, uint64_t count, size_t value_size, uint8_t* planes) {
    for (size_t p = 0; p < value_size; ++p, planes += count)
        for (uint64_t i = 0; i < count; ++i) planes[i] = values[i * value_size + p];
}

void JoinPlanes(const uint8_t* planes, uint64_t count, size_t value_size, uint8_t* values) {
    for (size_t p = 0; p < value_size; ++p, planes += count)
        for (uint64_t i = 0; i < count; ++i) values[i * value_size + p] = planes[i];
}

// How a chunk's values were laid out before zstd: the first byte of what the frame holds, so
// that its checksum covers it.
enum Layout : uint8_t { kAsIs = 0, kPlanes = 1 };

// One zstd frame of `content`, with its size and checksum.
std::string Compress(std::string_view content) {
    const std::unique_ptr<ZSTD_CCtx, size_t (*)(ZSTD_CCtx*)> context(ZSTD_createCCtx(),
                                                                     ZSTD_freeCCtx);
    PF_CHECK(context != nullptr);
    ZSTD_CCtx_setParameter(context.get(), ZSTD_c_compressionLevel, kZstdLevel);
    ZSTD_CCtx_setParameter(context.get(), ZSTD_c_checksumFlag, 1);
    std::string frame(ZSTD_compressBound(content.size()), '\0');
    const size_t written =
        ZSTD_compress2(context.get(), frame.data(), frame.size(), content.data(), content.size());
    PF_CHECK(!ZSTD_isError(written));  // into a buffer of the bound's size it cannot fail
    frame.resize(written);
    return frame;
}

// Byte planes pack most arrays smaller, but not all: where many values repeat whole (a hit
// point's photon sums within an epoch, built from a few distinct flux values), zstd finds the
// repeats only in the values as they are. So both are packed and the smaller kept.
std::string PackChunk(const uint8_t* values, uint64_t count, size_t value_size) {
    const size_t size = count * value_size;
    std::string content(1 + size, static_cast<char>(kPlanes));
    SplitPlanes(values, count, value_size, reinterpret_cast<uint8_t*>(content.data()) + 1);
    std::string planes = Compress(content);
    content[0] = static_cast<char>(kAsIs);
    std::memcpy(content.data() + 1, values, size);
    std::string as_is = Compress(content);
    std::string& smaller = as_is.size() < planes.size() ? as_is : planes;
    smaller.shrink_to_fit();  // from the bound's size
    return std::move(smaller);
}

// False unless `frame` is exactly one whole zstd frame, its checksum holding, of a layout
// byte and count * value_size bytes of values.
bool UnpackChunk(std::string_view frame, uint64_t count, size_t value_size, uint8_t* values) {
    const size_t size = count * value_size;
    if (ZSTD_findFrameCompressedSize(frame.data(), frame.size()) != frame.size() ||
        ZSTD_getFrameContentSize(frame.data(), frame.size()) != 1 + size)
        return false;
    std::string content(1 + size, '\0');
    const size_t got = ZSTD_decompress(content.data(), content.size(), frame.data(), frame.size());
    if (ZSTD_isError(got) || got != content.size()) return false;
    const auto* bytes = reinterpret_cast<const uint8_t*>(content.data()) + 1;
    if (content[0] == kAsIs)
        std::memcpy(values, bytes, size);
    else if (content[0] == kPlanes)
        JoinPlanes(bytes, count, value_size, values);
    else
        return false;
    return true;
}

}  // namespace

void WritePacked(ByteWriter& out, std::span<const PackedArray> arrays) {
    struct Chunk {
        const uint8_t* values;
        uint64_t count;
        size_t value_size;
        std::string frame;
    };
    std::vector<Chunk> chunks;
    for (const PackedArray& array : arrays) {
        const uint64_t per_chunk = ChunkValues(array.value_size);
        for (uint64_t begin = 0; begin < array.count; begin += per_chunk)
            chunks.push_back({static_cast<const uint8_t*>(array.data) + begin * array.value_size,
                              std::min(per_chunk, array.count - begin),
                              array.value_size,
                              {}});
    }
    tbb::parallel_for(size_t{0}, chunks.size(), [&](size_t c) {
        chunks[c].frame = PackChunk(chunks[c].values, chunks[c].count, chunks[c].value_size);
    });
    size_t total = out.Bytes().size() + sizeof(uint64_t) * (arrays.size() + chunks.size());
    for (const Chunk& chunk : chunks) total += chunk.frame.size();
    out.Bytes().reserve(total);
    auto chunk = chunks.begin();
    for (const PackedArray& array : arrays) {
        out.Value<uint64_t>(array.count);
        for (uint64_t packed = 0; packed < array.count; packed += chunk->count, ++chunk) {
            out.Value<uint64_t>(chunk->frame.size());
            out.Bytes().append(chunk->frame);
        }
    }
}

bool ReadPacked(ByteReader& in, uint64_t count, size_t value_size, void* values) {
    uint64_t stored = 0;
    if (!in.Value(&stored) || stored != count) return false;
    const uint64_t per_chunk = ChunkValues(value_size);
    std::vector<std::string_view> frames;
    for (uint64_t begin = 0; begin < count; begin += per_chunk) {
        uint64_t size = 0;
        std::string_view frame;
        if (!in.Value(&size) || !in.Bytes(size, &frame)) return false;
        frames.push_back(frame);
    }
    std::atomic<bool> whole = true;
    tbb::parallel_for(size_t{0}, frames.size(), [&](size_t c) {
        const uint64_t begin = c * per_chunk;
        if (!UnpackChunk(frames[c], std::min(per_chunk, count - begin), value_size,
                         static_cast<uint8_t*>(values) + begin * value_size))
            whole = false;
    });
    return whole;
}

}  // namespace pf
