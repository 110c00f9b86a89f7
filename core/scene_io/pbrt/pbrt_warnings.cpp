// Errors and warnings of the pbrt-v4 loader: one line each, naming file and line.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "core/scene_io/pbrt/pbrt_scene_builder.h"

namespace pf::pbrt {

absl::Status ErrorAt(const Location& where, const std::string& what) {
    return absl::InvalidArgumentError(absl::StrCat(where.ToString(), ": ", what));
}

void PbrtSceneBuilder::Warn(const Location& where, const std::string& what) {
    // Packing reads the scene only for its references; the load that follows warns.
    if (options_.references_only) return;
    // The same warning for many shapes is logged once, with the count at the end.
    if (warning_counts_[what]++ > 0) return;
    // A warning whose text names its element itself (Location{}) takes no location of its own.
    const std::string line = where.file.empty()
                                 ? absl::StrCat("warning: ", what)
                                 : absl::StrCat(where.ToString(), ": warning: ", what);
    spdlog::warn("{}", line);
    if (options_.warnings) options_.warnings->push_back(line);
}

void PbrtSceneBuilder::WarnIfMoving(const Location& where, const std::string& directive) {
    double difference = 0, size = 0;
    for (int row = 0; row < 4; ++row)
        for (int column = 0; column < 4; ++column) {
            difference = std::max(
                difference, std::abs(state_.ctm.m[row][column] - state_.ctm_end.m[row][column]));
            size = std::max(size, std::abs(state_.ctm.m[row][column]));
        }
    if (!(difference > 1e-9 * std::max(size, 1.0))) return;
    Warn(where, absl::StrCat(directive,
                             ": motion blur is left out: the transform differs between "
                             "ActiveTransform StartTime and EndTime, and the scene renders "
                             "still, at the start time"));
}

void PbrtSceneBuilder::WarnUnused(const ParameterList& parameters, const std::string& directive) {
    for (const Parameter* parameter : parameters.Unused())
        Warn(parameter->where, absl::StrCat(directive, ": parameter \"", parameter->type, " ",
                                            parameter->name, "\" is not supported; ignored"));
}

}  // namespace pf::pbrt
