// The options that describe a job, shared by `render` (on this machine) and `submit` (to a
// farm) so both accept the same flags with the same checks.
#pragma once

#include <CLI/CLI.hpp>

#include "core/job/job_spec.h"
#include "core/job/scene_settings.h"

namespace pf {

// Adds --integrator, the budgets (--photons, --epochs, --seconds, --target-error), --spp,
// --width/--height, --alpha, --radius, --seed, the batch layout and classic photon mapping's
// settings (--pm-*, --final-gather, --photon-index) and the environment (--environment*) to
// `command`, writing into `spec` (spec->environment.file: the image's path on this machine,
// which BundleEnvironment moves into the scene's bundle).
void AddJobOptions(CLI::App* command, JobSpec* spec);
// After parsing: which of the settings a scene file may choose the user gave as flags.
GivenSettings GivenSettingsOf(const CLI::App& command);

}  // namespace pf
