// Writing and checking procedural textures' programs.
#include "core/scene/texture_program.h"

#include <bit>
#include <cmath>

#include "absl/strings/str_cat.h"

namespace pf {
namespace {

float Bits(uint32_t value) { return std::bit_cast<float>(value); }
uint32_t Op(const gpu::vec4& header) { return std::bit_cast<uint32_t>(header.x); }

// The words an instruction of `op` takes, header included; 0 for an unknown op.
size_t Words(uint32_t op) {
    switch (op) {
        case gpu::kTextureConstant:
        case gpu::kTextureMultiply:
        case gpu::kTextureMix:
        case gpu::kTextureDirectionMix:
        case gpu::kTexturePower:
        case gpu::kTextureClamp:
            return 1;
        case gpu::kTextureImage:
        case gpu::kTextureCheckerboard:
        case gpu::kTextureDots:
            return 3;
        case gpu::kTextureCheckerboard3D:
        case gpu::kTextureFbm:
        case gpu::kTextureWrinkled:
        case gpu::kTextureWindy:
            return 4;
        case gpu::kTextureMarble:
            return 5;
        case gpu::kTextureBilerp:
            return 7;
        default:
            return 0;
    }
}

// Values an instruction of `op` takes from the stack, and puts back.
std::pair<int, int> StackUse(uint32_t op) {
    switch (op) {
        case gpu::kTextureMultiply:
        case gpu::kTextureDirectionMix:
        case gpu::kTextureCheckerboard:
        case gpu::kTextureCheckerboard3D:
        case gpu::kTextureDots:
            return {2, 1};
        case gpu::kTextureMix:
            return {3, 1};
        case gpu::kTexturePower:
        case gpu::kTextureClamp:
            return {1, 1};
        default:
            return {0, 1};
    }
}

bool HasUv(uint32_t op) {
    return op == gpu::kTextureImage || op == gpu::kTextureCheckerboard || op == gpu::kTextureDots ||
           op == gpu::kTextureBilerp;
}

bool Finite(const gpu::vec4& word) {
    return std::isfinite(word.x) && std::isfinite(word.y) && std::isfinite(word.z) &&
           std::isfinite(word.w);
}

}  // namespace

void TextureProgramWriter::Header(uint32_t op, float y, float z, float w) {
    program_.push_back({Bits(op), y, z, w});
}

void TextureProgramWriter::Uv(const double (&uv)[6]) {
    program_.push_back({float(uv[0]), float(uv[1]), float(uv[2]), float(uv[3])});
    program_.push_back({float(uv[4]), float(uv[5]), 0, 0});
}

void TextureProgramWriter::Rows(const Transform& transform) {
    for (int row = 0; row < 3; ++row)
        program_.push_back({float(transform.m[row][0]), float(transform.m[row][1]),
                            float(transform.m[row][2]), float(transform.m[row][3])});
}

void TextureProgramWriter::Constant(const Rgb& value) {
    Header(gpu::kTextureConstant, value.x, value.y, value.z);
}

void TextureProgramWriter::Image(int32_t texture, const double (&uv)[6]) {
    Header(gpu::kTextureImage, std::bit_cast<float>(texture));
    Uv(uv);
}

void TextureProgramWriter::Combine(uint32_t op) { Header(op); }

void TextureProgramWriter::DirectionMix(const Vec3& direction) {
    Header(gpu::kTextureDirectionMix, direction.x, direction.y, direction.z);
}

void TextureProgramWriter::Planar(uint32_t op, const double (&st)[6]) {
    Header(op);
    Uv(st);
}

void TextureProgramWriter::Bilerp(const double (&st)[6], const Rgb& v00, const Rgb& v01,
                                  const Rgb& v10, const Rgb& v11) {
    Header(gpu::kTextureBilerp);
    Uv(st);
    for (const Rgb& v : {v00, v01, v10, v11}) program_.push_back({v.x, v.y, v.z, 0});
}

void TextureProgramWriter::Solid(uint32_t op, const Transform& texture_from_world, float omega,
                                 uint32_t octaves) {
    Header(op, omega, Bits(octaves));
    Rows(texture_from_world);
}

void TextureProgramWriter::Marble(const Transform& texture_from_world, float omega,
                                  uint32_t octaves, float scale, float variation) {
    Header(gpu::kTextureMarble, omega, Bits(octaves), scale);
    program_.push_back({variation, 0, 0, 0});
    Rows(texture_from_world);
}

void TextureProgramWriter::Power(float exponent) { Header(gpu::kTexturePower, exponent); }

void TextureProgramWriter::Clamp(float bound) { Header(gpu::kTextureClamp, bound); }

std::vector<size_t> ProgramUvWords(const std::vector<gpu::vec4>& program) {
    std::vector<size_t> words;
    for (size_t pc = 0; pc < program.size(); pc += Words(Op(program[pc])))
        if (HasUv(Op(program[pc]))) words.push_back(pc + 1);
    return words;
}

std::vector<size_t> ProgramImageWords(const std::vector<gpu::vec4>& program) {
    std::vector<size_t> words;
    for (size_t pc = 0; pc < program.size(); pc += Words(Op(program[pc])))
        if (Op(program[pc]) == gpu::kTextureImage) words.push_back(pc);
    return words;
}

absl::Status CheckTextureProgram(const std::vector<gpu::vec4>& program,
                                 const std::vector<std::shared_ptr<const Texture>>& textures) {
    const auto invalid = [](size_t pc, const std::string& what) {
        return absl::InvalidArgumentError(absl::StrCat("texture program word ", pc, ": ", what));
    };
    int depth = 0;
    size_t pc = 0;
    while (pc < program.size()) {
        const uint32_t op = Op(program[pc]);
        const size_t words = Words(op);
        if (words == 0) return invalid(pc, absl::StrCat("unknown instruction ", op));
        if (program.size() - pc < words) return invalid(pc, "truncated");
        // Every word's bits are finite floats: values, and small integers' bits.
        for (size_t i = pc; i < pc + words; ++i)
            if (!Finite(program[i])) return invalid(i, "a value that is not finite");
        const gpu::vec4& header = program[pc];
        if (op == gpu::kTextureImage) {
            const int32_t texture = std::bit_cast<int32_t>(header.y);
            if (texture < 0 || size_t(texture) >= textures.size() || !textures[texture] ||
                textures[texture]->IsProcedural() || textures[texture]->texels.empty())
                return invalid(pc, absl::StrCat("image ", texture, " is not an image texture"));
        }
        if ((op == gpu::kTextureFbm || op == gpu::kTextureWrinkled || op == gpu::kTextureMarble) &&
            std::bit_cast<uint32_t>(header.z) > gpu::kMaxNoiseOctaves)
            return invalid(pc, absl::StrCat("more than ", gpu::kMaxNoiseOctaves, " octaves"));
        if (op == gpu::kTextureClamp && !(header.y >= 0)) return invalid(pc, "a negative bound");
        const auto [taken, given] = StackUse(op);
        if (depth < taken) return invalid(pc, "its operands are missing");
        depth += given - taken;
        if (depth > gpu::kTextureStackSize)
            return invalid(pc, absl::StrCat("more than ", gpu::kTextureStackSize, " values"));
        pc += words;
    }
    if (depth != 1)
        return absl::InvalidArgumentError(
            absl::StrCat("texture program leaves ", depth, " values, not one"));
    return absl::OkStatus();
}

}  // namespace pf
