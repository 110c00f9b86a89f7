// pbrt-v4's textures onto photonfarm's images: imagemap through OpenImageIO, checkerboard and
// bilerp baked into images, constant, scale and mix (of images: baked), each with its texture
// mapping (pbrt_mapping.h).
#include <algorithm>
#include <cmath>

#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "core/scene_io/image_decode.h"
#include "core/scene_io/pbrt/pbrt_scene_builder.h"
#include "core/util/check.h"

namespace pf::pbrt {

std::string UnsupportedNote(const TextureRef& texture) {
    if (texture.unsupported == texture.type)
        return absl::StrCat(texture.described, " is not evaluated by photonfarm");
    return absl::StrCat(texture.described,
                        " is not evaluated by photonfarm: ", texture.unsupported);
}

std::string FormatRgb(const Rgb& value) {
    if (value.x == value.y && value.y == value.z) return absl::StrCat(value.x);
    return absl::StrCat("(", value.x, " ", value.y, " ", value.z, ")");
}

absl::StatusOr<int32_t> PbrtSceneBuilder::ImageIndex(const TextureRef& texture) {
    if (texture.baked != nullptr) {
        if (options_.references_only) return kNoTexture;
        const auto key = std::make_tuple(absl::StrCat("baked:", texture.element), texture.decode);
        if (const auto it = images_.find(key); it != images_.end()) return it->second;
        const auto index = static_cast<int32_t>(scene_.textures.size());
        auto decoded = std::make_shared<pf::Texture>(*texture.baked);
        ApplyValueOptions(texture.decode, decoded.get());
        scene_.textures.push_back(std::move(decoded));
        images_[key] = index;
        return index;
    }
    if (texture.path.empty()) return kNoTexture;
    absl::StatusOr<std::string_view> bytes = files_.Read(texture.path);
    if (!bytes.ok())
        return absl::Status(bytes.status().code(),
                            absl::StrCat(texture.element, ": ", bytes.status().message()));
    if (options_.references_only) return kNoTexture;
    const auto key = std::make_tuple(texture.path, texture.decode);
    if (const auto it = images_.find(key); it != images_.end()) return it->second;
    absl::StatusOr<pf::Texture> image =
        DecodeImage(*bytes, texture.path, options_.limits, texture.decode);
    if (!image.ok())
        return absl::Status(image.status().code(),
                            absl::StrCat(texture.element, ": ", image.status().message()));
    const auto index = static_cast<int32_t>(scene_.textures.size());
    scene_.textures.push_back(std::make_shared<const pf::Texture>(std::move(*image)));
    images_[key] = index;
    return index;
}

absl::Status PbrtSceneBuilder::BakeProcedural(const std::string& type, bool scalar,
                                              ParameterList& parameters, const Location& where,
                                              TextureRef* texture) {
    const auto value = [&](const std::string& name, float fallback) -> std::optional<Rgb> {
        if (parameters.TextureName(name)) return std::nullopt;  // a texture operand
        return scalar ? Rgb(static_cast<float>(parameters.Float(name, fallback)))
                      : parameters.Color(name).value_or(Rgb(fallback));
    };
    const auto left_out = [&](const std::string& what) {  // noted where the texture is used
        texture->unsupported = what;
        parameters.ConsumeAll();
        return absl::OkStatus();
    };
    // The image covers `period` of pbrt-v4's s and t (a checkerboard's two checks, bilerp's unit
    // square), t up; photonfarm's v is down.
    absl::StatusOr<TextureMapping> mapping = Mapping(parameters, where);
    if (!mapping.ok()) return mapping.status();
    const int size = type == "checkerboard" ? 128 : 64;
    const double period = type == "checkerboard" ? 2 : 1;
    UvTransform image;
    image.m[0] = 1 / period, image.m[4] = -1 / period, image.m[5] = 1 / period;
    texture->mapping = *mapping;
    texture->mapping.uv = mapping->uv.Then(image);
    auto baked = std::make_shared<pf::Texture>();
    baked->width = baked->height = size;
    baked->texels.resize(size_t(size) * size);
    const auto at = [&](int x, int y) {  // (s, t) at the texel's centre
        return std::pair{period * (x + 0.5) / size, 1 - period * (y + 0.5) / size};
    };
    if (type == "checkerboard") {
        // pbrt-v4's: tex1 where floor(s) + floor(t) is even, tex2 where odd.
        parameters.Integer("dimension", 2);  // 2: MakeProgram evaluates others at each point
        const std::optional<Rgb> one = value("tex1", 1), two = value("tex2", 0);
        PF_CHECK(one && two);  // texture operands: MakeProgram's
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const auto [s, t] = at(x, y);
                const bool even = (int(std::floor(s)) + int(std::floor(t))) % 2 == 0;
                baked->texels[size_t(y) * size + x] = even ? *one : *two;
            }
    } else {
        // pbrt-v4's bilerp: v00 (1 - s)(1 - t) + v01 (1 - s) t + v10 s (1 - t) + v11 s t.
        const std::optional<Rgb> v00 = value("v00", 0), v01 = value("v01", 1),
                                 v10 = value("v10", 0), v11 = value("v11", 1);
        if (!v00 || !v01 || !v10 || !v11) return left_out("bilerp of textures");
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const auto [s, t] = at(x, y);
                const float fs = float(s), ft = float(t);
                baked->texels[size_t(y) * size + x] = *v00 * ((1 - fs) * (1 - ft)) +
                                                      *v01 * ((1 - fs) * ft) +
                                                      *v10 * (fs * (1 - ft)) + *v11 * (fs * ft);
            }
    }
    for (const Rgb& texel : baked->texels)
        if (!IsFinite(texel) || MinComponent(texel) < 0)
            return ErrorAt(where, absl::StrCat("Texture (", type,
                                               "): its values must be finite and non-negative"));
    texture->baked = std::move(baked);
    return absl::OkStatus();
}

absl::StatusOr<TextureMapping> PbrtSceneBuilder::Mapping(ParameterList& parameters,
                                                         const Location& where) {
    absl::StatusOr<TextureMapping> mapping = ParseMapping(parameters, state_.ctm);
    if (!mapping.ok()) return ErrorAt(where, absl::StrCat("Texture: ", mapping.status().message()));
    return mapping;
}

absl::StatusOr<PbrtSceneBuilder::Operand> PbrtSceneBuilder::TextureOperand(
    ParameterList& parameters, const std::string& name, bool scalar, Rgb fallback,
    const std::string& what, const Location& where) {
    Operand operand;
    operand.value = fallback;
    const std::optional<std::string> texture_name = parameters.TextureName(name);
    if (!texture_name) {
        operand.value = scalar ? Rgb(static_cast<float>(parameters.Float(name, fallback.x)))
                               : parameters.Color(name).value_or(fallback);
        return operand;
    }
    const std::map<std::string, TextureRef>& named = scalar ? float_textures_ : textures_;
    const auto it = named.find(*texture_name);
    if (it == named.end())
        return ErrorAt(
            where, absl::StrCat(what, ": \"", name, "\" names no ", scalar ? "float" : "spectrum",
                                " texture \"", *texture_name, "\""));
    operand.texture = &it->second;
    // A constant; a texture photonfarm cannot evaluate stays an operand, for its caller to note.
    if (it->second.path.empty() && it->second.baked == nullptr && !it->second.program &&
        it->second.unsupported.empty()) {
        operand.value = it->second.scale;
        operand.texture = nullptr;
    }
    return operand;
}

absl::StatusOr<std::shared_ptr<const pf::Texture>> PbrtSceneBuilder::OperandImage(
    const TextureRef& texture) {
    if (texture.baked != nullptr) {
        auto image = std::make_shared<pf::Texture>(*texture.baked);
        ApplyValueOptions(texture.decode, image.get());
        return image;
    }
    absl::StatusOr<std::string_view> bytes = files_.Read(texture.path);
    if (!bytes.ok())
        return absl::Status(bytes.status().code(),
                            absl::StrCat(texture.element, ": ", bytes.status().message()));
    if (options_.references_only) return nullptr;
    absl::StatusOr<pf::Texture> image =
        DecodeImage(*bytes, texture.path, options_.limits, texture.decode);
    if (!image.ok())
        return absl::Status(image.status().code(),
                            absl::StrCat(texture.element, ": ", image.status().message()));
    return std::make_shared<const pf::Texture>(std::move(*image));
}

absl::Status PbrtSceneBuilder::Combine(const std::string& name, const std::string& type,
                                       bool scalar, ParameterList& parameters,
                                       const Location& where, TextureRef* texture) {
    const std::string what = absl::StrCat("Texture \"", name, "\" (", type, ")");
    // pbrt-v4's operands and defaults: scale's "tex" (1) times the float "scale" (1); mix's
    // (1 - amount) "tex1" (0) + amount "tex2" (1), amount a float (0.5); directionmix's
    // amount "tex1" + (1 - amount) "tex2", the same at amount 1/2.
    const bool scale = type == "scale";
    std::vector<Operand> operands;
    for (const auto& [operand, is_scalar, fallback] :
         scale ? std::vector<std::tuple<std::string, bool, float>>{{"tex", scalar, 1.0f},
                                                                   {"scale", true, 1.0f}}
               : std::vector<std::tuple<std::string, bool, float>>{
                     {"tex1", scalar, 0.0f}, {"tex2", scalar, 1.0f}, {"amount", true, 0.5f}}) {
        absl::StatusOr<Operand> read =
            TextureOperand(parameters, operand, is_scalar, Rgb(fallback), what, where);
        if (!read.ok()) return read.status();
        if (read->texture != nullptr && !read->texture->unsupported.empty()) {
            texture->unsupported = absl::StrCat(type, " of ", read->texture->described);
            parameters.ConsumeAll();
            return absl::OkStatus();
        }
        operands.push_back(*read);
    }
    // directionmix's amount is |n . dir| at each point, n the surface's normal, which no image
    // over (u, v) holds; a procedural operand is evaluated at each point: a program of them.
    if (type == "directionmix" ||
        std::any_of(operands.begin(), operands.end(), [](const Operand& operand) {
            return operand.texture != nullptr && operand.texture->program;
        }))
        return CombineProgram(what, type, parameters, operands, where, texture);
    const auto combine = [&](const std::vector<Rgb>& v) {
        return scale ? v[0] * v[1].x : v[0] * (1.0f - v[2].x) + v[1] * v[2].x;
    };
    std::vector<const TextureRef*> images;
    for (const Operand& operand : operands)
        if (operand.texture != nullptr) images.push_back(operand.texture);
    if (images.empty()) {
        std::vector<Rgb> values;
        for (const Operand& operand : operands) values.push_back(operand.value);
        texture->scale = combine(values);
        return absl::OkStatus();
    }
    // One image times constants: the image, scaled (pbrt-v4's scale of a texture).
    if (scale && images.size() == 1) {
        const size_t constant = operands[0].texture == nullptr ? 0 : 1;
        *texture = *images[0];
        texture->scale = texture->scale * (constant == 1 ? operands[1].value.x : 1.0f);
        if (constant == 0) texture->scale = texture->scale * operands[0].value;
        return absl::OkStatus();
    }
    // Otherwise baked: every image read through one mapping, evaluated at each texel of the
    // finest of them over the unit square of that mapping's image coordinates.
    // Images under different mappings: a program reading each through its own.
    for (const TextureRef* image : images)
        if (!(image->mapping == images[0]->mapping))
            return CombineProgram(what, type, parameters, operands, where, texture);
    std::vector<std::shared_ptr<const pf::Texture>> decoded(operands.size());
    int width = 1, height = 1;
    const pf::Texture* first = nullptr;  // whose wrap modes the baked image keeps
    for (size_t i = 0; i < operands.size(); ++i) {
        if (operands[i].texture == nullptr) continue;
        absl::StatusOr<std::shared_ptr<const pf::Texture>> image =
            OperandImage(*operands[i].texture);
        if (!image.ok()) return image.status();
        if (*image == nullptr) continue;  // packing: every operand's file is what counts
        decoded[i] = *image;
        if (first == nullptr) first = decoded[i].get();
        width = std::max(width, decoded[i]->width), height = std::max(height, decoded[i]->height);
    }
    if (options_.references_only) return absl::OkStatus();
    if (uint64_t(width) * uint64_t(height) > options_.limits.max_image_pixels)
        return ErrorAt(where, absl::StrCat(what, ": its operands' ", width, "x", height,
                                           " texels exceed the image limit"));
    auto baked = std::make_shared<pf::Texture>();
    baked->width = width, baked->height = height;
    baked->wrap_u = first->wrap_u, baked->wrap_v = first->wrap_v;
    baked->texels.resize(size_t(width) * height);
    std::vector<Rgb> values(operands.size());
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float u = (x + 0.5f) / width, v = (y + 0.5f) / height;
            for (size_t i = 0; i < operands.size(); ++i)
                values[i] = decoded[i] ? decoded[i]->Sample(u, v) * operands[i].texture->scale
                                       : operands[i].value;
            baked->texels[size_t(y) * width + x] = Max(combine(values), Rgb(0.0f));
        }
    texture->baked = std::move(baked);
    texture->mapping = images[0]->mapping;
    texture->element = absl::StrCat(where.ToString(), ": Texture \"", name, "\"");
    return absl::OkStatus();
}

absl::Status PbrtSceneBuilder::Texture(const std::string& name, const std::string& kind,
                                       const std::string& type, ParameterList& parameters,
                                       const Location& where) {
    if (kind != "spectrum" && kind != "float")
        return ErrorAt(where, absl::StrCat("Texture \"", name, "\": class '", kind,
                                           "' is not \"spectrum\" or \"float\""));
    // A float texture is kept as a grey one: its value in every channel.
    const bool scalar = kind == "float";
    std::map<std::string, TextureRef>& named = scalar ? float_textures_ : textures_;
    TextureRef texture;
    if (scalar) texture.decode.channels = ImageChannels::kFloat;
    if (type == "imagemap") {
        const std::string filename = parameters.String("filename", "");
        if (filename.empty())
            return ErrorAt(where, absl::StrCat("Texture \"", name, "\" needs \"string filename\""));
        absl::StatusOr<std::string> path = ResolveReference(filename, base_folder_);
        if (!path.ok())
            return ErrorAt(where,
                           absl::StrCat("Texture \"", name, "\": ", path.status().message()));
        ImageDecodeOptions& decode = texture.decode;
        const std::string encoding = parameters.String("encoding", "");
        if (encoding == "sRGB") {
            decode.encoding = ImageEncoding::kSrgb;
        } else if (encoding == "linear") {
            decode.encoding = ImageEncoding::kLinear;
        } else if (absl::StartsWith(encoding, "gamma ") &&
                   absl::SimpleAtod(encoding.substr(6), &decode.gamma) && decode.gamma > 0) {
            decode.encoding = ImageEncoding::kGamma;
        } else if (!encoding.empty()) {
            return ErrorAt(where, absl::StrCat("Texture \"", name, "\": encoding '", encoding,
                                               "' is not sRGB, linear or \"gamma g\""));
        }
        // pbrt's t = 0 at the image's bottom row; photonfarm's textures put v = 0 at the top.
        absl::StatusOr<TextureMapping> mapping = Mapping(parameters, where);
        if (!mapping.ok()) return mapping.status();
        UvTransform flip;
        flip.m[4] = -1, flip.m[5] = 1;
        texture.mapping = *mapping;
        texture.mapping.uv = mapping->uv.Then(flip);
        texture.scale = Rgb(static_cast<float>(parameters.Float("scale", 1.0)));
        decode.invert = parameters.Bool("invert", false);
        const std::string wrap = parameters.String("wrap", "repeat");
        if (wrap == "clamp" || wrap == "black") {
            decode.wrap_u = decode.wrap_v = wrap == "clamp" ? gpu::kWrapClamp : gpu::kWrapBlack;
        } else if (wrap == "octahedralsphere") {
            decode.wrap_u = decode.wrap_v = gpu::kWrapOctahedral;
        } else if (wrap != "repeat") {
            Warn(where, absl::StrCat("Texture \"", name, "\": wrap \"", wrap,
                                     "\" is rendered as \"repeat\""));
        }
        parameters.String("filter", "");
        parameters.Float("maxanisotropy", 8);
        texture.path = *path;
        texture.element = absl::StrCat(where.ToString(), ": Texture \"", name, "\"");
    } else if (type == "checkerboard" &&
               (parameters.Integer("dimension", 2) != 2 || parameters.TextureName("tex1") ||
                parameters.TextureName("tex2"))) {
        // Of dimension 3, or of textures: evaluated at each point.
        if (absl::Status status = MakeProgram(name, type, scalar, parameters, where, &texture);
            !status.ok())
            return status;
    } else if (type == "checkerboard" || type == "bilerp") {
        if (absl::Status status = BakeProcedural(type, scalar, parameters, where, &texture);
            !status.ok())
            return status;
        texture.element = absl::StrCat(where.ToString(), ": Texture \"", name, "\"");
    } else if (type == "fbm" || type == "wrinkled" || type == "windy" || type == "dots" ||
               (type == "marble" && !scalar)) {
        // pbrt-v4's float noise textures (a spectrum one: pbrt-v3's, grey) and its spectrum
        // marble; dots of either.
        if (absl::Status status = MakeProgram(name, type, scalar, parameters, where, &texture);
            !status.ok())
            return status;
    } else if (type == "constant") {
        texture.scale = scalar ? Rgb(static_cast<float>(parameters.Float("value", 1.0)))
                               : parameters.Color("value").value_or(Rgb(1.0f));
    } else if (type == "scale" || type == "mix" || type == "directionmix") {
        if (absl::Status status = Combine(name, type, scalar, parameters, where, &texture);
            !status.ok())
            return status;
    } else {
        parameters.ConsumeAll();
        texture.unsupported = type;
    }
    if (!parameters.status().ok()) return parameters.status();
    // A float texture may scale its values below 0: as a displacement, a bump pointing inwards
    // (pbrt-v4 allows it; kroken's carpet); FloatParameter refuses it anywhere else.
    if (!IsFinite(texture.scale) || (!scalar && MinComponent(texture.scale) < 0))
        return ErrorAt(where, absl::StrCat("Texture \"", name, "\": its values must be finite",
                                           scalar ? "" : " and non-negative"));
    texture.described = absl::StrCat("Texture \"", name, "\" (", type, ") at ", where.ToString());
    texture.type = type;
    named[name] = texture;
    return absl::OkStatus();
}

}  // namespace pf::pbrt
