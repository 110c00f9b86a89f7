// How an image texture is addressed outside its texels, one definition for the CPU
// (core/scene/texture.h) and the Vulkan kernels (trace.glsl's TextureSample): glTF's sampler
// wrap modes and pbrt-v4's imagemap "wrap", per axis.
#ifndef PF_CORE_SHARED_TEXTURE_WRAP_H
#define PF_CORE_SHARED_TEXTURE_WRAP_H

#include "core/shared/gpu_prelude.h"

PF_GPU_BEGIN

PF_CONST(uint32_t) kWrapRepeat = 0;  // periodic (glTF's REPEAT, pbrt's "repeat")
PF_CONST(uint32_t) kWrapClamp = 1;   // the edge texel beyond (CLAMP_TO_EDGE, "clamp")
PF_CONST(uint32_t) kWrapMirror = 2;  // mirrored every other period (MIRRORED_REPEAT)
PF_CONST(uint32_t) kWrapBlack = 3;   // black beyond (pbrt's "black")

// The texel that coordinate i of an axis `size` texels long reads under `mode`; -1 where it
// reads black.
// i modulo a positive `period`, in [0, period), with % taken of non-negative operands only
// (GLSL leaves % of a negative operand undefined).
PF_GPU_FN int32_t FloorMod(int32_t i, int32_t period) {
    return i >= 0 ? i % period : period - 1 - (-(i + 1)) % period;
}

PF_GPU_FN int32_t WrapTexel(int32_t i, int32_t size, uint32_t mode) {
    if (mode == kWrapClamp) return i < 0 ? 0 : (i >= size ? size - 1 : i);
    if (mode == kWrapBlack) return i < 0 || i >= size ? -1 : i;
    if (mode == kWrapMirror) {
        const int32_t m = FloorMod(i, 2 * size);
        return m < size ? m : 2 * size - 1 - m;
    }
    return FloorMod(i, size);
}

PF_GPU_END

#endif  // PF_CORE_SHARED_TEXTURE_WRAP_H
