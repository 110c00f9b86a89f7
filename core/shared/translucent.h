// Diffuse transmission (pbrt-v4's DiffuseTransmissionBxDF): a surface reflecting R / pi back to
// the side light arrives from and letting T / pi through to the other, both Lambertian. Every
// pass takes it as two diffuse surfaces back to back: a point seen from one side reads the light
// arriving on that side times R and the light arriving on the other times T (a hit point whose
// normal is turned to the other side gathers the photons that land there), and a path that
// goes on chooses one with the probability below, as pbrt-v4 chooses. One definition for the
// CPU passes (core/shared/scatter.h's ChooseDiffuseSide) and the Vulkan photon kernel.
#ifndef PF_CORE_SHARED_TRANSLUCENT_H
#define PF_CORE_SHARED_TRANSLUCENT_H

#include "core/shared/gpu_prelude.h"

PF_GPU_BEGIN

// The probability of going through: T's largest channel over R's plus T's (0 where both are
// black).
PF_GPU_FN float TransmitProbability(vec3 reflectance, vec3 transmittance) {
    const float r = max(reflectance.x, max(reflectance.y, reflectance.z));
    const float t = max(transmittance.x, max(transmittance.y, transmittance.z));
    return r + t > 0.0f ? t / (r + t) : 0.0f;
}

PF_GPU_END

#endif  // PF_CORE_SHARED_TRANSLUCENT_H
