// Tone-mapped 8-bit sRGB PNG: encoded in memory (the dashboard serves it) or written to a file,
// through stb_image_write. Kept in its own library (pf_png) so only the processes that write
// PNG link it.
#pragma once

#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/film/image.h"

namespace pf {

// Scales by 2^exposure, clamps to [0, 1] and encodes with the sRGB transfer function: the
// PNG file's bytes. INVALID_ARGUMENT for an empty image.
absl::StatusOr<std::string> EncodePng(const Image& image, float exposure = 0.0f);

// EncodePng, written to `path` (whole or not at all).
absl::Status WritePng(const std::string& path, const Image& image, float exposure = 0.0f);

}  // namespace pf
