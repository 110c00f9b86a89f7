// Decompressing the gzip files scenes bring (pbrt's .pbrt.gz includes and .ply.gz meshes),
// in memory, through zlib, within a size limit: a few bytes cannot ask for gigabytes.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "absl/status/statusor.h"

namespace pf {

// Whether `bytes` begin as a gzip stream does (1f 8b).
bool IsGzip(std::string_view bytes);

// The decompressed contents of gzip stream `bytes` (members one after another are joined, as
// gunzip does). A stream that is malformed, truncated or would decompress past `max_bytes`
// is refused naming `name` (INVALID_ARGUMENT, or RESOURCE_EXHAUSTED past the limit).
absl::StatusOr<std::string> Gunzip(std::string_view bytes, const std::string& name,
                                   uint64_t max_bytes);

}  // namespace pf
