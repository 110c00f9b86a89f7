// Reads both images, prints the metrics as text or JSON.
#include "client/compare_command.h"

#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "absl/strings/str_format.h"
#include "core/film/exr_io.h"
#include "core/film/image_metrics.h"

namespace pf {
namespace {

struct CompareOptions {
    std::string image, reference;
    bool json = false;
};

// JSON has no infinity: an exact match's PSNR is written as null.
std::string JsonNumber(double value) {
    return std::isfinite(value) ? absl::StrFormat("%.9g", value) : "null";
}

int RunCompare(const CompareOptions& options) {
    absl::StatusOr<Image> image = ReadExr(options.image);
    absl::StatusOr<Image> reference = image.ok() ? ReadExr(options.reference) : image.status();
    absl::StatusOr<ImageDifference> difference =
        reference.ok() ? CompareImages(*image, *reference) : reference.status();
    if (!difference.ok()) {
        spdlog::error("{}", std::string(difference.status().message()));
        return 1;
    }
    const ImageDifference& d = *difference;
    if (options.json) {
        std::printf(
            "{\"rmse\":%s,\"rel_mse\":%s,\"psnr\":%s,\"max_abs\":%s,\"nonfinite_pixels\":%llu,"
            "\"nonfinite_reference_pixels\":%llu}\n",
            JsonNumber(d.rmse).c_str(), JsonNumber(d.rel_mse).c_str(), JsonNumber(d.psnr).c_str(),
            JsonNumber(d.max_abs).c_str(), static_cast<unsigned long long>(d.nonfinite_pixels),
            static_cast<unsigned long long>(d.nonfinite_reference_pixels));
    } else {
        std::printf(
            "rmse %.6g\nrel_mse %.6g\npsnr %.2f dB\nmax_abs %.6g\nnonfinite_pixels %llu\n"
            "nonfinite_reference_pixels %llu\n",
            d.rmse, d.rel_mse, d.psnr, d.max_abs,
            static_cast<unsigned long long>(d.nonfinite_pixels),
            static_cast<unsigned long long>(d.nonfinite_reference_pixels));
    }
    // A NaN or Inf pixel, in either image, is a defect worth failing a script on: the metrics
    // leave it out, so they alone would not show it.
    if (!d.AllFinite())
        spdlog::error("{} NaN/Inf pixels in {}, {} in {}: left out of the metrics",
                      d.nonfinite_pixels, options.image, d.nonfinite_reference_pixels,
                      options.reference);
    return d.AllFinite() ? 0 : 3;
}

}  // namespace

void AddCompareCommand(CLI::App& app, int* exit_code) {
    auto options = std::make_shared<CompareOptions>();
    CLI::App* compare = app.add_subcommand("compare",
                                           "Compare an EXR image with a reference: RMSE, relative "
                                           "MSE, PSNR, max difference, NaN/Inf pixels "
                                           "(exit code 3 when either image has NaN or Inf pixels)");
    compare->add_option("image", options->image, "The image (EXR)")
        ->required()
        ->check(CLI::ExistingFile);
    compare->add_option("reference", options->reference, "The reference (EXR), the same size")
        ->required()
        ->check(CLI::ExistingFile);
    compare->add_flag("--json", options->json, "Print one JSON object");
    compare->callback([options, exit_code] { *exit_code = RunCompare(*options); });
}

}  // namespace pf
