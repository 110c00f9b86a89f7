// Warping uniform samples to the distributions photon mapping needs, defined once for the CPU
// and the Vulkan kernels in core/shared/path_sampling.h. Each function states its density
// there, so callers can divide by it; all directions are unit vectors.
#pragma once

#include "core/math/point2.h"
#include "core/math/vec3.h"
#include "core/shared/path_sampling.h"

namespace pf {

using gpu::PowerHeuristic;          // multiple importance sampling's weight
using gpu::SampleCosineHemisphere;  // density cos(theta) / pi about +z
using gpu::SampleUniformCone;       // density 1 / (2 pi (1 - cos_max)) about +z
using gpu::SampleUniformDisk;       // density 1 / pi on the unit disk
using gpu::SampleUniformSphere;     // density 1 / (4 pi)
using gpu::SampleUniformTriangle;   // barycentrics (b1, b2), density 1 / area

}  // namespace pf
