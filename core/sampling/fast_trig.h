// sin and cos of a full turn's fraction, without a libm call (core/shared/path_sampling.h
// defines it once for the CPU and the Vulkan kernels). Absolute error below 4e-7 for u in
// [0, 1).
#pragma once

#include "core/shared/path_sampling.h"

namespace pf {

// Sets *sine = sin(2 pi u) and *cosine = cos(2 pi u), for u in [0, 1).
inline void SinCosTurns(float u, float* sine, float* cosine) {
    gpu::SinCosTurns(u, *sine, *cosine);
}

}  // namespace pf
