// Writing images from the command line: checks made before any work starts, so no render is
// lost to a typo in a path, and the EXR (+ PNG) pair every command writes.
#pragma once

#include <string>

#include "absl/status/status.h"
#include "core/film/exr_io.h"
#include "core/film/image.h"

namespace pf {

// Before any work: both image paths writable (either may be "") and the snapshot folder
// made (may be ""). The first problem, naming the path.
absl::Status PrepareOutputs(const std::string& exr, const std::string& png,
                            const std::string& snapshot_dir);
// Writes `exr` (float RGB with metadata) and, when `png` is not empty, a tone-mapped PNG;
// logs each file written.
absl::Status WriteImageFiles(const Image& image, const ImageMetadata& metadata,
                             const std::string& exr, const std::string& png, float exposure);

}  // namespace pf
