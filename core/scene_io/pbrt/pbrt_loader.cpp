// The pbrt-v4 directives: graphics state, transforms, named materials and textures, object
// instances (expanded into the scene's triangles), lights, and what is noted or refused.
#include "core/scene_io/pbrt/pbrt_loader.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "core/scene_io/decompress.h"
#include "core/scene_io/pbrt/pbrt_scene_builder.h"

namespace pf::pbrt {

absl::StatusOr<Scene> PbrtSceneBuilder::Load(const std::string& main_file) {
    scene_.source = display_root_.empty() ? main_file : absl::StrCat(display_root_, "/", main_file);
    base_folder_ = BundleFolder(main_file);
    if (absl::Status status = ParseFile(main_file); !status.ok()) return status;
    const Location end{file_names_.front(), 0, 0};
    if (!attribute_stack_.empty())
        Warn(end, "AttributeBegin without AttributeEnd at the end of the scene");
    if (!current_object_.empty())
        return ErrorAt(end, absl::StrCat("ObjectBegin \"", current_object_, "\" is never ended"));
    if (absl::Status status = FinishCamera(); !status.ok()) return status;
    for (const auto& [what, count] : warning_counts_)
        if (count > 1)
            spdlog::warn("{}: ... and {} more times: {}", scene_.source, count - 1, what);
    FinishInstancing(&scene_);
    if (options_.references_only) return std::move(scene_);
    if (scene_.triangles.empty() && scene_.curves.empty())
        return absl::InvalidArgumentError(absl::StrCat(scene_.source, ": scene has no shapes"));
    return std::move(scene_);
}

absl::Status PbrtSceneBuilder::ParseFile(const std::string& path) {
    const std::string& display = file_names_.emplace_back(
        display_root_.empty() ? path : absl::StrCat(display_root_, "/", path));
    absl::StatusOr<std::string_view> contents = ReadFile(path);
    if (!contents.ok())
        return absl::Status(contents.status().code(),
                            absl::StrCat(display, ": ", contents.status().message()));
    absl::StatusOr<std::vector<Token>> tokens = pbrt::Tokenize(display, *contents);
    if (!tokens.ok()) return tokens.status();
    TokenStream in(std::move(*tokens), [this](const Token& include, const Token& file, int depth) {
        return IncludedTokens(include, file, depth);
    });
    while (in.Peek() != nullptr) {
        const absl::Status status = Directive(in);
        // An include that failed ends the stream: its error, not what the directive made of it.
        if (!in.status().ok()) return in.status();
        if (!status.ok()) return status;
    }
    return in.status();
}

absl::StatusOr<std::vector<Token>> PbrtSceneBuilder::IncludedTokens(const Token& include,
                                                                    const Token& file, int depth) {
    if (depth > options_.limits.max_include_depth)
        return ErrorAt(include.where, absl::StrCat("includes nest deeper than ",
                                                   options_.limits.max_include_depth, " files"));
    absl::StatusOr<std::string> path = ResolveReference(file.text, base_folder_);
    if (!path.ok())
        return ErrorAt(include.where, absl::StrCat(include.text, ": ", path.status().message()));
    const std::string& display = file_names_.emplace_back(
        display_root_.empty() ? *path : absl::StrCat(display_root_, "/", *path));
    absl::StatusOr<std::string_view> contents = ReadFile(*path);
    if (!contents.ok())
        return absl::Status(contents.status().code(), absl::StrCat(include.where.ToString(), ": ",
                                                                   contents.status().message()));
    return pbrt::Tokenize(display, *contents);
}

absl::StatusOr<std::string_view> PbrtSceneBuilder::ReadFile(const std::string& path) {
    absl::StatusOr<std::string_view> bytes = files_.Read(path);
    if (!bytes.ok() || !absl::EndsWithIgnoreCase(path, ".gz")) return bytes;
    // Within what a bundle may hold in all.
    absl::StatusOr<std::string> contents = Gunzip(*bytes, path, kMaxBundleBytes);
    if (!contents.ok()) return contents.status();
    return std::string_view(decompressed_.emplace_back(std::move(*contents)));
}

absl::StatusOr<std::string> PbrtSceneBuilder::ReadString(TokenStream& in, const Token& directive) {
    if (!in.NextIs(TokenKind::kString))
        return ErrorAt(directive.where,
                       absl::StrCat(directive.text, " needs a quoted string after it"));
    return in.Next().text;
}

absl::StatusOr<std::vector<double>> PbrtSceneBuilder::ReadNumbers(TokenStream& in,
                                                                  const Token& directive,
                                                                  size_t count) {
    const bool bracketed = in.NextIs(TokenKind::kOpenBracket);
    if (bracketed) in.Skip();
    std::vector<double> numbers;
    while (numbers.size() < count) {
        if (!in.NextIs(TokenKind::kNumber))
            return ErrorAt(directive.where,
                           absl::StrCat(directive.text, " needs ", count, " numbers"));
        const Token& token = *in.Peek();
        double value;
        if (!absl::SimpleAtod(token.text, &value) || !std::isfinite(value))
            return ErrorAt(token.where, absl::StrCat("'", token.text, "' is not a finite number"));
        numbers.push_back(value);
        in.Skip();
    }
    if (bracketed) {
        if (!in.NextIs(TokenKind::kCloseBracket))
            return ErrorAt(directive.where, absl::StrCat(directive.text, " needs exactly ", count,
                                                         " numbers in [ ]"));
        in.Skip();
    }
    return numbers;
}

absl::StatusOr<std::vector<double>> PbrtSceneBuilder::SpectrumFile(const std::string& name,
                                                                   const Token& declaration) {
    const std::string parameter = Describe(declaration);
    absl::StatusOr<std::string> path = ResolveReference(name, base_folder_);
    if (!path.ok())
        return ErrorAt(declaration.where,
                       absl::StrCat("parameter ", parameter, ": ", path.status().message()));
    absl::StatusOr<std::string_view> contents = ReadFile(*path);
    if (!contents.ok())
        return ErrorAt(declaration.where,
                       absl::StrCat("parameter ", parameter, ": '", name,
                                    "' is neither a spectrum pbrt-v4 names nor a file of the "
                                    "scene (",
                                    contents.status().message(), ")"));
    return ParseSpectrumFile(
        *contents, file_names_.emplace_back(
                       display_root_.empty() ? *path : absl::StrCat(display_root_, "/", *path)));
}

absl::StatusOr<ParameterList> PbrtSceneBuilder::ReadParameters(TokenStream& in) {
    static const std::map<std::string, std::string> kTypes = {
        {"float", "float"},     {"integer", "integer"},     {"bool", "bool"},
        {"string", "string"},   {"texture", "texture"},     {"rgb", "rgb"},
        {"color", "rgb"},       {"blackbody", "blackbody"}, {"spectrum", "spectrum"},
        {"point2", "point2"},   {"vector2", "vector2"},     {"point3", "point3"},
        {"point", "point3"},    {"vector3", "vector3"},     {"vector", "vector3"},
        {"normal3", "normal3"}, {"normal", "normal3"},
    };
    std::vector<Parameter> parameters;
    while (in.NextIs(TokenKind::kString)) {
        const Token declaration = in.Next();
        const std::vector<std::string> words =
            absl::StrSplit(declaration.text, ' ', absl::SkipWhitespace());
        if (words.size() != 2)
            return ErrorAt(declaration.where, absl::StrCat("parameter ", Describe(declaration),
                                                           " is not \"type name\""));
        const auto type = kTypes.find(words[0]);
        if (type == kTypes.end())
            return ErrorAt(declaration.where, absl::StrCat("parameter ", Describe(declaration),
                                                           " has unknown type '", words[0], "'"));
        Parameter parameter{type->second, words[1], declaration.where};
        auto add_value = [&](const Token& value) -> absl::Status {
            if (value.kind == TokenKind::kNumber) {
                double number;
                if (!absl::SimpleAtod(value.text, &number) || !std::isfinite(number))
                    return ErrorAt(value.where,
                                   absl::StrCat("'", value.text, "' is not a finite number"));
                parameter.numbers.push_back(number);
            } else if (parameter.type == "bool" &&
                       (value.text == "true" || value.text == "false")) {
                parameter.bools.push_back(value.text == "true");
            } else if (value.kind == TokenKind::kString) {
                parameter.strings.push_back(value.text);
            } else {
                return ErrorAt(value.where,
                               absl::StrCat("unexpected ", Describe(value),
                                            " in the value of parameter ", Describe(declaration)));
            }
            return absl::OkStatus();
        };
        if (in.Peek() == nullptr)
            return ErrorAt(declaration.where,
                           absl::StrCat("parameter ", Describe(declaration), " has no value"));
        if (in.NextIs(TokenKind::kOpenBracket)) {
            in.Skip();
            for (const Token* value = in.Peek();
                 value != nullptr && value->kind != TokenKind::kCloseBracket; value = in.Peek()) {
                if (absl::Status status = add_value(*value); !status.ok()) return status;
                in.Skip();
            }
            if (in.Peek() == nullptr)
                return ErrorAt(declaration.where, absl::StrCat("parameter ", Describe(declaration),
                                                               ": '[' is never closed"));
            in.Skip();
        } else {
            if (absl::Status status = add_value(in.Next()); !status.ok()) return status;
        }
        if (parameter.type == "integer")
            for (double number : parameter.numbers)
                if (number != std::floor(number) || std::abs(number) > 2147483647.0)
                    return ErrorAt(declaration.where,
                                   absl::StrCat("parameter ", Describe(declaration), ": ", number,
                                                " is not a 32-bit integer"));
        const bool numeric = parameter.type != "string" && parameter.type != "texture" &&
                             parameter.type != "bool" && parameter.type != "spectrum";
        std::string wrong;
        if (numeric && !parameter.strings.empty())
            wrong = absl::StrCat("needs numbers, found \"", parameter.strings[0], "\"");
        if ((parameter.type == "string" || parameter.type == "texture") &&
            !parameter.numbers.empty())
            wrong = absl::StrCat("needs a quoted string, found ", parameter.numbers[0]);
        if (parameter.type == "bool" && (parameter.bools.empty() || !parameter.numbers.empty()))
            wrong = "needs true or false";
        if (!wrong.empty())
            return ErrorAt(declaration.where,
                           absl::StrCat("parameter ", Describe(declaration), " ", wrong));
        if (parameter.type == "spectrum" && parameter.strings.size() == 1 &&
            !NamedSpectrum(parameter.strings[0])) {
            // Not a name pbrt knows: a spectrum file of the bundle.
            absl::StatusOr<std::vector<double>> values =
                SpectrumFile(parameter.strings[0], declaration);
            if (!values.ok()) return values.status();
            parameter.strings.clear();
            parameter.numbers = std::move(*values);
        }
        parameters.push_back(std::move(parameter));
    }
    return ParameterList(std::move(parameters));
}

absl::Status PbrtSceneBuilder::ApplyTransform(const Transform& transform) {
    // The start-time transform is rendered; the end time's only compared with it.
    if (transform_at_start_) state_.ctm = state_.ctm * transform;
    if (transform_at_end_) state_.ctm_end = state_.ctm_end * transform;
    if (!state_.ctm.IsFinite())
        return absl::InvalidArgumentError("transform overflows to NaN or Inf");
    return absl::OkStatus();
}

// Directives with a type (or name) and a parameter list.
absl::Status PbrtSceneBuilder::TypedDirective(const Token& directive, TokenStream& in) {
    const std::string& name = directive.text;
    const Location& where = directive.where;
    auto string_argument = [&]() { return ReadString(in, directive); };
    absl::StatusOr<std::string> type = string_argument();
    if (!type.ok()) return type.status();
    absl::StatusOr<ParameterList> parameters = ReadParameters(in);
    if (!parameters.ok()) return parameters.status();
    absl::StatusOr<UpgradeResult> upgrade = Upgrade(name, &*type, nullptr, &*parameters, where);
    if (!upgrade.ok()) return upgrade.status();
    absl::Status status;
    if (name == "Camera" || name == "Shape" || name == "LightSource") WarnIfMoving(where, name);
    if (name == "Camera") {
        status = Camera(*type, *parameters, where);
    } else if (name == "Film") {
        status = Film(*parameters, where);
    } else if (name == "Sampler") {
        status = Sampler(*type, *parameters, where);
    } else if (name == "PixelFilter") {
        status = PixelFilter(*type, *parameters, where);
    } else if (name == "Accelerator") {
        parameters->ConsumeAll();
    } else if (name == "Integrator") {
        status = Integrator(*type, *parameters, where);
    } else if (name == "Shape") {
        status = Shape(*type, *parameters, where);
    } else if (name == "Material") {
        absl::StatusOr<int> material = MakeMaterial(*type, *parameters, where);
        if (!material.ok()) return material.status();
        state_.material = *material;
    } else if (name == "MakeNamedMaterial") {
        const std::string material_type = parameters->String("type", "");
        if (material_type.empty())
            return ErrorAt(where,
                           absl::StrCat("MakeNamedMaterial \"", *type, "\" needs \"string type\""));
        absl::StatusOr<int> material = MakeMaterial(material_type, *parameters, where);
        if (!material.ok()) return material.status();
        named_materials_[*type] = *material;
    } else if (name == "LightSource") {
        status = LightSource(*type, *parameters, where, upgrade->lat_long_map);
    } else if (name == "AreaLightSource") {
        if (*type != "diffuse")
            return ErrorAt(where,
                           absl::StrCat("AreaLightSource \"", *type,
                                        "\" is unknown (\"diffuse\" is pbrt-v4's only one)"));
        const std::optional<Rgb> color = parameters->Color("L", SpectrumUse::kIlluminant);
        const Rgb radiance =
            color.value_or(Rgb(1.0f)) * static_cast<float>(parameters->Float("scale", 1.0));
        AreaLight light{radiance, parameters->Float("power", 0.0),
                        parameters->Bool("twosided", false)};
        if (!IsFinite(radiance) || MinComponent(radiance) < 0 || light.power < 0)
            return ErrorAt(where,
                           "AreaLightSource: L, scale and power must be finite and non-negative");
        // "filename": an image of the radiance over the shape's (u, v), as pbrt-v4 reads it
        // (v up), in its own encoding (8-bit sRGB, floating point linear).
        if (const std::string filename = parameters->String("filename", ""); !filename.empty()) {
            if (color)
                return ErrorAt(where, "AreaLightSource: give \"L\" or \"filename\", not both");
            absl::StatusOr<std::string> path = ResolveReference(filename, base_folder_);
            if (!path.ok())
                return ErrorAt(where, absl::StrCat("AreaLightSource: ", path.status().message()));
            light.image.path = *path;
            light.image.element = absl::StrCat(where.ToString(), ": AreaLightSource");
            light.image.mapping.uv.m[4] = -1, light.image.mapping.uv.m[5] = 1;
        }
        state_.area_light = light;
    } else if (name == "MakeNamedMedium") {
        status = MakeNamedMedium(*type, *parameters, where);
    } else if (name == "Attribute") {
        parameters->ConsumeAll();
        Warn(where,
             "Attribute: default parameters for a class of objects are not supported; ignored");
    }
    if (!status.ok()) return status;
    if (!parameters->status().ok()) return parameters->status();
    WarnUnused(*parameters, absl::StrCat(name, " \"", *type, "\""));
    return absl::OkStatus();
}

// Transform directives; nullopt for any other.
std::optional<absl::Status> PbrtSceneBuilder::TransformDirective(const Token& directive,
                                                                 TokenStream& in) {
    const std::string& name = directive.text;
    const Location& where = directive.where;
    auto string_argument = [&]() { return ReadString(in, directive); };
    auto numbers = [&](size_t count) { return ReadNumbers(in, directive, count); };
    auto transform_error = [&](absl::Status status) {
        return status.ok() ? status : ErrorAt(where, absl::StrCat(name, ": ", status.message()));
    };
    if (name == "LookAt") {
        absl::StatusOr<std::vector<double>> v = numbers(9);
        if (!v.ok()) return v.status();
        const Vec3d eye((*v)[0], (*v)[1], (*v)[2]), look((*v)[3], (*v)[4], (*v)[5]),
            up((*v)[6], (*v)[7], (*v)[8]);
        const Vec3d dir = Normalize(look - eye);
        const Vec3d right = Normalize(Cross(Normalize(up), dir));
        if (!IsFinite(dir) || !IsFinite(right))
            return ErrorAt(
                where, "LookAt: eye and look coincide, or up is parallel to the view direction");
        const Vec3d new_up = Cross(dir, right);
        Transform world_from_camera;
        for (int row = 0; row < 3; ++row)
            world_from_camera.m[row] = {right[row], new_up[row], dir[row], eye[row]};
        return transform_error(ApplyTransform(*world_from_camera.Inverse()));
    }
    if (name == "Translate" || name == "Scale") {
        absl::StatusOr<std::vector<double>> v = numbers(3);
        if (!v.ok()) return v.status();
        const Vec3d value((*v)[0], (*v)[1], (*v)[2]);
        return transform_error(ApplyTransform(name == "Translate" ? Transform::Translate(value)
                                                                  : Transform::Scale(value)));
    }
    if (name == "Rotate") {
        absl::StatusOr<std::vector<double>> v = numbers(4);
        if (!v.ok()) return v.status();
        const Vec3d axis((*v)[1], (*v)[2], (*v)[3]);
        if (!(LengthSquared(axis) > 0)) return ErrorAt(where, "Rotate: the axis is zero");
        return transform_error(ApplyTransform(Transform::Rotate((*v)[0], axis)));
    }
    if (name == "Transform" || name == "ConcatTransform") {
        absl::StatusOr<std::vector<double>> v = numbers(16);
        if (!v.ok()) return v.status();
        const Transform given =
            Transform::FromColumnMajor(v->data());  // pbrt lists the matrix transposed
        if (name == "Transform") {
            if (transform_at_start_) state_.ctm = given;
            if (transform_at_end_) state_.ctm_end = given;
            return absl::OkStatus();
        }
        return transform_error(ApplyTransform(given));
    }
    if (name == "Identity") {
        if (transform_at_start_) state_.ctm = Transform{};
        if (transform_at_end_) state_.ctm_end = Transform{};
        return absl::OkStatus();
    }
    if (name == "CoordinateSystem" || name == "CoordSysTransform") {
        absl::StatusOr<std::string> system = string_argument();
        if (!system.ok()) return system.status();
        if (name == "CoordinateSystem") {
            coordinate_systems_[*system] = {state_.ctm, state_.ctm_end};
        } else if (const auto it = coordinate_systems_.find(*system);
                   it != coordinate_systems_.end()) {
            if (transform_at_start_) state_.ctm = it->second.first;
            if (transform_at_end_) state_.ctm_end = it->second.second;
        } else {
            Warn(where, absl::StrCat("CoordSysTransform: no coordinate system \"", *system,
                                     "\"; the transform is unchanged"));
        }
        return absl::OkStatus();
    }
    if (name == "ActiveTransform") {
        if (!in.NextIs(TokenKind::kWord))
            return ErrorAt(where, "ActiveTransform needs StartTime, EndTime or All");
        const std::string which = in.Next().text;
        if (which != "StartTime" && which != "EndTime" && which != "All")
            return ErrorAt(where, absl::StrCat("ActiveTransform: '", which,
                                               "' is not StartTime, EndTime or All"));
        transform_at_start_ = which != "EndTime";
        transform_at_end_ = which != "StartTime";
        return absl::OkStatus();
    }
    if (name == "TransformTimes") {
        absl::StatusOr<std::vector<double>> v = numbers(2);
        return v.ok() ? absl::OkStatus() : v.status();
    }
    return std::nullopt;
}

// Directives on the graphics state, the world and objects; nullopt for any other.
std::optional<absl::Status> PbrtSceneBuilder::StateDirective(const Token& directive,
                                                             TokenStream& in) {
    const std::string& name = directive.text;
    const Location& where = directive.where;
    auto string_argument = [&]() { return ReadString(in, directive); };
    if (name == "ReverseOrientation") {
        state_.reverse_orientation = !state_.reverse_orientation;
        return absl::OkStatus();
    }
    if (name == "WorldBegin") {
        if (in_world_) return ErrorAt(where, "WorldBegin appears twice");
        in_world_ = true;
        if (absl::Status status = FinishCamera(); !status.ok()) return status;
        state_.ctm = state_.ctm_end = Transform{};
        coordinate_systems_["world"] = {state_.ctm, state_.ctm_end};
        return absl::OkStatus();
    }
    if (name == "WorldEnd")
        return absl::OkStatus();  // pbrt-v3's; v4 ends the world at the end of the file
    if (name == "AttributeBegin") {
        attribute_stack_.push_back(state_);
        return absl::OkStatus();
    }
    if (name == "AttributeEnd") {
        if (attribute_stack_.empty()) return ErrorAt(where, "AttributeEnd without AttributeBegin");
        state_ = attribute_stack_.back();
        attribute_stack_.pop_back();
        return absl::OkStatus();
    }
    if (name == "TransformBegin") {
        transform_stack_.push_back({state_.ctm, state_.ctm_end, state_.reverse_orientation});
        return absl::OkStatus();
    }
    if (name == "TransformEnd") {
        if (transform_stack_.empty()) return ErrorAt(where, "TransformEnd without TransformBegin");
        state_.ctm = transform_stack_.back().start;
        state_.ctm_end = transform_stack_.back().end;
        state_.reverse_orientation = transform_stack_.back().reverse_orientation;
        transform_stack_.pop_back();
        return absl::OkStatus();
    }
    if (name == "NamedMaterial") {
        absl::StatusOr<std::string> material = string_argument();
        if (!material.ok()) return material.status();
        const auto it = named_materials_.find(*material);
        if (it == named_materials_.end())
            return ErrorAt(where,
                           absl::StrCat("NamedMaterial: no material named \"", *material, "\""));
        state_.material = it->second;
        return absl::OkStatus();
    }
    if (name == "ObjectBegin") {
        absl::StatusOr<std::string> object = string_argument();
        if (!object.ok()) return object.status();
        if (!current_object_.empty())
            return ErrorAt(where, absl::StrCat("ObjectBegin \"", *object,
                                               "\" inside ObjectBegin \"", current_object_, "\""));
        if (objects_.contains(*object))
            return ErrorAt(where,
                           absl::StrCat("ObjectBegin: object \"", *object, "\" is defined twice"));
        attribute_stack_.push_back(state_);
        current_object_ = *object;
        objects_[*object];
        return absl::OkStatus();
    }
    if (name == "ObjectEnd") {
        if (current_object_.empty() || attribute_stack_.empty())
            return ErrorAt(where, "ObjectEnd without ObjectBegin");
        state_ = attribute_stack_.back();
        attribute_stack_.pop_back();
        current_object_.clear();
        return absl::OkStatus();
    }
    if (name == "ObjectInstance") {
        absl::StatusOr<std::string> object = string_argument();
        if (!object.ok()) return object.status();
        if (!current_object_.empty()) return ErrorAt(where, "ObjectInstance inside ObjectBegin");
        const auto it = objects_.find(*object);
        if (it == objects_.end())
            return ErrorAt(where,
                           absl::StrCat("ObjectInstance: no object named \"", *object, "\""));
        WarnIfMoving(where, "ObjectInstance");
        return ObjectInstance(*object, it->second, where);
    }
    if (name == "MediumInterface") {
        // "inside" "outside", or one name for both sides (pbrt-v4's parser reads it so).
        absl::StatusOr<std::string> inside = string_argument();
        if (!inside.ok()) return inside.status();
        std::string outside = *inside;
        if (in.NextIs(TokenKind::kString)) {
            absl::StatusOr<std::string> second = string_argument();
            if (!second.ok()) return second.status();
            outside = *second;
        }
        return SetMediumInterface(*inside, outside, where);
    }
    if (name == "ColorSpace") {
        absl::StatusOr<std::string> space = string_argument();
        if (!space.ok()) return space.status();
        if (*space != "srgb")
            Warn(where,
                 absl::StrCat("ColorSpace \"", *space, "\": colours are read as linear sRGB"));
        return absl::OkStatus();
    }
    if (name == "Option") {
        absl::StatusOr<ParameterList> parameters = ReadParameters(in);
        if (!parameters.ok()) return parameters.status();
        for (const Parameter* p : parameters->Unused())
            Warn(p->where, absl::StrCat("Option \"", p->name, "\" is not supported; ignored"));
        return absl::OkStatus();
    }
    return std::nullopt;
}

absl::Status PbrtSceneBuilder::Directive(TokenStream& in) {
    const Token directive = in.Next();
    const std::string& name = directive.text;
    const Location& where = directive.where;
    if (directive.kind != TokenKind::kWord)
        return ErrorAt(where, absl::StrCat("expected a directive, found ", Describe(directive)));
    auto string_argument = [&]() { return ReadString(in, directive); };
    static const std::set<std::string> kTyped = {"Camera",
                                                 "Film",
                                                 "Sampler",
                                                 "PixelFilter",
                                                 "Integrator",
                                                 "Accelerator",
                                                 "Shape",
                                                 "Material",
                                                 "MakeNamedMaterial",
                                                 "LightSource",
                                                 "AreaLightSource",
                                                 "MakeNamedMedium",
                                                 "Attribute"};
    if (kTyped.contains(name)) return TypedDirective(directive, in);
    if (name == "Texture") {
        absl::StatusOr<std::string> texture_name = string_argument();
        if (!texture_name.ok()) return texture_name.status();
        absl::StatusOr<std::string> kind = string_argument();
        if (!kind.ok()) return kind.status();
        absl::StatusOr<std::string> type = string_argument();
        if (!type.ok()) return type.status();
        absl::StatusOr<ParameterList> parameters = ReadParameters(in);
        if (!parameters.ok()) return parameters.status();
        if (absl::StatusOr<UpgradeResult> upgrade =
                Upgrade(name, &*type, &*kind, &*parameters, where);
            !upgrade.ok())
            return upgrade.status();
        if (absl::Status status = Texture(*texture_name, *kind, *type, *parameters, where);
            !status.ok())
            return status;
        if (!parameters->status().ok()) return parameters->status();
        WarnUnused(*parameters, absl::StrCat("Texture \"", *texture_name, "\""));
        return absl::OkStatus();
    }
    if (std::optional<absl::Status> status = TransformDirective(directive, in)) return *status;
    if (std::optional<absl::Status> status = StateDirective(directive, in)) return *status;
    return ErrorAt(where, absl::StrCat("unknown directive '", name, "'"));
}

}  // namespace pf::pbrt

namespace pf {

absl::StatusOr<Scene> LoadPbrt(SceneFiles& files, const std::string& main_file,
                               const std::string& display_root, const PbrtLoadOptions& options) {
    return pbrt::PbrtSceneBuilder(files, display_root, options).Load(main_file);
}

}  // namespace pf
