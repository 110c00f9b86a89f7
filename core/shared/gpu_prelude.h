// The one prelude of the headers in core/shared/, which both C++ and GLSL compile: in C++,
// namespace pf::gpu gets the GLSL vocabulary they are written in (vec2 and vec3 are Point2 and
// Vec3; vec4 and uvec4 std430-aligned storage; sqrt, abs, min, max, clamp, dot, cross,
// normalize, exp, log2, pow, floor, sin, cos, acos, atan and the bit casts are GLSL's functions)
// and the macros spell C++; in GLSL the same macros mean GLSL. Shared structs use only vec2, vec4,
// uvec4 and 32/64-bit scalars, whose std430 layout C++ reproduces exactly; each struct's size is
// asserted in C++ (PF_GPU_LAYOUT), so the two cannot drift apart.
#ifndef PF_CORE_SHARED_GPU_PRELUDE_H
#define PF_CORE_SHARED_GPU_PRELUDE_H

#ifdef __cplusplus
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "core/math/point2.h"
#include "core/math/vec3.h"

namespace pf::gpu {

using vec2 = ::pf::Point2;  // 8 bytes, aligned to 8 as std430's vec2
using vec3 = ::pf::Vec3;  // maths only: std430's vec3 is 16-aligned, so no shared struct holds one
struct alignas(16) vec4 {
    float x, y, z, w;
};
struct alignas(16) uvec4 {
    uint32_t x, y, z, w;
};

inline float sqrt(float x) { return std::sqrt(x); }
inline float abs(float x) { return std::abs(x); }
inline float min(float a, float b) { return std::min(a, b); }
inline float max(float a, float b) { return std::max(a, b); }
inline float clamp(float x, float low, float high) { return std::clamp(x, low, high); }
inline float exp(float x) { return std::exp(x); }
inline float log2(float x) { return std::log2(x); }
inline float pow(float x, float y) { return std::pow(x, y); }
inline float floor(float x) { return std::floor(x); }
inline float sin(float x) { return std::sin(x); }
inline float cos(float x) { return std::cos(x); }
inline float acos(float x) { return std::acos(x); }
inline float atan(float x) { return std::atan(x); }
inline float atan(float y, float x) { return std::atan2(y, x); }  // GLSL's two-argument atan
inline float dot(const vec3& a, const vec3& b) { return Dot(a, b); }
inline vec3 cross(const vec3& a, const vec3& b) { return Cross(a, b); }
inline vec3 normalize(const vec3& v) { return Normalize(v); }
inline uint32_t floatBitsToUint(float x) { return std::bit_cast<uint32_t>(x); }
inline int32_t floatBitsToInt(float x) { return std::bit_cast<int32_t>(x); }
inline float uintBitsToFloat(uint32_t x) { return std::bit_cast<float>(x); }
inline float intBitsToFloat(int32_t x) { return std::bit_cast<float>(x); }

}  // namespace pf::gpu

#define PF_GPU_BEGIN namespace pf::gpu {
#define PF_GPU_END }
// A function both languages compile; PF_GPU_CONSTEXPR_FN one that C++ constant expressions
// call too (the RNG's seeding), so nothing in it may call libm.
#define PF_GPU_FN inline
#define PF_GPU_CONSTEXPR_FN constexpr inline
#define PF_INOUT(Type) Type&
#define PF_OUT(Type) Type&
// A struct read by a function: by reference in C++, where a call that is not inlined would copy
// it, by value in GLSL.
#define PF_IN(Type) const Type&
#define PF_CONST(Type) inline constexpr Type
// The struct's std430 size; alignment follows from its largest member in both languages.
#define PF_GPU_LAYOUT(Type, bytes) \
    static_assert(sizeof(Type) == (bytes), #Type " does not have its std430 size")

#else  // GLSL

#define PF_GPU_BEGIN
#define PF_GPU_END
#define PF_GPU_FN
#define PF_GPU_CONSTEXPR_FN
#define PF_INOUT(Type) inout Type
#define PF_OUT(Type) out Type
#define PF_IN(Type) Type
#define PF_CONST(Type) const Type
#define PF_GPU_LAYOUT(Type, bytes)

#endif
#endif  // PF_CORE_SHARED_GPU_PRELUDE_H
