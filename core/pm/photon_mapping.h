// Classic photon mapping's rendering pass (Jensen 1996, section 3): a camera path follows
// specular and rough bounces to its first diffuse surface, where the light leaving it is the
// sum of direct light (core/ppm/direct_light.h), caustics (the caustic map's estimate) and
// indirect light, read from the global map there or, with final gathering, from the global map
// where gather rays land. Each part of the light is counted by exactly one of them.
#pragma once

#include <cstdint>

#include "core/geometry/ray.h"
#include "core/geometry/tracer.h"
#include "core/job/integrator.h"
#include "core/pm/photon_map.h"
#include "core/sampling/rng.h"
#include "core/scene/emitters.h"
#include "core/scene/scene.h"
#include "core/scene/scene_features.h"

namespace pf {

// What a camera sample reads; fixed for a job, shared by all threads.
struct PhotonMappingInputs {
    const Scene* scene = nullptr;
    const Emitters* emitters = nullptr;
    const Tracer* tracer = nullptr;
    const PhotonMaps* maps =
        nullptr;  // built with these settings (final gathering decides the global map's content)
    PhotonMapSettings settings;
    float max_radius = 0;  // of the k-nearest search (MaxSearchRadius)
    float filter_angle =
        0;  // a camera sample's cone, for textures at its diffuse hit (as PathInputs)
    SceneFeatures features = SceneFeatures::All();
    int max_depth = 0;  // JobSpec::max_depth: of camera paths (0: no limit)
};

// One sample of the radiance arriving along a camera ray, W/(m^2 sr). Thread-safe.
Rgb PhotonMappingRadiance(const PhotonMappingInputs& inputs, Ray ray, Rng& rng);

}  // namespace pf
