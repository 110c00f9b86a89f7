// How far an image is from a reference: the metrics of `photonfarm compare` and of the error
// against run time (docs/farm.md, "Error without a reference", for the estimate without one).
#pragma once

#include <cstdint>

#include "absl/status/statusor.h"
#include "core/film/image.h"

namespace pf {

// Over every channel of the pixels that are finite in both images. A pixel with a NaN or Inf
// channel is counted apart, in either image, and left out: a comparison with a nonzero count
// has failed, whatever the metrics say (`photonfarm compare` exits 3). Where no pixel is
// finite in both, the metrics are NaN: nothing was measured, which is not a match.
struct ImageDifference {
    double rmse = 0;     // root mean squared error
    double rel_mse = 0;  // mean of (image - reference)^2 / (reference^2 + 0.01)
    double psnr = 0;     // dB, against the reference's largest finite value; +Inf if equal
    double max_abs = 0;  // largest |image - reference|
    uint64_t nonfinite_pixels = 0;            // pixels of `image` with a NaN or Inf channel
    uint64_t nonfinite_reference_pixels = 0;  // pixels of `reference` with one
    // Whether every pixel of both images is finite, and so counted in the metrics.
    bool AllFinite() const { return nonfinite_pixels == 0 && nonfinite_reference_pixels == 0; }
};

// Pixels with a NaN or Inf channel.
uint64_t NonfinitePixels(const Image& image);

// INVALID_ARGUMENT when the sizes differ (naming both).
absl::StatusOr<ImageDifference> CompareImages(const Image& image, const Image& reference);

}  // namespace pf
