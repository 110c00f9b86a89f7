// The filters of classic photon mapping's k-nearest density estimate (Jensen 2001, section
// 7.1; core/pm/density_estimate.h): a photon's weight by its distance within the disc of the
// k-th, and each filter's normalisation c = (1 / (pi r^2)) x the weight's integral over the
// disc, so that a uniform density is estimated without bias whatever the filter. For the CPU
// and the Vulkan kernels alike; filters numbered as DensityFilter (core/job/integrator.h).
#ifndef PF_CORE_SHARED_DENSITY_FILTER_H
#define PF_CORE_SHARED_DENSITY_FILTER_H

#include "core/shared/gpu_prelude.h"

PF_GPU_BEGIN

PF_CONST(uint32_t) kFilterBox = 0;
PF_CONST(uint32_t) kFilterCone = 1;
PF_CONST(uint32_t) kFilterGaussian = 2;
// The cone filter's constant k >= 1: weights fall from 1 at the point to 1 - 1/k at r.
PF_CONST(float) kConeFilterK = 1.1f;
// The Gaussian filter's beta (Pavicic 1990, as Jensen uses it).
PF_CONST(float) kGaussianBeta = 1.953f;

PF_GPU_FN float DensityFilterWeight(uint32_t kind, float distance_sq, float radius_sq) {
    if (kind == kFilterCone) return 1.0f - sqrt(distance_sq / radius_sq) / kConeFilterK;
    if (kind == kFilterGaussian)
        return 1.0f - (1.0f - exp(-0.5f * kGaussianBeta * (distance_sq / radius_sq))) /
                          (1.0f - exp(-kGaussianBeta));
    return 1.0f;
}

PF_GPU_FN float DensityFilterNormalisation(uint32_t kind) {
    // integral over the unit disc of (1 - s / k) 2 s ds = 1 - 2 / (3 k)
    if (kind == kFilterCone) return 1.0f - 2.0f / (3.0f * kConeFilterK);
    // integral of (1 - (1 - e^(-beta s^2 / 2)) / (1 - e^-beta)) 2 s ds
    if (kind == kFilterGaussian)
        return 1.0f - (1.0f - (2.0f / kGaussianBeta) * (1.0f - exp(-0.5f * kGaussianBeta))) /
                          (1.0f - exp(-kGaussianBeta));
    return 1.0f;
}

PF_GPU_END

#endif  // PF_CORE_SHARED_DENSITY_FILTER_H
