// Orthonormal frame around a unit normal, for sampling directions in local space: the shared
// definition (core/shared/frame.h), which the Vulkan kernels compile too.
#pragma once

#include "core/shared/frame.h"

namespace pf {

using gpu::Frame;
using gpu::FrameFromNormal;
using gpu::ToLocal;
using gpu::ToWorld;

}  // namespace pf
