// Adaptive photon tracing (Hachisuka & Jensen 2011, "Robust adaptive photon tracing using photon
// path visibility"): Markov chains over photon paths whose target is the photon's visibility (1
// where some deposit lands within a hit point's radius, else 0). A state is the numbers of a
// photon's emission and the stream its walk draws from. Each step first traces a fresh photon;
// where it is visible the chain jumps to it (their replica exchange), otherwise it proposes the
// state's emission mutated, walked with the state's stream, accepted where visible. The state
// contributes once a step; the uniform photons' visible share V_c normalises the chain's sum.
// One definition of the mutation and of its adaptation for the CPU (core/ppm/photon_pass.cpp)
// and the Vulkan kernel (photon_trace.comp).
#ifndef PF_CORE_SHARED_PHOTON_CHAIN_H
#define PF_CORE_SHARED_PHOTON_CHAIN_H

#include "core/shared/gpu_prelude.h"

PF_GPU_BEGIN

// The numbers a photon's emission takes, drawn before its walk: the emitter's pick, then the
// point and the direction (Emitters::Emit, lights.glsl's EmitPhotonFrom).
PF_CONST(uint32_t) kEmissionNumbers = 6u;
// The acceptance rate the mutation size is steered toward (Roberts, Gelman & Gilks 1997's
// optimum, which Hachisuka & Jensen take).
PF_CONST(float) kTargetAcceptance = 0.234f;
// The mutation size's first value and its bounds, in the unit interval's widths.
PF_CONST(float) kFirstMutationSize = 0.25f;
PF_CONST(float) kLeastMutationSize = 1.0f / 16384.0f;
PF_CONST(float) kMostMutationSize = 0.5f;

// `u` moved by size x (2v - 1) and wrapped into [0, 1): a symmetric proposal, so that accepting
// every visible one leaves the chain's target, uniform over the visible photons, in place.
PF_GPU_FN float MutateNumber(float u, float v, float size) {
    const float moved = u + size * (2.0f * v - 1.0f);
    const float wrapped = moved - floor(moved);
    return wrapped < 1.0f ? wrapped : 0.0f;  // a tiny negative `moved` rounds up to 1
}

// The size after a chain's `mutated`-th mutation, `accepted` of them taken (Robbins-Monro
// steps toward the target rate, shrinking as 1 / mutated, so the adaptation dies out).
PF_GPU_FN float AdaptMutationSize(float size, uint32_t accepted, uint32_t mutated) {
    const float rate = float(accepted) / float(mutated);
    return clamp(size + (rate - kTargetAcceptance) / float(mutated), kLeastMutationSize,
                 kMostMutationSize);
}

PF_GPU_END

#endif  // PF_CORE_SHARED_PHOTON_CHAIN_H
