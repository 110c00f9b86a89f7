// Writing images from the command line: checks made before any work starts, so no render is
// lost to a typo in a path, and the EXR (+ PNG) pair every command writes.
#pragma once

#include <string>

#include "absl/status/status.h"
#include "core/film/exr_io.h"
#include "core/film/image.h"

namespace pf {

// INVALID_ARGUMENT naming the path unless its folder exists and is writable ("" is fine).
absl::Status CheckWritable(const std::string& path);
// INVALID_ARGUMENT unless `dir` exists or can be created ("" is fine).
absl::Status MakeDirectory(const std::string& dir);
// Writes `exr` (float RGB with metadata) and, when `png` is not empty, a tone-mapped PNG;
// logs each file written.
absl::Status WriteImageFiles(const Image& image, const ImageMetadata& metadata, const std::string& exr,
                             const std::string& png, float exposure);

}  // namespace pf
