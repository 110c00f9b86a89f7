// The integration tests' small renders of the shipped scenes, shared by the integrator tests.
#pragma once

#include <string>

#include "core/job/integrator.h"
#include "embedded/local_render.h"

namespace pf::testing {

inline std::string ScenePath(const std::string& name) {
    return std::string(PF_SOURCE_DIR) + "/scenes/" + name;
}

// A small render of `scene` with `integrator`, on two threads, with a budget that puts its
// noise well below the bounds below in a few seconds.
inline RenderSettings Small(const std::string& scene, Integrator integrator, int size) {
    RenderSettings settings;
    settings.scene_path = ScenePath(scene);
    settings.threads = 2;
    JobSpec& job = settings.job;
    job.integrator = integrator;
    job.width = job.height = size;
    job.seed = 5;
    job.layout = {1u << 18, 8};
    switch (integrator) {
        // Progressive photon mapping keeps its k camera samples a pixel for good: with 4, the
        // light's edge pixels alone move a 64-pixel image's mean by a few percent from seed to
        // seed, error that no photon removes (stochastic ppm re-samples them every epoch).
        case Integrator::kPpm:
            job.samples_per_pixel = 16, job.photon_budget = 12'000'000;
            break;
        case Integrator::kSppm:
        case Integrator::kRpm:
            job.photon_budget = 12'000'000;
            break;
        case Integrator::kPm:
            job.photon_map.global_photons = 1'000'000;
            job.photon_map.caustic_photons = 1'000'000;
            job.epoch_budget = 8;
            break;
        case Integrator::kPath:
            job.epoch_budget = 96;
            break;
    }
    return settings;
}

}  // namespace pf::testing
