// pbrt-v4's participating media, as far as photonfarm renders them: a homogeneous medium's
// absorption inside a dielectric (MediumInterface's inside, on a shape of glass), which every
// pass applies by Beer-Lambert along the segments inside (Material::absorption). Scattering,
// emission and the other media types are left out, each with a note.
#include <algorithm>

#include "absl/strings/str_cat.h"
#include "core/scene/pbrt/pbrt_scene_builder.h"

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
                                                  const Location& where) {
    if (!inside.empty() && !media_.contains(inside))
        return ErrorAt(where, absl::StrCat("MediumInterface: no medium named \"", inside, "\""));
    state_.inside_medium = inside;
    return absl::OkStatus();
}

Rgb PbrtSceneBuilder::InsideAbsorption(const GraphicsState& state, const std::string& element) {
    if (state.inside_medium.empty()) return Rgb(0.0f);
    const Rgb absorption = media_.at(state.inside_medium).absorption;
    const Material& material =
        state.material >= 0 ? materials_[state.material].material : DefaultMaterial().material;
    if (material.type == MaterialType::kDielectric ||
        material.type == MaterialType::kRoughDielectric)
        return absorption;
    if (!IsBlack(absorption))
        Warn(Location{}, absl::StrCat(element, ": the medium \"", state.inside_medium,
                                      "\" is inside a surface that is not solid glass; media "
                                      "are rendered inside glass only, so it is left out"));
    return Rgb(0.0f);
}

}  // namespace pf::pbrt
