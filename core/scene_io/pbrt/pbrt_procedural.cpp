// pbrt-v4's procedural textures that no image over (u, v) holds, as programs evaluated at each
// point (core/shared/procedural_texture.h): fbm, wrinkled, windy and marble (util/noise.h, of
// the point in the texture's space: the world point through the inverse of the transform
// current at the Texture directive, pbrt-v4's PointTransformMapping), dots, checkerboard of
// dimension 3 or of textures, directionmix, and scale and mix of any of them.
#include <algorithm>
#include <bit>
#include <cmath>
#include <optional>

#include "absl/strings/str_cat.h"
#include "core/scene/texture_program.h"
#include "core/scene_io/pbrt/pbrt_scene_builder.h"

namespace pf::pbrt {
namespace {

std::optional<UvTransform> InverseUv(const UvTransform& t) {
    const double* m = t.m;
    const double determinant = m[0] * m[4] - m[1] * m[3];
    if (!(std::abs(determinant) > 1e-300) || !std::isfinite(1 / determinant)) return std::nullopt;
    UvTransform inverse;
    double* r = inverse.m;
    r[0] = m[4] / determinant, r[1] = -m[1] / determinant;
    r[3] = -m[3] / determinant, r[4] = m[0] / determinant;
    r[2] = -(r[0] * m[2] + r[1] * m[5]), r[5] = -(r[3] * m[2] + r[4] * m[5]);
    return inverse;
}

// Whether two mappings take (s, t) from the same place (the mesh's coordinates, or the same
// projection of the point), whatever each then does to them.
bool SameGeometry(TextureMapping a, TextureMapping b) {
    a.uv = b.uv = UvTransform{};
    return a == b;
}

UvTransform UvOfWords(const gpu::vec4& first, const gpu::vec4& second) {
    UvTransform t;
    const double values[6] = {first.x, first.y, first.z, first.w, second.x, second.y};
    std::copy(std::begin(values), std::end(values), t.m);
    return t;
}

// The program of a procedural texture being defined, its UV transforms all from the
// coordinates of one mapping: the first operand's that reads (s, t).
class ProgramBuilder {
public:
    ProgramBuilder() : writer_(&program_.words) {}

    TextureProgramWriter& Writer() { return writer_; }
    // The UV transform from the program's coordinates to those mapping `node` gives to the
    // operand `owner` (a texture's or the program's own description). Another mapping's (s, t)
    // cannot be had from the program's: it is noted, and read from the program's.
    UvTransform Coordinates(const TextureMapping& node, const std::string& owner) {
        program_.reads_uv = true;
        if (!mapping_) {
            mapping_ = node, mapping_owner_ = owner;
            return UvTransform{};
        }
        if (!SameGeometry(*mapping_, node))
            notes_.push_back(absl::StrCat(owner, " maps (s, t) otherwise than ", mapping_owner_,
                                          "; it is read through the latter's mapping"));
        const std::optional<UvTransform> inverse = InverseUv(mapping_->uv);
        if (!inverse) return node.uv;
        return inverse->Then(node.uv);
    }
    // A constant, an image (times its scale) or another program.
    void Add(const Rgb& value, const TextureRef* texture) {
        if (texture == nullptr) return writer_.Constant(value);
        if (texture->program) {
            const ProgramRef& operand = *texture->program;
            const size_t offset = program_.words.size();
            program_.words.insert(program_.words.end(), operand.words.begin(), operand.words.end());
            for (const auto& [word, image] : operand.images)
                program_.images.emplace_back(offset + word, image);
            if (!operand.reads_uv) return;
            const UvTransform before = Coordinates(texture->mapping, texture->described);
            for (const size_t word : ProgramUvWords(program_.words)) {
                if (word < offset) continue;
                gpu::vec4& first = program_.words[word];
                gpu::vec4& second = program_.words[word + 1];
                const UvTransform t = before.Then(UvOfWords(first, second));
                first = {float(t.m[0]), float(t.m[1]), float(t.m[2]), float(t.m[3])};
                second = {float(t.m[4]), float(t.m[5]), 0, 0};
            }
            return;
        }
        const UvTransform uv = Coordinates(texture->mapping, texture->described);
        program_.images.emplace_back(program_.words.size(),
                                     std::make_shared<const TextureRef>(*texture));
        writer_.Image(kNoTexture, uv.m);
        if (texture->scale != Rgb(1.0f)) {
            writer_.Constant(texture->scale);
            writer_.Combine(gpu::kTextureMultiply);
        }
    }
    // The texture: its program and mapping; notes on it in `notes`.
    void Finish(TextureRef* texture, std::vector<std::string>* notes) {
        texture->mapping = mapping_.value_or(TextureMapping{});
        texture->scale = Rgb(1.0f);
        texture->program = std::make_shared<const ProgramRef>(std::move(program_));
        *notes = std::move(notes_);
    }
    const std::vector<gpu::vec4>& Words() const { return program_.words; }
    // Whether every value is finite; an image's header holds kNoTexture's bits (NaN as a float)
    // until the scene's images are numbered, so its texture word is not a value.
    bool Finite() const {
        std::vector<gpu::vec4> words = program_.words;
        for (const size_t image : ProgramImageWords(words)) words[image].y = 0;
        return std::all_of(words.begin(), words.end(), [](const gpu::vec4& w) {
            return std::isfinite(w.x) && std::isfinite(w.y) && std::isfinite(w.z) &&
                   std::isfinite(w.w);
        });
    }

private:
    ProgramRef program_;
    TextureProgramWriter writer_;
    std::optional<TextureMapping> mapping_;
    std::string mapping_owner_;
    std::vector<std::string> notes_;
};

// The most values `program` holds at once.
int StackDepth(const std::vector<gpu::vec4>& program) {
    int depth = 0, deepest = 0;
    size_t pc = 0;
    while (pc < program.size()) {
        const uint32_t op = std::bit_cast<uint32_t>(program[pc].x);
        size_t words = 1;
        switch (op) {
            case gpu::kTextureMix:
                depth -= 2;
                break;
            case gpu::kTextureMultiply:
            case gpu::kTextureDirectionMix:
                depth -= 1;
                break;
            case gpu::kTexturePower:
            case gpu::kTextureClamp:
                break;
            case gpu::kTextureCheckerboard:
            case gpu::kTextureDots:
                depth -= 1, words = 3;
                break;
            case gpu::kTextureCheckerboard3D:
                depth -= 1, words = 4;
                break;
            case gpu::kTextureImage:
                depth += 1, words = 3;
                break;
            case gpu::kTextureFbm:
            case gpu::kTextureWrinkled:
            case gpu::kTextureWindy:
                depth += 1, words = 4;
                break;
            case gpu::kTextureMarble:
                depth += 1, words = 5;
                break;
            case gpu::kTextureBilerp:
                depth += 1, words = 7;
                break;
            default:  // kTextureConstant
                depth += 1;
        }
        deepest = std::max(deepest, depth);
        pc += words;
    }
    return deepest;
}

// Hands `program` to `texture`, with the notes to warn of in `notes`: an error where a value
// (of `values`) is not finite; where it needs more than the evaluator's stack (less room for
// a final op), the texture is marked unsupported instead.
absl::Status FinishProgram(ProgramBuilder& program, const std::string& what,
                           const std::string& type, const std::string& values,
                           const Location& where, TextureRef* texture,
                           std::vector<std::string>* notes) {
    if (!program.Finite())
        return ErrorAt(where, absl::StrCat(what, ": ", values, " must be finite"));
    if (StackDepth(program.Words()) > gpu::kTextureStackSize - 1) {
        texture->unsupported = absl::StrCat(type, " of textures nested too deeply");
        return absl::OkStatus();
    }
    program.Finish(texture, notes);
    return absl::OkStatus();
}

}  // namespace

absl::Status PbrtSceneBuilder::MakeProgram(const std::string& name, const std::string& type,
                                           bool scalar, ParameterList& parameters,
                                           const Location& where, TextureRef* texture) {
    const std::string what = absl::StrCat("Texture \"", name, "\" (", type, ")");
    ProgramBuilder program;
    TextureProgramWriter& writer = program.Writer();
    // Operands as pbrt-v4 reads them; one photonfarm cannot evaluate makes this one so.
    bool left_out = false;
    const auto operand = [&](const std::string& parameter, float fallback) -> absl::Status {
        absl::StatusOr<Operand> read =
            TextureOperand(parameters, parameter, scalar, Rgb(fallback), what, where);
        if (!read.ok()) return read.status();
        if (read->texture != nullptr && !read->texture->unsupported.empty()) {
            texture->unsupported = absl::StrCat(type, " of ", read->texture->described);
            left_out = true;
        }
        program.Add(read->value, read->texture);
        return absl::OkStatus();
    };
    // The point's transform into the texture's space: pbrt-v4's textureFromRender, the render
    // space's offset from the world cancelling.
    const std::optional<Transform> texture_from_world = state_.ctm.Inverse();
    if (!texture_from_world)
        return ErrorAt(where, absl::StrCat(what, ": the transform current here is singular"));
    const auto octaves = [&]() -> uint32_t {
        const int count = parameters.Integer("octaves", 8);
        if (count >= 0 && uint32_t(count) <= gpu::kMaxNoiseOctaves) return uint32_t(count);
        Warn(where, absl::StrCat(what, ": \"octaves\" ", count, " is taken as ",
                                 count < 0 ? 0u : gpu::kMaxNoiseOctaves));
        return count < 0 ? 0u : gpu::kMaxNoiseOctaves;
    };
    // pbrt-v4's defaults: octaves 8, roughness (omega) 0.5; marble's scale 1, variation 0.2.
    if (type == "fbm" || type == "wrinkled") {
        const uint32_t count = octaves();
        writer.Solid(type == "fbm" ? gpu::kTextureFbm : gpu::kTextureWrinkled, *texture_from_world,
                     float(parameters.Float("roughness", 0.5)), count);
    } else if (type == "windy") {
        writer.Solid(gpu::kTextureWindy, *texture_from_world);
    } else if (type == "marble") {
        const uint32_t count = octaves();
        const float omega = float(parameters.Float("roughness", 0.5));
        writer.Marble(*texture_from_world, omega, count, float(parameters.Float("scale", 1)),
                      float(parameters.Float("variation", 0.2)));
    } else if (type == "checkerboard") {
        // tex1 (1) on even checks, tex2 (0) on odd ones.
        const int dimension = parameters.Integer("dimension", 2);
        if (dimension != 2 && dimension != 3)
            return ErrorAt(where, absl::StrCat(what, ": dimension ", dimension,
                                               " is not 2 or 3, as pbrt-v4 has it"));
        if (absl::Status status = operand("tex1", 1); !status.ok()) return status;
        if (absl::Status status = operand("tex2", 0); !status.ok()) return status;
        if (dimension == 3) {
            writer.Solid(gpu::kTextureCheckerboard3D, *texture_from_world);
        } else {
            absl::StatusOr<TextureMapping> mapping = Mapping(parameters, where);
            if (!mapping.ok()) return mapping.status();
            writer.Planar(gpu::kTextureCheckerboard,
                          program.Coordinates(*mapping, absl::StrCat(what, "'s mapping")).m);
        }
    } else if (type == "dots") {
        // pbrt-v4 (textures.cpp, DotsTexture::Create) hands "inside" (1) and "outside" (0) to
        // its constructor as its outside and inside textures, in that order: a dot shows
        // "outside", the space between "inside". Its values, so its order.
        absl::StatusOr<TextureMapping> mapping = Mapping(parameters, where);
        if (!mapping.ok()) return mapping.status();
        if (absl::Status status = operand("outside", 0); !status.ok()) return status;
        if (absl::Status status = operand("inside", 1); !status.ok()) return status;
        writer.Planar(gpu::kTextureDots,
                      program.Coordinates(*mapping, absl::StrCat(what, "'s mapping")).m);
    }
    if (left_out) {
        parameters.ConsumeAll();
        return absl::OkStatus();
    }
    std::vector<std::string> notes;
    const absl::Status status =
        FinishProgram(program, what, type, "its parameters", where, texture, &notes);
    for (const std::string& note : notes) Warn(where, absl::StrCat(what, ": ", note));
    return status;
}

absl::Status PbrtSceneBuilder::CombineProgram(const std::string& what, const std::string& type,
                                              ParameterList& parameters,
                                              const std::vector<Operand>& operands,
                                              const Location& where, TextureRef* texture) {
    ProgramBuilder program;
    // scale: tex x scale; mix: tex1, tex2 and amount; directionmix: tex1 and tex2, by |n . dir|
    // with dir in the world (pbrt-v4's renderFromTexture of "dir", (0, 1, 0) by default).
    const size_t count = type == "mix" ? 3 : 2;
    for (size_t i = 0; i < count; ++i) program.Add(operands[i].value, operands[i].texture);
    if (type == "directionmix") {
        const Vec3d dir =
            state_.ctm.ApplyVector(parameters.Vector3("dir").value_or(Vec3d(0, 1, 0)));
        if (!(LengthSquared(dir) > 0) || !IsFinite(Vec3(dir)))
            return ErrorAt(where, absl::StrCat(what, ": \"dir\" must be a direction"));
        program.Writer().DirectionMix(Vec3(Normalize(dir)));
    } else {
        program.Writer().Combine(type == "mix" ? gpu::kTextureMix : gpu::kTextureMultiply);
    }
    std::vector<std::string> notes;
    const absl::Status status =
        FinishProgram(program, what, type, "its operands' mappings", where, texture, &notes);
    for (const std::string& note : notes) Warn(where, absl::StrCat(what, ": ", note));
    return status;
}

absl::StatusOr<int32_t> PbrtSceneBuilder::TextureIndex(const TextureRef& texture, double exponent,
                                                       float bound, bool signed_values) {
    if (!texture.program) {
        TextureRef image = texture;
        image.decode.exponent = exponent;
        return ImageIndex(image);
    }
    const auto key = std::make_tuple(texture.program.get(), exponent, bound, signed_values);
    if (const auto it = programs_.find(key); it != programs_.end()) return it->second;
    auto made = std::make_shared<pf::Texture>();
    made->program = texture.program->words;
    for (const auto& [word, image] : texture.program->images) {
        absl::StatusOr<int32_t> index = ImageIndex(*image);
        if (!index.ok()) return index.status();
        made->program[word].y = std::bit_cast<float>(*index);
    }
    if (options_.references_only) return kNoTexture;  // packing: the images' files are read
    TextureProgramWriter writer(&made->program);
    if (exponent != 1) writer.Power(float(exponent));
    if (!signed_values) writer.Clamp(bound);
    // Checked as a prepared scene's are (finite values, operands, images), though it was
    // made so.
    if (absl::Status check = CheckTextureProgram(made->program, scene_.textures); !check.ok())
        return absl::InvalidArgumentError(absl::StrCat(texture.described, ": ", check.message()));
    const auto index = static_cast<int32_t>(scene_.textures.size());
    scene_.textures.push_back(std::move(made));
    programs_[key] = index;
    return index;
}

}  // namespace pf::pbrt
