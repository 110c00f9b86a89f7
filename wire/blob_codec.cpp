// Byte-plane shuffling and zstd framing for the farm's bulk data.
#include "wire/blob_codec.h"

#include <zstd.h>

#include <bit>
#include <cstddef>
#include <cstring>
#include <iterator>

#include "absl/strings/str_cat.h"
#include "core/scene/prepared_scene.h"
#include "core/util/check.h"
#include "core/util/sha256.h"

namespace pf {
namespace {

static_assert(std::endian::native == std::endian::little, "the wire format is little-endian");

// zstd level 1: radii are encoded once per epoch on the merge's critical path, where level 1
// compresses within a few percent of level 3 at twice the speed.
constexpr int kZstdLevel = 1;

// Frame: the decompressed size as 8 bytes, then one zstd frame of `planes` byte planes.
std::string Compress(const std::vector<uint8_t>& raw) {
    std::string out(8 + ZSTD_compressBound(raw.size()), '\0');
    const uint64_t size = raw.size();
    std::memcpy(out.data(), &size, 8);
    const size_t written =
        ZSTD_compress(out.data() + 8, out.size() - 8, raw.data(), raw.size(), kZstdLevel);
    out.resize(8 + written);  // compression into a bound-sized buffer cannot fail
    return out;
}

absl::StatusOr<std::vector<uint8_t>> Decompress(std::string_view bytes, uint64_t expected_size,
                                                const char* what) {
    uint64_t size = 0;
    if (bytes.size() < 8) return absl::InvalidArgumentError(absl::StrCat(what, ": truncated blob"));
    std::memcpy(&size, bytes.data(), 8);
    if (size != expected_size)
        return absl::InvalidArgumentError(
            absl::StrCat(what, ": blob holds ", size, " bytes, expected ", expected_size));
    std::vector<uint8_t> raw(size);
    const size_t got = ZSTD_decompress(raw.data(), raw.size(), bytes.data() + 8, bytes.size() - 8);
    if (ZSTD_isError(got) || got != size)
        return absl::InvalidArgumentError(absl::StrCat(
            what, ": corrupt blob (", ZSTD_isError(got) ? ZSTD_getErrorName(got) : "short", ")"));
    return raw;
}

// A scene is encoded once per job, off the merge's path: a higher level pays for itself in
// the bytes every worker fetches.
constexpr int kSceneZstdLevel = 6;

// Appends `count` 4-byte words as four byte planes.
void AppendPlanes(const void* words, size_t count, std::vector<uint8_t>* out) {
    const uint8_t* bytes = static_cast<const uint8_t*>(words);
    const size_t base = out->size();
    out->resize(base + 4 * count);
    uint8_t* dst = out->data() + base;
    for (size_t i = 0; i < count; ++i)
        for (int b = 0; b < 4; ++b) dst[b * count + i] = bytes[4 * i + b];
}

void ReadPlanes(const uint8_t* planes, size_t count, void* words) {
    uint8_t* bytes = static_cast<uint8_t*>(words);
    for (size_t i = 0; i < count; ++i)
        for (int b = 0; b < 4; ++b) bytes[4 * i + b] = planes[b * count + i];
}

// Gathers one 4-byte field of every element of `items` (stride bytes apart) as planes.
template <typename T>
void AppendField(std::span<const T> items, size_t offset, std::vector<uint8_t>* out) {
    std::vector<uint32_t> words(items.size());
    for (size_t i = 0; i < items.size(); ++i)
        std::memcpy(&words[i], reinterpret_cast<const uint8_t*>(&items[i]) + offset, 4);
    AppendPlanes(words.data(), words.size(), out);
}

template <typename T>
void ReadField(const uint8_t* planes, size_t offset, std::span<T> items) {
    std::vector<uint32_t> words(items.size());
    ReadPlanes(planes, items.size(), words.data());
    for (size_t i = 0; i < items.size(); ++i)
        std::memcpy(reinterpret_cast<uint8_t*>(&items[i]) + offset, &words[i], 4);
}

// The HitPoint words a worker reads, by their offset in wire order: position, normal, weight,
// the pixel (a batch credits its pixels' hit points with their share of the epoch's emission
// pass, TraceBatchEmission) and the coat. Not what the hit point gathers: the hit points sent
// are ppm's, which gather kScatteredPhotons, the default (sppm's and rpm's workers trace their
// own).
constexpr size_t kHitPointWordOffsets[] = {0, 4, 8, 12, 16, 20, 24, 28, 32, 36, 40};
constexpr size_t kHitPointWords = std::size(kHitPointWordOffsets);
static_assert(sizeof(HitPoint) == 48 && offsetof(HitPoint, pixel) == 36 &&
                  offsetof(HitPoint, coat) == 40 && offsetof(HitPoint, gathers) == 44,
              "HitPoint is nine 4-byte words of geometry and weight, the pixel, the coat, then "
              "what it gathers");

}  // namespace

Blob Blob::Of(std::string bytes) {
    std::string digest = Sha256Hex(bytes);
    return {std::move(digest), std::move(bytes)};
}

std::string EncodeFloats(std::span<const float> values) {
    std::vector<uint8_t> raw;
    AppendPlanes(values.data(), values.size(), &raw);
    return Compress(raw);
}

absl::StatusOr<std::vector<float>> DecodeFloats(std::string_view bytes, uint64_t expected_count) {
    absl::StatusOr<std::vector<uint8_t>> raw = Decompress(bytes, 4 * expected_count, "floats");
    if (!raw.ok()) return raw.status();
    std::vector<float> values(expected_count);
    ReadPlanes(raw->data(), values.size(), values.data());
    return values;
}

std::string EncodeGatherRegions(const GatherRegions& regions) {
    PF_CHECK(regions.edges.empty() || regions.edges.size() == regions.radius_sq.size());
    std::vector<uint8_t> raw;
    AppendPlanes(regions.radius_sq.data(), regions.radius_sq.size(), &raw);
    if (!regions.edges.empty()) {
        const std::span<const uint64_t> edges(regions.edges);
        AppendField(edges, 0, &raw);
        AppendField(edges, 4, &raw);
    }
    return Compress(raw);
}

absl::StatusOr<GatherRegions> DecodeGatherRegions(std::string_view bytes, uint64_t expected_count) {
    // The frame's size tells whether edges follow the radii.
    uint64_t size = 0;
    if (bytes.size() >= 8) std::memcpy(&size, bytes.data(), 8);
    const bool edges = size == 12 * expected_count && expected_count > 0;
    absl::StatusOr<std::vector<uint8_t>> raw =
        Decompress(bytes, (edges ? 12 : 4) * expected_count, "gather regions");
    if (!raw.ok()) return raw.status();
    GatherRegions regions;
    regions.radius_sq.resize(expected_count);
    ReadPlanes(raw->data(), expected_count, regions.radius_sq.data());
    if (edges) {
        regions.edges.resize(expected_count);
        const std::span<uint64_t> out(regions.edges);
        ReadField(raw->data() + 4 * expected_count, 0, out);
        ReadField(raw->data() + 8 * expected_count, 4, out);
    }
    return regions;
}

std::string EncodeHitPoints(std::span<const HitPoint> hit_points) {
    std::vector<uint8_t> raw;
    raw.reserve(4 * kHitPointWords * hit_points.size());
    for (const size_t offset : kHitPointWordOffsets) AppendField(hit_points, offset, &raw);
    return Compress(raw);
}

absl::StatusOr<std::vector<HitPoint>> DecodeHitPoints(std::string_view bytes,
                                                      uint64_t expected_count) {
    absl::StatusOr<std::vector<uint8_t>> raw =
        Decompress(bytes, 4 * kHitPointWords * expected_count, "hit points");
    if (!raw.ok()) return raw.status();
    std::vector<HitPoint> hit_points(expected_count);
    for (size_t word = 0; word < kHitPointWords; ++word)
        ReadField(raw->data() + 4 * word * expected_count, kHitPointWordOffsets[word],
                  std::span<HitPoint>(hit_points));
    return hit_points;
}

std::string EncodeImagePixels(const Image& image) {
    return EncodeFloats(std::span<const float>(&image.pixels.data()->x, 3 * image.pixels.size()));
}

absl::StatusOr<Image> DecodeImagePixels(std::string_view bytes, int width, int height) {
    if (width < 0 || height < 0 || uint64_t(width) * uint64_t(height) > kMaxImagePixels)
        return absl::InvalidArgumentError(absl::StrCat("image: bad size ", width, "x", height));
    absl::StatusOr<std::vector<float>> values = DecodeFloats(bytes, 3ull * width * height);
    if (!values.ok()) return values.status();
    Image image(width, height);
    std::memcpy(static_cast<void*>(image.pixels.data()), values->data(),
                values->size() * sizeof(float));
    return image;
}

std::string EncodeSceneBlob(const Scene& scene) {
    const std::string raw = EncodePreparedScene(scene);
    std::string out(8 + ZSTD_compressBound(raw.size()), '\0');
    const uint64_t size = raw.size();
    std::memcpy(out.data(), &size, 8);
    const size_t written =
        ZSTD_compress(out.data() + 8, out.size() - 8, raw.data(), raw.size(), kSceneZstdLevel);
    out.resize(8 + written);
    return out;
}

absl::StatusOr<Scene> DecodeSceneBlob(std::string_view bytes, bool texture_filter) {
    uint64_t size = 0;
    if (bytes.size() < 8) return absl::InvalidArgumentError("scene blob: truncated");
    std::memcpy(&size, bytes.data(), 8);
    if (size > kMaxPreparedSceneBytes)
        return absl::InvalidArgumentError(absl::StrCat(
            "scene blob: ", size, " bytes unpacked, over the limit of ", kMaxPreparedSceneBytes));
    // The frame must say the same size before anything that large is allocated.
    const unsigned long long framed = ZSTD_getFrameContentSize(bytes.data() + 8, bytes.size() - 8);
    if (framed != size)
        return absl::InvalidArgumentError("scene blob: its frame and header disagree on its size");
    std::string raw(size, '\0');
    const size_t got = ZSTD_decompress(raw.data(), raw.size(), bytes.data() + 8, bytes.size() - 8);
    if (ZSTD_isError(got) || got != size)
        return absl::InvalidArgumentError(absl::StrCat(
            "scene blob: corrupt (", ZSTD_isError(got) ? ZSTD_getErrorName(got) : "short", ")"));
    return DecodePreparedScene(raw, texture_filter);
}

}  // namespace pf
