// Image difference metrics.
#include "core/film/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "absl/strings/str_cat.h"

namespace pf {

uint64_t NonfinitePixels(const Image& image) {
    return std::count_if(image.pixels.begin(), image.pixels.end(),
                         [](const Rgb& p) { return !IsFinite(p); });
}

absl::StatusOr<ImageDifference> CompareImages(const Image& image, const Image& reference) {
    if (image.width != reference.width || image.height != reference.height)
        return absl::InvalidArgumentError(absl::StrCat("the images differ in size: ", image.width,
                                                       "x", image.height, " against ",
                                                       reference.width, "x", reference.height));
    ImageDifference difference;
    double squared = 0, relative = 0, peak = 0;
    uint64_t samples = 0;
    for (size_t p = 0; p < image.pixels.size(); ++p) {
        const bool finite = IsFinite(image.pixels[p]),
                   reference_finite = IsFinite(reference.pixels[p]);
        difference.nonfinite_pixels += finite ? 0 : 1;
        difference.nonfinite_reference_pixels += reference_finite ? 0 : 1;
        if (!finite || !reference_finite) continue;
        for (int c = 0; c < 3; ++c) {
            const double value = image.pixels[p][c], expected = reference.pixels[p][c];
            const double error = value - expected;
            squared += error * error;
            relative += error * error / (expected * expected + 0.01);
            difference.max_abs = std::max(difference.max_abs, std::abs(error));
            peak = std::max(peak, std::abs(expected));
            ++samples;
        }
    }
    if (samples == 0 && !image.pixels.empty()) {
        const double nothing = std::numeric_limits<double>::quiet_NaN();
        difference.rmse = difference.rel_mse = difference.psnr = difference.max_abs = nothing;
        return difference;
    }
    if (samples > 0) {
        difference.rmse = std::sqrt(squared / samples);
        difference.rel_mse = relative / samples;
    }
    difference.psnr = difference.rmse > 0 && peak > 0 ? 20 * std::log10(peak / difference.rmse)
                                                      : std::numeric_limits<double>::infinity();
    return difference;
}

}  // namespace pf
