// How an image texture is addressed outside its texels, one definition for the CPU
// (core/scene/texture.h) and the Vulkan kernels (trace.glsl's TextureSample): glTF's sampler
// wrap modes and pbrt-v4's imagemap "wrap", per axis, or both at once for an equal-area
// octahedral image of the sphere (pbrt-v4's "octahedralsphere").
#ifndef PF_CORE_SHARED_TEXTURE_WRAP_H
#define PF_CORE_SHARED_TEXTURE_WRAP_H

#include "core/shared/gpu_prelude.h"

PF_GPU_BEGIN

PF_CONST(uint32_t) kWrapRepeat = 0;  // periodic (glTF's REPEAT, pbrt's "repeat")
PF_CONST(uint32_t) kWrapClamp = 1;   // the edge texel beyond (CLAMP_TO_EDGE, "clamp")
PF_CONST(uint32_t) kWrapMirror = 2;  // mirrored every other period (MIRRORED_REPEAT)
PF_CONST(uint32_t) kWrapBlack = 3;   // black beyond (pbrt's "black")
// Across an edge of an octahedral map of the sphere, where the sphere continues: mirrored
// along that edge (pbrt's "octahedralsphere"; both axes take it).
PF_CONST(uint32_t) kWrapOctahedral = 4;

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

// Texel (x, y) of an image width x height wrapped by `wrap_u` and `wrap_v`: each axis on its
// own, or, under kWrapOctahedral, as pbrt-v4's RemapPixelCoords crosses the octahedron's edges
// (then clamped to the image: a lookup reaches one texel beyond it at most). A coordinate of -1
// reads black.
PF_GPU_FN void WrapTexels(PF_INOUT(int32_t) x, PF_INOUT(int32_t) y, int32_t width, int32_t height,
                          uint32_t wrap_u, uint32_t wrap_v) {
    if (wrap_u != kWrapOctahedral) {
        x = WrapTexel(x, width, wrap_u);
        y = WrapTexel(y, height, wrap_v);
        return;
    }
    if (x < 0) {
        x = -x - 1;
        y = height - 1 - y;
    } else if (x >= width) {
        x = 2 * width - 1 - x;
        y = height - 1 - y;
    }
    if (y < 0) {
        x = width - 1 - x;
        y = -y - 1;
    } else if (y >= height) {
        x = width - 1 - x;
        y = 2 * height - 1 - y;
    }
    x = x < 0 ? 0 : (x >= width ? width - 1 : x);
    y = y < 0 ? 0 : (y >= height ? height - 1 : y);
}

PF_GPU_END

#endif  // PF_CORE_SHARED_TEXTURE_WRAP_H
