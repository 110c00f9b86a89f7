// pbrt-v3 scenes read as pbrt-v4's `pbrt --upgrade` rewrites them (pbrt-v4's
// src/pbrt/parser.cpp, FormattingParserTarget): a directive's type and parameters as parsed
// are rewritten into what pbrt-v4 reads before the builder sees them. What pbrt-v3 alone
// wrote is recognised by itself (its material, light and sampler names, "color" textures,
// "mapname", float texture coordinates, two-number black bodies, an rgb "scale"), so pbrt-v4
// files pass through unchanged.
#pragma once

#include <string>
#include <vector>

#include "absl/status/status.h"
#include "core/scene_io/pbrt/pbrt_parameters.h"

namespace pf::pbrt {

struct UpgradeResult {
    std::string change;  // the first pbrt-v3 construct rewritten ("Material \"plastic\" is
                         // \"coateddiffuse\""); empty where the directive was pbrt-v4's
    std::vector<std::string> warnings;  // parameters dropped, as --upgrade warns of them
    // LightSource "infinite": its image is pbrt-v3's latitude-longitude map ("mapname"), not
    // pbrt-v4's equal-area square.
    bool lat_long_map = false;
};

// Rewrites directive `directive` ("Material", "MakeNamedMaterial", "Texture", "LightSource",
// "AreaLightSource", "Shape", "Film", "Sampler", "Integrator"; others pass) with type
// `*type` (a Texture's class in `*texture_class`) in place. Errors are what --upgrade refuses
// (a non-grey rgb "scale", a non-opaque "opacity"), without a location: the caller adds it.
absl::Status UpgradeDirective(const std::string& directive, std::string* type,
                              std::string* texture_class, ParameterList* parameters,
                              UpgradeResult* result);

}  // namespace pf::pbrt
