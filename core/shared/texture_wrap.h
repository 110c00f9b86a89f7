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
PF_GPU_FN int32_t WrapTexel(int32_t i, int32_t size, uint32_t mode) {
    if (mode == kWrapClamp) return i < 0 ? 0 : (i >= size ? size - 1 : i);
    if (mode == kWrapBlack) return i < 0 || i >= size ? -1 : i;
    if (mode == kWrapMirror) {
        const int32_t period = 2 * size;
        const int32_t m = ((i % period) + period) % period;
        return m < size ? m : period - 1 - m;
    }
    return ((i % size) + size) % size;
}

PF_GPU_END

#endif  // PF_CORE_SHARED_TEXTURE_WRAP_H
