// How what a scene file asks of its render (SceneRenderSettings: pbrt's Integrator and Sampler
// directives choose the light transport, its samples and its depth) meets the user's flags:
// the flags given on the command line win, and what neither gives keeps photonfarm's defaults.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/job/integrator.h"
#include "core/scene/scene.h"

namespace pf {

struct JobSpec;

// Which of a job's choices the user made explicitly (a flag), so the scene's do not apply.
// The budget needs no entry: a JobSpec with none has none given.
struct GivenSettings {
    bool integrator = false;
    bool samples_per_pixel = false;
    bool layout = false;  // --photons-per-batch or --batches-per-epoch
    bool max_depth = false;
};

// The scene's settings put into `spec` where `given` leaves them open, then the default
// budget where there is none (ApplyDefaultBudget). Returns one line per setting taken from
// the scene, saying what and from where, for the user to see.
//   sppm: iterations -> epochs; photons per iteration -> photons per epoch (as many batches
//         as the layout has, up to one photon each); one camera sample a pixel per epoch.
//   path, pm: Sampler pixel samples N -> min(16, N) epochs (or --epochs) of ceil(N / epochs).
std::vector<std::string> ApplySceneSettings(const SceneRenderSettings& scene,
                                            const GivenSettings& given, JobSpec* spec);

// The default budget for a job given none: 20M photons for ppm and sppm, 16 epochs for path
// and pm.
void ApplyDefaultBudget(JobSpec* spec);

}  // namespace pf
