// pbrt-v4's participating media, as far as photonfarm renders them: a homogeneous medium's
// absorption on either side of the shapes that bound it (MediumInterface's inside and outside),
// which every pass applies by Beer-Lambert along each segment, by the medium of the side of the
// surface it ends at (Material::absorption, outside_absorption). Scattering, emission and the
// other media types are left out, each with a note.
#include <algorithm>

#include "absl/strings/str_cat.h"
#include "core/scene_io/pbrt/pbrt_scene_builder.h"

namespace pf::pbrt {

absl::Status PbrtSceneBuilder::MakeNamedMedium(const std::string& name, ParameterList& parameters,
                                               const Location& where) {
    const std::string type = parameters.String("type", "");
    Medium medium;
    if (type != "homogeneous") {
        parameters.ConsumeAll();
        Warn(where, absl::StrCat("MakeNamedMedium \"", name, "\": \"", type,
                                 "\" media are not rendered; the medium is left out"));
        media_[name] = medium;
        return absl::OkStatus();
    }
    // pbrt-v4's defaults: sigma_a = sigma_s = 1, scale 1.
    const std::string preset = parameters.String("preset", "");
    const std::optional<Rgb> sigma_a = parameters.Color("sigma_a", SpectrumUse::kUnbounded);
    const std::optional<Rgb> sigma_s = parameters.Color("sigma_s", SpectrumUse::kUnbounded);
    const double scale = parameters.Float("scale", 1.0);
    if (!parameters.status().ok()) return parameters.status();
    if (!preset.empty())
        Warn(where, absl::StrCat("MakeNamedMedium \"", name, "\": preset \"", preset,
                                 "\" is not known here; sigma_a and sigma_s are read instead"));
    medium.absorption = sigma_a.value_or(Rgb(1.0f)) * static_cast<float>(scale);
    const Rgb scattering = sigma_s.value_or(Rgb(1.0f)) * static_cast<float>(scale);
    if (!(scale >= 0 && MinComponent(medium.absorption) >= 0 && MinComponent(scattering) >= 0 &&
          MaxComponent(medium.absorption) <= 1e30f && MaxComponent(scattering) <= 1e30f))
        return ErrorAt(where, absl::StrCat("MakeNamedMedium \"", name,
                                           "\": sigma_a, sigma_s and scale must be finite and "
                                           "not negative"));
    if (MaxComponent(scattering) > 0)
        Warn(where, absl::StrCat("MakeNamedMedium \"", name,
                                 "\": scattering (sigma_s) is left out; the medium absorbs only"));
    parameters.Float("g", 0.0);
    if (parameters.Color("Le", SpectrumUse::kIlluminant).value_or(Rgb(0.0f)) != Rgb(0.0f))
        Warn(where, absl::StrCat("MakeNamedMedium \"", name, "\": emission (Le) is left out"));
    parameters.Float("Lescale", 1.0);
    media_[name] = medium;
    return absl::OkStatus();
}

absl::Status PbrtSceneBuilder::SetMediumInterface(const std::string& inside,
                                                  const std::string& outside,
                                                  const Location& where) {
    for (const std::string& name : {inside, outside})
        if (!name.empty() && !media_.contains(name))
            return ErrorAt(where, absl::StrCat("MediumInterface: no medium named \"", name, "\""));
    state_.inside_medium = inside;
    state_.outside_medium = outside;
    return absl::OkStatus();
}

// A segment of a path ends at a surface; the surface's media say what it crossed: its inside
// medium where it ended at the back (it came from inside), its outside medium at the front.
// For media bounded by surfaces that name them (glass of liquid: the liquid's surface with the
// liquid inside, the glass's with it outside), that is the medium the segment crossed.
PbrtSceneBuilder::Absorption PbrtSceneBuilder::MediumAbsorption(const GraphicsState& state) const {
    Absorption absorption;
    if (!state.inside_medium.empty()) absorption.inside = media_.at(state.inside_medium).absorption;
    if (!state.outside_medium.empty())
        absorption.outside = media_.at(state.outside_medium).absorption;
    return absorption;
}

}  // namespace pf::pbrt
