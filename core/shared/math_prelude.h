// The GLSL vocabulary that the shared maths of core/shared/ (path_sampling.h) is written in,
// given to C++: in namespace pf::shared, vec2 and vec3 are Point2 and Vec3, and sqrt, abs,
// min, max, clamp, dot, normalize and the bit casts are GLSL's functions. In GLSL the
// macros mean GLSL. Functions written against it compile in both languages unchanged.
#ifndef PF_CORE_SHARED_MATH_PRELUDE_H
#define PF_CORE_SHARED_MATH_PRELUDE_H

#ifdef __cplusplus
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "core/math/point2.h"
#include "core/math/vec3.h"

namespace pf::shared {

using vec2 = ::pf::Point2;
using vec3 = ::pf::Vec3;

inline float sqrt(float x) { return std::sqrt(x); }
inline float abs(float x) { return std::abs(x); }
inline float min(float a, float b) { return std::min(a, b); }
inline float max(float a, float b) { return std::max(a, b); }
inline float clamp(float x, float low, float high) { return std::clamp(x, low, high); }
inline float dot(const vec3& a, const vec3& b) { return Dot(a, b); }
inline vec3 normalize(const vec3& v) { return Normalize(v); }
inline uint32_t floatBitsToUint(float x) { return std::bit_cast<uint32_t>(x); }
inline int32_t floatBitsToInt(float x) { return std::bit_cast<int32_t>(x); }
inline float uintBitsToFloat(uint32_t x) { return std::bit_cast<float>(x); }
inline float intBitsToFloat(int32_t x) { return std::bit_cast<float>(x); }

}  // namespace pf::shared

#define PF_SHARED_BEGIN namespace pf::shared {
#define PF_SHARED_END }
#define PF_SHARED_FN inline
#define PF_OUT(Type) Type&

#else  // GLSL

#define PF_SHARED_BEGIN
#define PF_SHARED_END
#define PF_SHARED_FN
#define PF_OUT(Type) out Type

#endif
#endif  // PF_CORE_SHARED_MATH_PRELUDE_H
