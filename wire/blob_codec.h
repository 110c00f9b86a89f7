// Compact byte encodings of what the farm moves in bulk: a job's hit points, an epoch's
// squared radii, images. Floats are split into byte planes (all first bytes, then all second
// bytes...) before zstd, which puts the slowly varying sign/exponent bytes together: squared
// radii shrink to ~2.3 bytes per hit point, against ~3.8 for zstd alone. Decoding treats the
// bytes as hostile: sizes are checked before anything is allocated from them.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "absl/status/statusor.h"
#include "core/film/image.h"
#include "core/job/gather_regions.h"
#include "core/job/hit_point.h"
#include "core/scene/scene.h"

namespace pf {

// A content-addressed blob: its bytes and their SHA-256 (hex).
struct Blob {
    std::string digest;
    std::string bytes;

    static Blob Of(std::string bytes);
};

std::string EncodeFloats(std::span<const float> values);
// `expected_count` guards against a blob for another job: any other count is refused.
absl::StatusOr<std::vector<float>> DecodeFloats(std::string_view bytes, uint64_t expected_count);

// An epoch's gather regions: the squared radii as byte planes, then, where some hit point's
// surface ends within its radius, the edges' low and high words as byte planes (nearly all
// 0xff: a few bits a hit point after zstd). `expected_count` as for DecodeFloats.
std::string EncodeGatherRegions(const GatherRegions& regions);
absl::StatusOr<GatherRegions> DecodeGatherRegions(std::string_view bytes, uint64_t expected_count);

// What the photon pass reads of each hit point (position, normal, weight); the pixel stays
// with the coordinator and decodes as 0.
std::string EncodeHitPoints(std::span<const HitPoint> hit_points);
absl::StatusOr<std::vector<HitPoint>> DecodeHitPoints(std::string_view bytes,
                                                      uint64_t expected_count);

// An image's RGB floats, row-major from the top; the size travels beside it. Images of more
// than kMaxImagePixels (the hit point limit at one per pixel) are refused.
inline constexpr uint64_t kMaxImagePixels = uint64_t{1} << 25;
std::string EncodeImagePixels(const Image& image);
absl::StatusOr<Image> DecodeImagePixels(std::string_view bytes, int width, int height);

// A job's prepared scene (core/scene/prepared_scene.h), zstd-compressed: what a worker
// fetches instead of the scene's files. Decoding refuses more than kMaxPreparedSceneBytes
// unpacked and whatever DecodePreparedScene refuses.
inline constexpr uint64_t kMaxPreparedSceneBytes = uint64_t{16} << 30;
std::string EncodeSceneBlob(const Scene& scene);
absl::StatusOr<Scene> DecodeSceneBlob(std::string_view bytes, bool texture_filter);

}  // namespace pf
