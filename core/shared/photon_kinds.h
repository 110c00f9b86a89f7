// How a photon came to land where it did, one bit a kind, and which kinds a hit point gathers
// (a mask of them): one definition for the CPU photon pass (core/ppm/photon_trace.h, HashGrid)
// and the Vulkan kernel (photon_trace.comp, which reads a hit point's mask from
// GpuHitPoint::weight.w). Progressive and stochastic progressive photon mapping sample direct
// light apart and gather every scattered photon; reverse photon mapping splits the light as
// classic photon mapping's maps do: its camera hit points gather caustics alone, its gather
// hits everything.
#ifndef PF_CORE_SHARED_PHOTON_KINDS_H
#define PF_CORE_SHARED_PHOTON_KINDS_H

#include "core/shared/gpu_prelude.h"

PF_GPU_BEGIN

PF_CONST(uint32_t) kDirectPhoton = 1u;   // at its first surface: direct light
PF_CONST(uint32_t) kCausticPhoton = 2u;  // after specular and rough bounces alone
PF_CONST(uint32_t) kDiffusePhoton = 4u;  // after a diffuse bounce (or a coat's return)
// ppm's and sppm's hit points: every photon but direct light, which is sampled apart.
PF_CONST(uint32_t) kScatteredPhotons = 6u;  // kCausticPhoton | kDiffusePhoton
// rpm's gather hits: all light leaving the surface, as classic photon mapping's global map
// holds it for final gathering.
PF_CONST(uint32_t) kAllPhotons = 7u;  // kDirectPhoton | kCausticPhoton | kDiffusePhoton

// The kind of a photon landing: at its first surface (not `scattered`, unless a coat turned it
// back there), through specular and rough bounces alone (not `diffused`), or after a diffuse one.
PF_GPU_FN uint32_t PhotonKind(bool scattered, bool diffused, bool returned) {
    if (!scattered && !returned) return kDirectPhoton;
    return diffused || returned ? kDiffusePhoton : kCausticPhoton;
}

PF_GPU_END

#endif  // PF_CORE_SHARED_PHOTON_KINDS_H
