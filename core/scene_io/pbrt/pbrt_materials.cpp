// pbrt-v4 materials and textures onto photonfarm's: diffuse, smooth and rough dielectric and
// conductor (the Fresnel term of its complex index: core/shared/conductor.h), thin dielectric,
// coateddiffuse and coatedconductor (a coat over the base: core/shared/coat.h), mix,
// diffusetransmission (core/shared/translucent.h); image textures through OpenImageIO; normal
// and bump maps on any of them (Material::normal_texture, bump_texture).
#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/scene/texture_program.h"
#include "core/scene_io/image_decode.h"
#include "core/scene_io/pbrt/pbrt_scene_builder.h"
#include "core/shared/conductor.h"

namespace pf::pbrt {

absl::Status PbrtSceneBuilder::BaseColor(ParameterList& parameters, const std::string& name,
                                         Rgb fallback, const Location& where,
                                         MaterialRef* material) {
    material->material.base_color = fallback;
    if (const std::optional<std::string> texture_name = parameters.TextureName(name)) {
        const auto it = textures_.find(*texture_name);
        if (it == textures_.end()) {
            if (float_textures_.contains(*texture_name))
                return ErrorAt(where,
                               absl::StrCat("\"", name, "\" names float texture \"", *texture_name,
                                            "\"; it needs a spectrum texture"));
            return ErrorAt(where, absl::StrCat("no texture named \"", *texture_name, "\""));
        }
        const TextureRef& texture = it->second;
        if (!texture.unsupported.empty()) {
            Warn(where, absl::StrCat("\"", name, "\": ", UnsupportedNote(texture), "; ",
                                     "the material's default ", FormatRgb(fallback), " stands in"));
            return absl::OkStatus();
        }
        // A reflectance or transmittance at most 1, as pbrt-v4 clamps them.
        absl::StatusOr<int32_t> index = TextureIndex(texture, 1, 1.0f);
        if (!index.ok()) return index.status();
        material->material.base_color = texture.scale;
        material->material.base_color_texture = *index;
        material->mapping = texture.mapping;
    } else if (const std::optional<Rgb> color = parameters.Color(name)) {
        material->material.base_color = *color;
    }
    Rgb& base = material->material.base_color;
    if (!IsFinite(base) || MinComponent(base) < 0)
        return ErrorAt(where, absl::StrCat("\"", name, "\" must be finite and non-negative"));
    if (MaxComponent(base) > 1) {
        Warn(where, absl::StrCat("\"", name, "\" above 1 would create energy; clamped to 1"));
        base = Min(base, Rgb(1.0f));
    }
    return absl::OkStatus();
}

absl::StatusOr<FloatInput> PbrtSceneBuilder::FloatParameter(
    ParameterList& parameters, const std::string& name, double fallback, const std::string& what,
    const Location& where, double exponent, TextureUse use) {
    FloatInput input;
    input.value = static_cast<float>(fallback);
    const std::optional<std::string> texture_name = parameters.TextureName(name);
    if (!texture_name) {
        input.value = static_cast<float>(parameters.Float(name, fallback));
        return input;
    }
    const auto it = float_textures_.find(*texture_name);
    if (it == float_textures_.end())
        return ErrorAt(where,
                       absl::StrCat(what, " names no float texture \"", *texture_name, "\""));
    if (!it->second.unsupported.empty()) {
        Warn(where, absl::StrCat(what, ": ", UnsupportedNote(it->second), "; its default ",
                                 fallback, " stands in"));
        return input;
    }
    const TextureRef& texture = it->second;
    if (use != TextureUse::kDisplacement && MinComponent(texture.scale) < 0)
        return ErrorAt(where,
                       absl::StrCat(what, " texture \"", *texture_name,
                                    "\": its values must be non-negative (its scale is ",
                                    texture.scale.x, "; only a displacement's may be below 0)"));
    // Cut-outs are tested inside the kernels' traversal, where a procedural texture's
    // evaluation would weigh on every ray.
    if (texture.program && use == TextureUse::kCutOut) {
        Warn(where, absl::StrCat(what, ": ", texture.described,
                                 " is evaluated at each point, and cut-outs read images; its "
                                 "default ",
                                 fallback, " stands in"));
        return input;
    }
    const absl::StatusOr<int32_t> image = TextureIndex(
        texture, exponent, std::numeric_limits<float>::max(), use == TextureUse::kDisplacement);
    if (!image.ok()) return image.status();
    input = {texture.scale.x, *image, texture.mapping};
    return input;
}

absl::StatusOr<int> PbrtSceneBuilder::MakeMaterial(const std::string& type,
                                                   ParameterList& parameters,
                                                   const Location& where) {
    MaterialRef material;
    absl::Status status;
    // GGX alpha from pbrt's roughness parameters, numbers or float textures (remapped by
    // sqrt, as pbrt-v4's RoughnessToAlpha, unless remaproughness is false; a texture's values
    // likewise, on decoding); anisotropy is averaged away, or where a texture gives it, the
    // first texture is taken. Sets the material's roughness texture where one is given.
    const bool remap = parameters.Bool("remaproughness", true);
    auto roughness_alpha = [&](const std::string& prefix = "") -> absl::StatusOr<float> {
        const std::string what = absl::StrCat("Material \"", type, "\": \"", prefix);
        const double exponent = remap ? 0.5 : 1.0;
        absl::StatusOr<FloatInput> u = FloatParameter(parameters, prefix + "roughness", 0.0,
                                                      what + "roughness\"", where, exponent);
        if (!u.ok()) return u.status();
        absl::StatusOr<FloatInput> v = u;
        if (parameters.Has(prefix + "uroughness") || parameters.Has(prefix + "vroughness")) {
            u = FloatParameter(parameters, prefix + "uroughness", u->value, what + "uroughness\"",
                               where, exponent);
            if (!u.ok()) return u.status();
            v = FloatParameter(parameters, prefix + "vroughness", u->value, what + "vroughness\"",
                               where, exponent);
            if (!v.ok()) return v.status();
            if (u->value != v->value || u->texture != v->texture)
                Warn(where,
                     absl::StrCat("Material \"", type, "\": anisotropic ", prefix, "roughness (",
                                  u->value, ", ", v->value, ") rendered isotropic with ",
                                  u->texture != kNoTexture || v->texture != kNoTexture
                                      ? "the first texture"
                                      : "their mean"));
        }
        const FloatInput textured = u->texture != kNoTexture ? *u : *v;
        const double roughness =
            textured.texture != kNoTexture ? textured.value : 0.5 * (u->value + v->value);
        if (!(roughness >= 0 && roughness <= 1e3))
            return ErrorAt(where, absl::StrCat("Material \"", type, "\": ", prefix,
                                               "roughness must lie in [0, 1000]"));
        const double alpha = remap ? std::sqrt(roughness) : roughness;
        if (textured.texture != kNoTexture && alpha > 0) {
            Material& m = material.material;
            if (m.roughness_texture != kNoTexture && m.roughness_texture != textured.texture)
                Warn(where, absl::StrCat("Material \"", type,
                                         "\": one roughness texture scales both roughnesses; \"",
                                         prefix, "roughness\"'s is left out"));
            else
                m.roughness_texture = textured.texture;
            if (m.base_color_texture == kNoTexture) material.mapping = textured.mapping;
        }
        return alpha <= 0 ? 0.0f
                          : static_cast<float>(std::clamp(alpha, double(kMinRoughness), 1.0));
    };
    auto index_of_refraction = [&](double fallback, const std::string& name = "eta") {
        const Parameter* eta = parameters.Find(name);
        if (eta != nullptr && eta->type == "float") return parameters.Float(name, fallback);
        const std::optional<Rgb> color = parameters.Color(name, SpectrumUse::kUnbounded);
        return color ? double(color->y) : fallback;
    };
    // The coat of coateddiffuse and coatedconductor: its index (`eta_name`), roughness (with
    // `prefix`), thickness and depth, as pbrt-v4's LayeredBxDF takes them; scattering inside
    // it (albedo above 0) is left out, with a note.
    auto coat = [&](const std::string& eta_name, const std::string& prefix) -> absl::Status {
        Material& m = material.material;
        const double eta = index_of_refraction(1.5, eta_name);
        m.coat_ior = static_cast<float>(eta == 0 ? 1.0 : eta);  // pbrt-v4 reads 0 as 1
        const absl::StatusOr<float> alpha = roughness_alpha(prefix);
        if (!alpha.ok()) return alpha.status();
        m.coat_roughness = *alpha;
        // A textured thickness (kroken's moka pot) varies over the surface; one number stands
        // in: pbrt-v4's default.
        double thickness = 0.01;
        if (const std::optional<std::string> texture = parameters.TextureName("thickness")) {
            Warn(where, absl::StrCat("Material \"", type, "\": \"thickness\" from texture \"",
                                     *texture, "\" is not read; the default 0.01 is used"));
        } else {
            thickness = parameters.Float("thickness", thickness);
        }
        const int depth = parameters.Integer("maxdepth", 10);
        const int samples = parameters.Integer("nsamples", 1);
        parameters.Float("g", 0.0);
        const std::optional<Rgb> albedo = parameters.Color("albedo");
        if (albedo && MaxComponent(*albedo) > 0)
            Warn(where, absl::StrCat("Material \"", type,
                                     "\": scattering inside the coat (\"albedo\") is left out; "
                                     "the coat absorbs only"));
        if (!(m.coat_ior >= 1.0f && std::isfinite(m.coat_ior)))
            return ErrorAt(where, absl::StrCat("Material \"", type, "\": \"", eta_name,
                                               "\" must be at least 1"));
        if (!(thickness >= 0 && thickness <= 1e6))
            return ErrorAt(
                where, absl::StrCat("Material \"", type, "\": \"thickness\" must lie in [0, 1e6]"));
        if (!(depth >= 1 && depth <= 1024))
            return ErrorAt(
                where, absl::StrCat("Material \"", type, "\": \"maxdepth\" must lie in [1, 1024]"));
        if (!(samples >= 1 && samples <= 1024))
            return ErrorAt(
                where, absl::StrCat("Material \"", type, "\": \"nsamples\" must lie in [1, 1024]"));
        m.coat_samples = static_cast<uint32_t>(samples);
        m.coat_thickness = static_cast<float>(thickness);
        // pbrt-v4's walk crosses the layer once per step: down to the base, up to the coat
        // (where light may leave), so maxdepth allows maxdepth / 2 visits to the base with a
        // chance to leave after each (a smooth coat over white then reflects 0.866 head-on at
        // the default 10, as pbrt-v4's does, and 0.917 with no limit).
        m.coat_depth = static_cast<uint32_t>(depth / 2);
        return absl::OkStatus();
    };
    // A conductor's Fresnel term as pbrt-v4's (`prefix` "" or coatedconductor's "conductor."):
    // a "reflectance" r (colour or texture) stands for the index 1 + i 2 sqrt(r / (1 - r));
    // else the complex index eta + i k, each a named metal's, a spectrum's or a colour, copper's
    // where not given. Kept in vacuum: under a coat, core/shared/coat.h divides by its index.
    auto conductor = [&](const std::string& prefix) -> absl::Status {
        Material& m = material.material;
        if (parameters.Has("reflectance")) {
            if (parameters.Has(prefix + "eta") || parameters.Has(prefix + "k"))
                return ErrorAt(where,
                               absl::StrCat("Material \"", type,
                                            "\": give \"reflectance\" "
                                            "or \"",
                                            prefix, "eta\" and \"", prefix, "k\", not both"));
            m.conductor = gpu::kConductorReflectance;
            const absl::Status read =
                BaseColor(parameters, "reflectance", Rgb(1.0f), where, &material);
            if (read.ok() && m.base_color_texture == kNoTexture) {  // the index once, not per hit
                m.conductor = gpu::kConductorComplex;
                for (int c = 0; c < 3; ++c) {
                    const float r = std::clamp(m.base_color[c], 0.0f, 0.9999f);
                    m.conductor_k[c] = 2.0f * std::sqrt(r / (1.0f - r));
                }
                m.base_color = Rgb(1.0f);
            }
            return read;
        }
        m.conductor = gpu::kConductorComplex;
        m.base_color = Rgb(1.0f);
        const auto part = [&](const std::string& name, bool imaginary) {
            const Parameter* given = parameters.Find(name);
            const std::string named = given == nullptr ? (imaginary ? "metal-Cu-k" : "metal-Cu-eta")
                                      : given->strings.empty() ? ""
                                                               : given->strings[0];
            const std::optional<Rgb> color = parameters.Color(name, SpectrumUse::kUnbounded);
            if (const std::optional<ComplexIndex> metal = NamedMetalIndex(named))
                return imaginary ? metal->k : metal->eta;
            return color.value_or(Rgb(imaginary ? 0.0f : 1.0f));
        };
        m.conductor_eta = part(prefix + "eta", false);
        m.conductor_k = part(prefix + "k", true);
        for (int c = 0; c < 3; ++c)
            if (!(m.conductor_eta[c] > 0 && m.conductor_eta[c] < 1e4f && m.conductor_k[c] >= 0 &&
                  m.conductor_k[c] < 1e4f))
                return ErrorAt(where, absl::StrCat("Material \"", type, "\": \"", prefix,
                                                   "eta\" must lie in (0, 1e4) and \"", prefix,
                                                   "k\" in [0, 1e4)"));
        return absl::OkStatus();
    };
    if (type == "diffuse") {
        status = BaseColor(parameters, "reflectance", Rgb(0.5f), where, &material);
    } else if (type == "coateddiffuse") {
        status = BaseColor(parameters, "reflectance", Rgb(0.5f), where, &material);
        if (status.ok()) status = coat("eta", "");
    } else if (type == "coatedconductor") {
        status = coat("interface.eta", "interface.");
        if (status.ok()) {
            const absl::StatusOr<float> alpha = roughness_alpha("conductor.");
            if (!alpha.ok()) return alpha.status();
            material.material.type =
                *alpha > 0 ? MaterialType::kRoughConductor : MaterialType::kMirror;
            material.material.roughness = *alpha;
        }
        if (status.ok()) status = conductor("conductor.");
    } else if (type == "dielectric" || type == "thindielectric") {
        material.material.type =
            type == "dielectric" ? MaterialType::kDielectric : MaterialType::kThinDielectric;
        material.material.base_color = Rgb(1.0f);
        material.material.ior = static_cast<float>(index_of_refraction(1.5));
        if (type == "dielectric") {
            const absl::StatusOr<float> alpha = roughness_alpha();
            if (!alpha.ok()) return alpha.status();
            if (*alpha > 0) {
                material.material.type = MaterialType::kRoughDielectric;
                material.material.roughness = *alpha;
            }
        }
        // An eta below 1 is an interface whose outside is the denser side (glass-of-water's
        // water against glass); Fresnel, refraction and the eta^2 of radiance take either.
        if (!(material.material.ior > 0.0f && std::isfinite(material.material.ior)))
            return ErrorAt(where, absl::StrCat("Material \"", type,
                                               "\": \"eta\" must be positive and finite"));
    } else if (type == "conductor") {
        material.material.type = MaterialType::kMirror;
        const absl::StatusOr<float> alpha = roughness_alpha();
        if (!alpha.ok()) return alpha.status();
        if (*alpha > 0) {
            material.material.type = MaterialType::kRoughConductor;
            material.material.roughness = *alpha;
        }
        status = conductor("");
    } else if (type == "interface" || type == "none" || type.empty()) {
        material.interface = true;  // pbrt-v4 reads "" and "none" as no surface too
    } else if (type == "mix") {
        // pbrt-v4's MixMaterial: at each point one of the two, the second with probability
        // "amount" (picked by a hash of the point, Scene::ResolveMaterial).
        const Parameter* list = parameters.Consume("materials");
        const std::vector<std::string> names =
            list != nullptr && list->type == "string" ? list->strings : std::vector<std::string>{};
        if (names.size() != 2)
            return ErrorAt(where,
                           "Material \"mix\" needs \"string materials\" naming two materials");
        for (int i = 0; i < 2; ++i) {
            const auto it = named_materials_.find(names[i]);
            if (it == named_materials_.end())
                return ErrorAt(
                    where, absl::StrCat("Material \"mix\": no material named \"", names[i], "\""));
            if (materials_[it->second].interface)
                return ErrorAt(where, absl::StrCat("Material \"mix\": \"", names[i],
                                                   "\" is an interface, not a surface"));
            material.mix[i] = it->second;
        }
        const absl::StatusOr<FloatInput> amount =
            FloatParameter(parameters, "amount", 0.5, "Material \"mix\": \"amount\"", where);
        if (!amount.ok()) return amount.status();
        if (!(amount->value >= 0 && amount->value <= 1))
            return ErrorAt(where, "Material \"mix\": \"amount\" must lie in [0, 1]");
        material.material.type = MaterialType::kMix;
        material.material.mix_amount = amount->value;
        material.material.mix_texture = amount->texture;
        material.mapping = amount->mapping;
    } else if (type == "diffusetransmission") {
        status = DiffuseTransmission(parameters, where, &material);
    } else if (type == "subsurface") {
        // Its nearest surface: the interface (pbrt-v4's default index 1.33, its roughness)
        // over a diffuse base of its multiple-scattering albedo; light does not travel under
        // the surface.
        const bool eta_given = parameters.Has("eta");
        status = SubsurfaceAlbedo(parameters, where, &material);
        if (status.ok()) status = coat("eta", "");
        if (!eta_given) material.material.coat_ior = 1.33f;
        material.material.coat_thickness = 0;
        parameters.ConsumeAll();  // mfp, g, scale: what light under the surface would need
        Warn(where,
             "Material \"subsurface\" is shaded as its nearest surface, a coated diffuse "
             "of its albedo: light does not travel under the surface");
    } else if (type == "hair") {
        status = HairColour(parameters, where, &material);
        parameters.ConsumeAll();
        const Rgb& c = material.material.base_color;
        Warn(where, absl::StrCat("Material \"hair\" is shaded as a diffuse surface of its colour (",
                                 absl::StrFormat("%.3g %.3g %.3g", c.x, c.y, c.z),
                                 ") until a hair model exists"));
    } else if (type == "measured") {
        parameters.ConsumeAll();
        material.material.base_color = Rgb(0.5f);
        Warn(where,
             "Material \"measured\" (a measured BSDF file) is not read; shaded as grey "
             "diffuse (0.5)");
    } else {
        return ErrorAt(where, absl::StrCat("Material \"", type, "\" is unknown"));
    }
    if (!status.ok()) return status;
    parameters.String("type", "");  // MakeNamedMaterial's
    if (absl::Status detail = ShadingDetail(parameters, where, &material); !detail.ok())
        return detail;
    materials_.push_back(material);
    return static_cast<int>(materials_.size() - 1);
}

absl::Status PbrtSceneBuilder::DiffuseTransmission(ParameterList& parameters, const Location& where,
                                                   MaterialRef* material) {
    // pbrt-v4's defaults: 0.25 each, both times "scale" (core/shared/translucent.h).
    if (absl::Status status = BaseColor(parameters, "reflectance", Rgb(0.25f), where, material);
        !status.ok())
        return status;
    MaterialRef through;
    if (absl::Status status = BaseColor(parameters, "transmittance", Rgb(0.25f), where, &through);
        !status.ok())
        return status;
    Rgb& transmittance = material->material.transmittance;
    transmittance = through.material.base_color;
    const int32_t texture = through.material.base_color_texture;
    // A texture read at the point (the surface's one set of coordinates: its mapping, or the
    // reflectance texture's where that has one and it is the same).
    const bool same_mapping =
        material->material.base_color_texture == kNoTexture || material->mapping == through.mapping;
    // A procedural one is evaluated at each point, through the reflectance's mapping where it
    // reads (s, t).
    const bool procedural = texture != kNoTexture && scene_.textures[texture]->IsProcedural();
    if (texture != kNoTexture && (same_mapping || procedural)) {
        material->material.transmittance_texture = texture;
        if (same_mapping) {
            material->mapping = through.mapping;
        } else if (!ProgramUvWords(scene_.textures[texture]->program).empty()) {
            Warn(where,
                 "Material \"diffusetransmission\": the \"transmittance\" texture is "
                 "read through the reflectance texture's mapping, not its own");
        }
    } else if (texture != kNoTexture) {
        const std::vector<Rgb>& texels = scene_.textures[texture]->texels;
        Rgbd sum(0.0);
        for (const Rgb& texel : texels) sum += Rgbd(texel);
        transmittance = transmittance * Rgb(sum / static_cast<double>(texels.size()));
        Warn(where, absl::StrCat("Material \"diffusetransmission\": the \"transmittance\" texture "
                                 "under another mapping than the reflectance's is taken as its "
                                 "mean colour (",
                                 absl::StrFormat("%.3g %.3g %.3g", transmittance.x, transmittance.y,
                                                 transmittance.z),
                                 ")"));
    }
    const double scale = parameters.Float("scale", 1.0);
    if (!(std::isfinite(scale) && scale >= 0))
        return ErrorAt(where,
                       "Material \"diffusetransmission\": \"scale\" must be finite and "
                       "non-negative");
    // pbrt-v4 clamps each of scale x R and scale x T to 1.
    Rgb& reflectance = material->material.base_color;
    reflectance = Min(reflectance * static_cast<float>(scale), Rgb(1.0f));
    // A textured transmittance is clamped at the point (Scene::ShadingMaterial).
    transmittance = transmittance * static_cast<float>(scale);
    if (material->material.transmittance_texture == kNoTexture)
        transmittance = Min(transmittance, Rgb(1.0f));
    if (MaxComponent(reflectance + transmittance) > 1)
        Warn(where,
             "Material \"diffusetransmission\": reflectance + transmittance above 1 "
             "creates energy (as in pbrt-v4)");
    return absl::OkStatus();
}

absl::Status PbrtSceneBuilder::SubsurfaceAlbedo(ParameterList& parameters, const Location& where,
                                                MaterialRef* material) {
    if (parameters.Has("reflectance"))  // pbrt-v4's multiple-scattering albedo, as given
        return BaseColor(parameters, "reflectance", Rgb(1.0f), where, material);
    if (parameters.Has("name")) {
        material->material.base_color = Rgb(0.5f);
        Warn(where, absl::StrCat("Material \"subsurface\": the named medium \"",
                                 parameters.String("name", ""),
                                 "\" is not known here; its albedo is taken as 0.5"));
        return absl::OkStatus();
    }
    // The albedo of a semi-infinite medium of single-scattering albedo a under an index-matched
    // boundary, in the diffusion approximation (Jensen et al. 2001, A = 1): a/2 (1 +
    // exp(-4/3 s)) exp(-s), s = sqrt(3 (1 - a)); pbrt-v4's default coefficients, per mm.
    const Rgb sigma_a =
        parameters.Color("sigma_a", SpectrumUse::kUnbounded).value_or(Rgb(.0011f, .0024f, .014f));
    const Rgb sigma_s =
        parameters.Color("sigma_s", SpectrumUse::kUnbounded).value_or(Rgb(2.55f, 3.21f, 3.77f));
    Rgb& albedo = material->material.base_color;
    for (int c = 0; c < 3; ++c) {
        const double extinction = double(sigma_a[c]) + sigma_s[c];
        if (!(sigma_a[c] >= 0 && sigma_s[c] >= 0 && std::isfinite(extinction)))
            return ErrorAt(where,
                           "Material \"subsurface\": \"sigma_a\" and \"sigma_s\" must "
                           "be finite and non-negative");
        const double a = extinction > 0 ? sigma_s[c] / extinction : 0.0;
        const double root = std::sqrt(3 * (1 - a));
        albedo[c] = static_cast<float>(a / 2 * (1 + std::exp(-4.0 / 3.0 * root)) * std::exp(-root));
    }
    return absl::OkStatus();
}

absl::Status PbrtSceneBuilder::HairColour(ParameterList& parameters, const Location& where,
                                          MaterialRef* material) {
    Rgb& colour = material->material.base_color;
    // pbrt-v4's order (HairMaterial::Create): "sigma_a", else "reflectance" (or pbrt-v3's
    // "color"), else the melanin concentrations (eumelanin 1.3 where nothing is given).
    const std::optional<Rgb> given_sigma_a = parameters.Color("sigma_a", SpectrumUse::kUnbounded);
    std::optional<Rgb> reflectance = parameters.Color("reflectance");
    if (const std::optional<Rgb> color = parameters.Color("color"); !reflectance)
        reflectance = color;
    if (reflectance && !given_sigma_a) {
        colour = Min(Max(*reflectance, Rgb(0.0f)), Rgb(1.0f));
        return absl::OkStatus();
    }
    // The absorption, given or of the melanins; the colour pbrt-v4's SigmaAFromReflectance
    // inverts, exp(-sqrt(sigma_a) s(beta_n)).
    Rgb sigma_a(0.0f);
    if (given_sigma_a) {
        sigma_a = *given_sigma_a;
    } else {
        const bool melanin = parameters.Has("eumelanin") || parameters.Has("pheomelanin");
        const double eumelanin = parameters.Float("eumelanin", melanin ? 0.0 : 1.3);
        const double pheomelanin = parameters.Float("pheomelanin", 0.0);
        sigma_a =
            Rgb(Vec3d(0.419, 0.697, 1.37) * eumelanin + Vec3d(0.187, 0.4, 1.05) * pheomelanin);
    }
    const double b = parameters.Float("beta_n", 0.3);
    const double s = 5.969 - 0.215 * b + 2.532 * b * b - 10.73 * b * b * b + 5.574 * b * b * b * b +
                     0.245 * b * b * b * b * b;
    if (!(IsFinite(sigma_a) && MinComponent(sigma_a) >= 0 && std::isfinite(s)))
        return ErrorAt(where, "Material \"hair\": its absorption must be finite and non-negative");
    for (int c = 0; c < 3; ++c)
        colour[c] = static_cast<float>(std::exp(-std::sqrt(double(sigma_a[c])) * s));
    return absl::OkStatus();
}

absl::Status PbrtSceneBuilder::ShadingDetail(ParameterList& parameters, const Location& where,
                                             MaterialRef* material) {
    Material& m = material->material;
    const bool textured = m.ReadsUv();  // its coordinates are set: the detail reads the same
    // pbrt-v4's normalmap: an image file, linear, read at (u, 1 - v) without a mapping.
    if (const std::string file = parameters.String("normalmap", ""); !file.empty()) {
        absl::StatusOr<std::string> path = ResolveReference(file, base_folder_);
        if (!path.ok())
            return ErrorAt(where,
                           absl::StrCat("Material: \"normalmap\": ", path.status().message()));
        TextureRef normal_map;
        normal_map.path = *path;
        normal_map.decode.encoding = ImageEncoding::kLinear;
        normal_map.element = absl::StrCat(where.ToString(), ": Material \"normalmap\"");
        normal_map.mapping.uv.m[4] = -1, normal_map.mapping.uv.m[5] = 1;
        const absl::StatusOr<int32_t> index = ImageIndex(normal_map);
        if (!index.ok()) return index.status();
        m.normal_texture = *index;
        if (!textured) material->mapping = normal_map.mapping;
    }
    // The bump map: a float texture of displacement along the normal, in world units.
    const absl::StatusOr<FloatInput> displacement =
        FloatParameter(parameters, "displacement", 0.0, "Material: \"displacement\"", where,
                       /*exponent=*/1, TextureUse::kDisplacement);
    if (!displacement.ok()) return displacement.status();
    if (displacement->texture != kNoTexture) {
        if (!std::isfinite(displacement->value))
            return ErrorAt(where, "Material: \"displacement\"'s scale must be finite");
        m.bump_texture = displacement->texture;
        m.bump_scale = displacement->value;
        if (!textured && m.normal_texture == kNoTexture) material->mapping = displacement->mapping;
    }
    return absl::OkStatus();
}

}  // namespace pf::pbrt
