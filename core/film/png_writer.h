// Tone-mapped 8-bit sRGB PNG output through OpenImageIO. Kept in its own library (pf_png)
// because OpenImageIO costs every process that links it ~0.4 s of start-up.
#pragma once

#include <string>

#include "absl/status/status.h"
#include "core/film/image.h"

namespace pf {

// Scales by 2^exposure, clamps to [0, 1] and encodes with the sRGB transfer function.
absl::Status WritePng(const std::string& path, const Image& image, float exposure = 0.0f);

}  // namespace pf
