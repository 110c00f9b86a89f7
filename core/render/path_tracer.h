// A unidirectional path tracer with next-event estimation and multiple importance sampling
// (Veach 1997, ch. 9; pbrt-v4's PathIntegrator): the unbiased reference every photon mapper
// must converge to on diffuse scenes (tests/integration/integrators_test.cpp).
#pragma once

#include <cstdint>

#include "core/geometry/ray.h"
#include "core/geometry/tracer.h"
#include "core/sampling/rng.h"
#include "core/scene/emitters.h"
#include "core/scene/scene.h"
#include "core/scene/scene_features.h"

namespace pf {

// Russian roulette starts after this many bounces; paths end after kMaxPathDepth whatever
// their weight (with albedo 0.999 the chance of reaching it is about e^-65, as for photons).
inline constexpr int kPathRouletteDepth = 3;
inline constexpr int kMaxPathDepth = 1 << 16;

// What tracing a path reads; fixed for a job and shared by all threads.
struct PathInputs {
    const Scene* scene = nullptr;
    const Emitters* emitters = nullptr;
    const Tracer* tracer = nullptr;
    // The path code is instantiated for what the scene uses (AnalyseFeatures).
    SceneFeatures features = SceneFeatures::All();
    // A camera sample's cone, as a width per unit length: textures at the first diffuse hit
    // are averaged over it, as the camera pass does (0: point lookups).
    float filter_angle = 0;
    // Surfaces a path scatters at, at most (JobSpec::max_depth; the light met after the last
    // still counts, as in pbrt).
    int max_depth = kMaxPathDepth;
};

// One sample of the radiance arriving at ray.origin along -ray.direction, W/(m^2 sr).
// At every diffuse or rough-metal vertex one light sample (next-event estimation) and one
// continuation sampled from the BSDF, the two weighted by the power heuristic where both can
// find the light (area lights); specular vertices are followed by their one direction, and
// rough glass by its sampled one alone. May return NaN or Inf for
// a pathological scene: the caller discards and counts such samples.
Rgb TracePath(const PathInputs& inputs, Ray ray, Rng& rng);

}  // namespace pf
