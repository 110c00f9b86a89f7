// Procedural textures' programs (core/shared/procedural_texture.h) on the host: writing their
// instructions, and checking one before anything evaluates it (the loaders' own, and those a
// prepared scene brings from the wire), so that evaluation never reads past its words, its
// stack or the scene's textures.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "absl/status/status.h"
#include "core/math/transform.h"
#include "core/math/vec3.h"
#include "core/scene/texture.h"
#include "core/shared/procedural_texture.h"

namespace pf {

// Appends one instruction's words to `program`.
class TextureProgramWriter {
public:
    explicit TextureProgramWriter(std::vector<gpu::vec4>* program) : program_(*program) {}

    void Constant(const Rgb& value);
    // Image texture `texture` at (m0 u + m1 v + m2, m3 u + m4 v + m5).
    void Image(int32_t texture, const double (&uv)[6]);
    // kTextureMultiply, kTextureMix: operands already on the stack.
    void Combine(uint32_t op);
    void DirectionMix(const Vec3& direction);  // unit
    // kTextureCheckerboard, kTextureDots, at (s, t) = the transform of (u, v).
    void Planar(uint32_t op, const double (&st)[6]);
    void Bilerp(const double (&st)[6], const Rgb& v00, const Rgb& v01, const Rgb& v10,
                const Rgb& v11);
    // kTextureCheckerboard3D, kTextureWindy (omega and octaves unused), kTextureFbm,
    // kTextureWrinkled, at the point `texture_from_world` maps a world point to.
    void Solid(uint32_t op, const Transform& texture_from_world, float omega = 0,
               uint32_t octaves = 0);
    void Marble(const Transform& texture_from_world, float omega, uint32_t octaves, float scale,
                float variation);
    void Power(float exponent);
    void Clamp(float bound);

private:
    void Header(uint32_t op, float y = 0, float z = 0, float w = 0);
    void Uv(const double (&uv)[6]);
    void Rows(const Transform& transform);
    std::vector<gpu::vec4>& program_;
};

// The word at which each UV transform of `program` begins (images', checkerboards', dots',
// bilerps'), and each image instruction's header.
std::vector<size_t> ProgramUvWords(const std::vector<gpu::vec4>& program);
std::vector<size_t> ProgramImageWords(const std::vector<gpu::vec4>& program);

// OK where `program` is whole: known instructions with the words they take, finite values,
// noise octaves within kMaxNoiseOctaves, a stack that never underflows nor holds more than
// kTextureStackSize values and ends with one, images that are image textures of `textures`.
absl::Status CheckTextureProgram(const std::vector<gpu::vec4>& program,
                                 const std::vector<std::shared_ptr<const Texture>>& textures);

}  // namespace pf
