// Warping uniform samples to the distributions photon mapping needs, defined once for the CPU
// and the Vulkan kernels in core/shared/path_sampling.h. Each function states its density
// there, so callers can divide by it; all directions are unit vectors.
#pragma once

#include "core/math/point2.h"
#include "core/math/vec3.h"
#include "core/shared/path_sampling.h"

namespace pf {

using shared::PowerHeuristic;          // multiple importance sampling's weight
using shared::SampleCosineHemisphere;  // density cos(theta) / pi about +z
using shared::SampleUniformCone;       // density 1 / (2 pi (1 - cos_max)) about +z
using shared::SampleUniformDisk;       // density 1 / pi on the unit disk
using shared::SampleUniformSphere;     // density 1 / (4 pi)
using shared::SampleUniformTriangle;   // barycentrics (b1, b2), density 1 / area

}  // namespace pf
