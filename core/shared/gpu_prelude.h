// The common ground of the headers in core/shared/, which both C++ and GLSL compile: in C++
// the GLSL vector types they use (std430-aligned) and the spelling of functions and
// constants; in GLSL the same macros with GLSL's meaning. Shared structs use only vec2, vec4,
// uvec4 and 32/64-bit scalars, whose std430 layout C++ reproduces exactly; each struct's
// size is asserted in C++ (PF_GPU_LAYOUT), so the two cannot drift apart.
#ifndef PF_CORE_SHARED_GPU_PRELUDE_H
#define PF_CORE_SHARED_GPU_PRELUDE_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>

namespace pf::gpu {

struct alignas(8) vec2 {
    float x, y;
};
struct alignas(16) vec4 {
    float x, y, z, w;
};
struct alignas(16) uvec4 {
    uint32_t x, y, z, w;
};

}  // namespace pf::gpu

#define PF_GPU_BEGIN namespace pf::gpu {
#define PF_GPU_END }
// A function both languages compile.
#define PF_GPU_FN constexpr inline
#define PF_INOUT(Type) Type&
#define PF_CONST(Type) inline constexpr Type
// The struct's std430 size; alignment follows from its largest member in both languages.
#define PF_GPU_LAYOUT(Type, bytes) \
    static_assert(sizeof(Type) == (bytes), #Type " does not have its std430 size")

#else  // GLSL

#define PF_GPU_BEGIN
#define PF_GPU_END
#define PF_GPU_FN
#define PF_INOUT(Type) inout Type
#define PF_CONST(Type) const Type
#define PF_GPU_LAYOUT(Type, bytes)

#endif
#endif  // PF_CORE_SHARED_GPU_PRELUDE_H
