// pbrt-v3 directives rewritten as pbrt-v4's.
#include "core/scene_io/pbrt/pbrt_upgrade.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "absl/strings/str_cat.h"

namespace pf::pbrt {
namespace {

absl::Status Refused(const std::string& what) { return absl::InvalidArgumentError(what); }

void Changed(UpgradeResult* result, const std::string& change) {
    if (result->change.empty()) result->change = change;
}

// An rgb (or pbrt-v3 "color") parameter whose three values are equal: that value.
std::optional<double> Grey(const Parameter& parameter) {
    if (parameter.type != "rgb" || parameter.numbers.size() != 3 ||
        parameter.numbers[0] != parameter.numbers[1] ||
        parameter.numbers[1] != parameter.numbers[2])
        return std::nullopt;
    return parameter.numbers[0];
}

// Removes spectrum or texture parameter `name`, warning unless it was the constant `value`
// (--upgrade's removeParamSilentIfConstant); whether it was.
bool RemoveUnlessConstant(ParameterList* parameters, const std::string& name, double value,
                          const std::string& material, UpgradeResult* result) {
    const Parameter* parameter = parameters->Find(name);
    if (parameter == nullptr) return false;
    const bool matches = Grey(*parameter) == value ||
                         (parameter->type == "float" && parameter->numbers.size() == 1 &&
                          parameter->numbers[0] == value);
    if (!matches)
        result->warnings.push_back(absl::StrCat("\"", parameter->type, " ", name,
                                                "\" is dropped: pbrt-v4's \"", material,
                                                "\" has no such parameter"));
    parameters->Remove(name);
    return matches;
}

// pbrt-v3's glass and uber "index" is pbrt-v4's "eta".
void IndexToEta(ParameterList* parameters) {
    if (parameters->Find("index") != nullptr && parameters->Find("eta") == nullptr)
        parameters->Rename("index", "eta");
}

absl::Status UpgradeMaterial(std::string* type, ParameterList* parameters, UpgradeResult* result) {
    const std::string v3 = *type;
    parameters->Rename("bumpmap", "displacement");
    if (v3 == "glass" || v3 == "uber") IndexToEta(parameters);
    if (v3 == "uber") {
        *type = "coateddiffuse";
        if (RemoveUnlessConstant(parameters, "Ks", 0, *type, result)) {
            *type = "diffuse";
            parameters->Remove("eta");
            parameters->Remove("roughness");
        }
        RemoveUnlessConstant(parameters, "Kr", 0, *type, result);
        RemoveUnlessConstant(parameters, "Kt", 0, *type, result);
        parameters->Rename("Kd", "reflectance");
        if (const Parameter* opacity = parameters->Find("opacity")) {
            if (Grey(*opacity) != 1.0)
                return Refused(
                    "a non-opaque \"opacity\" of pbrt-v3's \"uber\" has no pbrt-v4 "
                    "equivalent (as pbrt --upgrade says); edit the material");
            parameters->Remove("opacity");
        }
    } else if (v3 == "substrate") {
        *type = "coateddiffuse";
        RemoveUnlessConstant(parameters, "Ks", 1, *type, result);
        parameters->Rename("Kd", "reflectance");
    } else if (v3 == "glass") {
        *type = "dielectric";
        RemoveUnlessConstant(parameters, "Kr", 1, *type, result);
        RemoveUnlessConstant(parameters, "Kt", 1, *type, result);
    } else if (v3 == "plastic") {
        *type = "coateddiffuse";
        if (RemoveUnlessConstant(parameters, "Ks", 0, *type, result)) {
            *type = "diffuse";
            parameters->Remove("roughness");
            parameters->Remove("eta");
        }
        parameters->Rename("Kd", "reflectance");
    } else if (v3 == "kdsubsurface") {
        *type = "subsurface";
        parameters->Rename("Kd", "reflectance");
    } else if (v3 == "matte") {
        *type = "diffuse";
        parameters->Rename("Kd", "reflectance");
        if (const Parameter* sigma = parameters->Find("sigma");
            sigma != nullptr && !(sigma->numbers.size() == 1 && sigma->numbers[0] == 0))
            result->warnings.push_back(
                "\"sigma\" (Oren-Nayar roughness) is dropped: pbrt-v4's \"diffuse\" is "
                "Lambertian");
        parameters->Remove("sigma");
    } else if (v3 == "metal") {
        *type = "conductor";
        RemoveUnlessConstant(parameters, "Kr", 1, *type, result);
    } else if (v3 == "translucent") {
        *type = "diffusetransmission";
        parameters->Rename("Kd", "transmittance");
        RemoveUnlessConstant(parameters, "reflect", 0, *type, result);
        RemoveUnlessConstant(parameters, "transmit", 1, *type, result);
        RemoveUnlessConstant(parameters, "Ks", 0, *type, result);
        parameters->Remove("roughness");
    } else if (v3 == "mirror") {
        // pbrt --upgrade makes a mirror smooth silver, whatever its Kr.
        *type = "conductor";
        RemoveUnlessConstant(parameters, "Kr", 0, *type, result);
        parameters->Add({"float", "roughness", {}, {0.0}});
        parameters->Add({"spectrum", "eta", {}, {}, {"metal-Ag-eta"}});
        parameters->Add({"spectrum", "k", {}, {}, {"metal-Ag-k"}});
    } else if (v3 == "disney") {
        *type = "diffuse";
        parameters->Rename("color", "reflectance");
    } else if (v3 == "mix" && parameters->Find("namedmaterial1") != nullptr) {
        Parameter* amount = parameters->Find("amount");
        if (amount != nullptr && amount->type == "rgb" && amount->numbers.size() == 3) {
            const double average =
                (amount->numbers[0] + amount->numbers[1] + amount->numbers[2]) / 3;
            if (!Grey(*amount))
                result->warnings.push_back(
                    absl::StrCat("the rgb \"amount\" is taken as its average, ", average));
            amount->type = "float";
            amount->numbers = {average};
        }
        const Parameter* first = parameters->Find("namedmaterial1");
        const Parameter* second = parameters->Find("namedmaterial2");
        if (first == nullptr || second == nullptr || first->strings.size() != 1 ||
            second->strings.size() != 1)
            return Refused("pbrt-v3's \"mix\" needs \"namedmaterial1\" and \"namedmaterial2\"");
        // pbrt-v4 lists them the other way round.
        Parameter materials{
            "string", "materials", first->where, {}, {second->strings[0], first->strings[0]}};
        parameters->Remove("namedmaterial1");
        parameters->Remove("namedmaterial2");
        parameters->Add(std::move(materials));
    } else {
        return absl::OkStatus();
    }
    Changed(result, absl::StrCat("Material \"", v3, "\" is pbrt-v4's \"", *type, "\""));
    return absl::OkStatus();
}

absl::Status UpgradeTexture(std::string* texture_class, const std::string& type,
                            ParameterList* parameters, UpgradeResult* result) {
    if (*texture_class == "color") {
        *texture_class = "spectrum";
        Changed(result, "a \"color\" Texture is pbrt-v4's \"spectrum\"");
    }
    if (type == "imagemap") {
        if (Parameter* gamma = parameters->Find("gamma")) {
            std::string encoding;
            if (gamma->type == "bool" && gamma->bools.size() == 1)
                encoding = gamma->bools[0] ? "sRGB" : "linear";
            else if (gamma->type == "float" && gamma->numbers.size() == 1)
                encoding = absl::StrCat("gamma ", gamma->numbers[0]);
            if (!encoding.empty()) {
                parameters->Remove("gamma");
                parameters->Add({"string", "encoding", {}, {}, {encoding}});
                Changed(result, "the imagemap's \"gamma\" is pbrt-v4's \"encoding\"");
            }
        }
        if (const Parameter* trilinear = parameters->Find("trilinear");
            trilinear != nullptr && trilinear->type == "bool" && trilinear->bools.size() == 1) {
            const std::string filter = trilinear->bools[0] ? "trilinear" : "bilinear";
            parameters->Remove("trilinear");
            parameters->Add({"string", "filter", {}, {}, {filter}});
            Changed(result, "the imagemap's \"trilinear\" is pbrt-v4's \"filter\"");
        }
    }
    if (type == "scale" && (parameters->Find("tex1") != nullptr || parameters->Find("tex2"))) {
        // pbrt-v3's product tex1 x tex2: a texture and a grey constant in pbrt-v4's form.
        Parameter* constant = nullptr;
        for (const char* name : {"tex1", "tex2"})
            if (Parameter* p = parameters->Find(name);
                p != nullptr && p->type != "texture" && constant == nullptr)
                constant = p;
        if (constant != nullptr) {
            const std::optional<double> grey =
                constant->type == "float" && constant->numbers.size() == 1
                    ? std::optional<double>(constant->numbers[0])
                    : Grey(*constant);
            if (!grey)
                return Refused(
                    "a \"scale\" texture of two colours has no pbrt-v4 form (as "
                    "pbrt --upgrade says); edit the texture");
            constant->type = "float";
            constant->numbers = {*grey};
            const std::string other = constant->name == "tex1" ? "tex2" : "tex1";
            constant->name = "scale";
            parameters->Rename(other, "tex");
        } else {
            parameters->Rename("tex1", "tex");
            parameters->Rename("tex2", "scale");
        }
        Changed(result,
                "a \"scale\" texture's \"tex1\" and \"tex2\" are pbrt-v4's \"tex\" and \"scale\"");
    }
    return absl::OkStatus();
}

// pbrt-v3's rgb "scale" (and other spectra named `names` that --upgrade folds in, and the
// second number of a pbrt-v3 black body) into pbrt-v4's float "scale".
absl::Status FoldIntoScale(ParameterList* parameters, const std::vector<const char*>& names,
                           const char* light, UpgradeResult* result) {
    double scale = 1;
    bool changed = false;
    if (Parameter* given = parameters->Find("scale"); given != nullptr && given->type == "rgb") {
        const std::optional<double> grey = Grey(*given);
        if (!grey)
            return Refused(absl::StrCat("in pbrt-v4, \"scale\" of a ", light,
                                        " is one float, and this rgb one is not grey (as pbrt "
                                        "--upgrade says); edit the light"));
        scale *= *grey;
        parameters->Remove("scale");
        changed = true;
    }
    for (const char* name : names)
        if (Parameter* p = parameters->Find(name); p != nullptr && p->type == "rgb") {
            const std::optional<double> grey = Grey(*p);
            if (!grey)
                return Refused(
                    absl::StrCat("a coloured \"", name,
                                 "\" with \"mapname\" has no "
                                 "pbrt-v4 form (as pbrt --upgrade says); edit the light"));
            scale *= *grey;
            parameters->Remove(name);
            changed = true;
        }
    for (const char* name : {"L", "I"})
        if (Parameter* p = parameters->Find(name);
            p != nullptr && p->type == "blackbody" && p->numbers.size() == 2) {
            scale *= p->numbers[1];
            p->numbers.pop_back();
            changed = true;
        }
    if (!changed) return absl::OkStatus();
    if (Parameter* p = parameters->Find("scale");
        p != nullptr && p->type == "float" && p->numbers.size() == 1)
        p->numbers[0] *= scale;
    else
        parameters->Add({"float", "scale", {}, {scale}});
    Changed(result, absl::StrCat("the ", light,
                                 "'s rgb \"scale\" or two-number black body is "
                                 "pbrt-v4's float \"scale\""));
    return absl::OkStatus();
}

absl::Status UpgradeLight(const std::string& type, ParameterList* parameters,
                          UpgradeResult* result) {
    parameters->Remove("samples");
    const bool mapname = parameters->Find("mapname") != nullptr;
    std::vector<const char*> folded;
    if (mapname && type == "infinite") folded = {"L"};
    if (mapname && type == "projection") folded = {"I"};
    if (absl::Status status = FoldIntoScale(parameters, folded, "light", result); !status.ok())
        return status;
    if (mapname) {
        parameters->Rename("mapname", "filename");
        result->lat_long_map = type == "infinite";
        Changed(result, "\"mapname\" is pbrt-v4's \"filename\"");
    }
    return absl::OkStatus();
}

absl::Status UpgradeAreaLight(std::string* type, ParameterList* parameters, UpgradeResult* result) {
    if (absl::Status status = FoldIntoScale(parameters, {}, "area light", result); !status.ok())
        return status;
    if (*type == "area") {
        *type = "diffuse";
        parameters->Remove("nsamples");
        Changed(result, "AreaLightSource \"area\" is pbrt-v4's \"diffuse\"");
    }
    return absl::OkStatus();
}

void UpgradeShape(const std::string& type, ParameterList* parameters, UpgradeResult* result) {
    if (type == "loopsubdiv" && parameters->Find("nlevels") != nullptr) {
        parameters->Rename("nlevels", "levels");
        Changed(result, "loopsubdiv's \"nlevels\" is pbrt-v4's \"levels\"");
    }
    if (type != "trianglemesh" && type != "plymesh") return;
    parameters->Remove("discarddegenerateUVs");
    if (type != "trianglemesh") return;
    // pbrt-v3's "float uv" (or "st", or "point2 st"): pbrt-v4's "point2 uv".
    for (const char* name : {"uv", "st"})
        if (Parameter* p = parameters->Find(name);
            p != nullptr && (p->type == "float" || (p->type == "point2" && p->name == "st"))) {
            p->type = "point2";
            p->name = "uv";
            Changed(result,
                    absl::StrCat("\"", name, "\" texture coordinates are pbrt-v4's \"point2 uv\""));
            break;
        }
}

}  // namespace

absl::Status UpgradeDirective(const std::string& directive, std::string* type,
                              std::string* texture_class, ParameterList* parameters,
                              UpgradeResult* result) {
    if (directive == "Material") return UpgradeMaterial(type, parameters, result);
    if (directive == "MakeNamedMaterial") {
        Parameter* material = parameters->Find("type");
        if (material == nullptr || material->type != "string" || material->strings.size() != 1)
            return absl::OkStatus();  // the builder says what is wrong
        return UpgradeMaterial(&material->strings[0], parameters, result);
    }
    if (directive == "Texture") return UpgradeTexture(texture_class, *type, parameters, result);
    if (directive == "LightSource") return UpgradeLight(*type, parameters, result);
    if (directive == "AreaLightSource") return UpgradeAreaLight(type, parameters, result);
    if (directive == "Shape") UpgradeShape(*type, parameters, result);
    if (directive == "Film" && *type == "image") {  // pbrt-v3's only film
        *type = "rgb";
        Changed(result, "Film \"image\" is pbrt-v4's \"rgb\"");
        if (Parameter* scale = parameters->Find("scale");
            scale != nullptr && scale->type == "float" && scale->numbers.size() == 1) {
            // --upgrade's reading: pbrt-v3's pixel scale is an ISO of 100 x scale.
            scale->name = "iso";
            scale->numbers[0] *= 100;
            Changed(result, "the Film's \"scale\" is pbrt-v4's \"iso\" (100 x scale)");
        }
        parameters->Rename("maxsampleluminance", "maxcomponentvalue");
    }
    if (directive == "PixelFilter") {  // pbrt-v3's widths are radii; its Gaussian took alpha
        for (const auto& [v3, v4] : {std::pair{"xwidth", "xradius"}, {"ywidth", "yradius"}})
            if (parameters->Find(v3) != nullptr) {
                parameters->Rename(v3, v4);
                Changed(result, absl::StrCat("PixelFilter \"", v3, "\" is pbrt-v4's \"", v4, "\""));
            }
        if (Parameter* alpha = parameters->Find("alpha"); alpha != nullptr && *type == "gaussian" &&
                                                          alpha->type == "float" &&
                                                          alpha->numbers.size() == 1) {
            if (!(alpha->numbers[0] > 0))
                return Refused("the Gaussian's \"alpha\" must be positive");
            alpha->name = "sigma";
            alpha->numbers[0] = 1 / std::sqrt(2 * alpha->numbers[0]);
            Changed(result,
                    "the Gaussian filter's \"alpha\" is pbrt-v4's \"sigma\" (1 / sqrt(2 alpha))");
        }
        if (parameters->Find("supersample") != nullptr) {  // pbrt-v3's Mitchell option
            parameters->Remove("supersample");
            Changed(result, "PixelFilter \"supersample\" is gone in pbrt-v4");
        }
    }
    if (directive == "Sampler") {
        const std::string v3 = *type;
        if (v3 == "lowdiscrepancy" || v3 == "02sequence") *type = "paddedsobol";
        if (v3 == "maxmindist") *type = "pmj02bn";
        if (v3 == "random") *type = "independent";
        if (*type != v3)
            Changed(result, absl::StrCat("Sampler \"", v3, "\" is pbrt-v4's \"", *type, "\""));
    }
    if (directive == "Integrator") {
        parameters->Remove("rrthreshold");
        if (*type == "directlighting") {
            *type = "path";
            if (Parameter* depth = parameters->Find("maxdepth")) parameters->Remove(depth->name);
            parameters->Add({"integer", "maxdepth", {}, {1.0}});
            Changed(result, "Integrator \"directlighting\" is pbrt-v4's \"path\" with maxdepth 1");
        }
        if (*type == "sppm" && parameters->Find("numiterations") != nullptr) {
            parameters->Remove("numiterations");
            parameters->Remove("imagewritefrequency");
            result->warnings.push_back(
                "\"numiterations\" is dropped: pbrt-v4's sppm takes its iterations from the "
                "Sampler's pixel samples");
            Changed(result, "Integrator \"sppm\"'s \"numiterations\" is pbrt-v4's pixel samples");
        }
    }
    return absl::OkStatus();
}

}  // namespace pf::pbrt
