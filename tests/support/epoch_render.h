// The settings of a small local render that runs a fixed number of epochs, for tests that
// compare a photon mapper's image with the path tracer's.
#pragma once

#include <cstdint>
#include <string>

#include "embedded/local_render.h"

namespace pf::testing {

// `scene` at size x size pixels, `epochs` epochs of `integrator` on two threads.
inline RenderSettings EpochRender(const std::string& scene, Integrator integrator, int size,
                                  uint64_t seed, uint64_t epochs) {
    RenderSettings settings;
    settings.scene_path = scene;
    settings.threads = 2;
    settings.job.integrator = integrator;
    settings.job.width = settings.job.height = size;
    settings.job.seed = seed;
    settings.job.epoch_budget = epochs;
    return settings;
}

}  // namespace pf::testing
