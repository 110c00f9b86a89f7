// Reading and writing float RGB OpenEXR images with string metadata, through OpenEXR
// directly (it starts in milliseconds, unlike OpenImageIO).
#pragma once

#include <map>
#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/film/image.h"

namespace pf {

using ImageMetadata = std::map<std::string, std::string>;

// The EXR file's bytes: 32-bit float R, G, B channels, ZIP-compressed, with each metadata
// entry as a string attribute.
absl::StatusOr<std::string> EncodeExr(const Image& image, const ImageMetadata& metadata = {});

// EncodeExr's bytes, written to a temporary file first and renamed, so an existing file is
// replaced only by a complete one.
absl::Status WriteExr(const std::string& path, const Image& image,
                      const ImageMetadata& metadata = {});

// Reads the R, G, B channels of an EXR file as float; string attributes go to *metadata.
absl::StatusOr<Image> ReadExr(const std::string& path, ImageMetadata* metadata = nullptr);

}  // namespace pf
