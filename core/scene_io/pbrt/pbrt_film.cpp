// pbrt-v4's Film and PixelFilter onto the scene's image settings.
#include <spdlog/spdlog.h>

#include <cmath>
#include <limits>
#include <map>

#include "absl/strings/str_cat.h"
#include "core/scene/pixel_filter.h"
#include "core/scene_io/pbrt/pbrt_scene_builder.h"

namespace pf::pbrt {

absl::Status PbrtSceneBuilder::Film(ParameterList& parameters, const Location& where) {
    film_width_ = parameters.Integer("xresolution", 1280);
    film_height_ = parameters.Integer("yresolution", 720);
    // The image goes where --out says: a note, not a warning (nothing of the render changes).
    if (parameters.Has("filename")) {
        parameters.String("filename", "");
        if (!options_.references_only)
            spdlog::info("{}: Film: \"filename\" is not used; the image goes where --out says",
                         parameters.Find("filename")->where.ToString());
    }
    // pbrt-v4 scales a sample whose largest RGB component exceeds this down to it, trading
    // the energy of fireflies for less noise; photonfarm's estimators keep it all.
    if (const double clamp =
            parameters.Float("maxcomponentvalue", std::numeric_limits<double>::infinity());
        parameters.Has("maxcomponentvalue") && std::isfinite(clamp))
        Warn(parameters.Find("maxcomponentvalue")->where,
             absl::StrCat("Film: \"maxcomponentvalue\" ", clamp,
                          " is left out: samples are not clamped, so where pbrt-v4 would clip "
                          "bright samples the image reads brighter than pbrt-v4's"));
    film_iso_ = parameters.Float("iso", 100.0);
    film_white_balance_ = parameters.Float("whitebalance", 0.0);
    const std::string sensor = parameters.String("sensor", "cie1931");
    if (sensor != "cie1931") {
        // pbrt-v4 then balances for D65 unless told otherwise; the camera's spectral curves
        // themselves are not available here.
        if (film_white_balance_ == 0) film_white_balance_ = 6500;
        Warn(parameters.Find("sensor")->where,
             absl::StrCat("Film: sensor \"", sensor,
                          "\": its spectral response is not modelled; the CIE 1931 observer "
                          "with the same white balance and imaging ratio stands in"));
    }
    if (film_width_ < 1 || film_height_ < 1 || film_width_ > 32768 || film_height_ > 32768)
        return ErrorAt(where, "Film: resolution must lie in 1..32768");
    if (!(film_iso_ > 0 && film_iso_ < 1e7))
        return ErrorAt(where, "Film: \"iso\" must lie in (0, 1e7)");
    if (film_white_balance_ != 0 && !(film_white_balance_ >= 4000 && film_white_balance_ <= 25000))
        return ErrorAt(where,
                       "Film: \"whitebalance\" must be 0 (none) or a temperature in [4000, "
                       "25000] K (the CIE daylight locus)");
    return absl::OkStatus();
}

absl::Status PbrtSceneBuilder::PixelFilter(const std::string& type, ParameterList& parameters,
                                           const Location& where) {
    // pbrt-v4's filters and their default radii and parameters.
    static const std::map<std::string, std::pair<FilterKind, float>> kFilters = {
        {"box", {FilterKind::kBox, 0.5f}},
        {"triangle", {FilterKind::kTriangle, 2.0f}},
        {"gaussian", {FilterKind::kGaussian, 1.5f}},
        {"mitchell", {FilterKind::kMitchell, 2.0f}},
        {"sinc", {FilterKind::kSinc, 4.0f}}};
    const auto known = kFilters.find(type);
    if (known == kFilters.end())
        return ErrorAt(where, absl::StrCat("PixelFilter \"", type,
                                           "\": not a filter (box, triangle, gaussian, mitchell, "
                                           "sinc)"));
    pf::PixelFilter filter;
    filter.kind = known->second.first;
    filter.radius_x = static_cast<float>(parameters.Float("xradius", known->second.second));
    filter.radius_y = static_cast<float>(parameters.Float("yradius", known->second.second));
    if (filter.kind == FilterKind::kGaussian)
        filter.sigma = static_cast<float>(parameters.Float("sigma", 0.5));
    if (filter.kind == FilterKind::kMitchell) {
        filter.b = static_cast<float>(parameters.Float("B", 1.0 / 3));
        filter.c = static_cast<float>(parameters.Float("C", 1.0 / 3));
    }
    if (filter.kind == FilterKind::kSinc)
        filter.tau = static_cast<float>(parameters.Float("tau", 3.0));
    if (const std::optional<std::string> problem = FilterProblem(filter))
        return ErrorAt(where, absl::StrCat("PixelFilter \"", type, "\": ", *problem));
    if (camera_finished_)
        return ErrorAt(where, "PixelFilter: must come before WorldBegin, as the camera's options");
    pixel_filter_ = filter;
    return absl::OkStatus();
}

}  // namespace pf::pbrt
