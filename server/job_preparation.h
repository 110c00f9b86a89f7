// Preparing a submitted job: everything a job needs before its first batch.
#pragma once

#include "absl/status/statusor.h"
#include "server/coordinator.h"
#include "server/job.h"

namespace pf {

// Loads the scene, runs the camera pass and sets up the estimate; errors name the setting
// (as flags or as message fields, options.setting_names) or the scene's problem.
absl::StatusOr<PreparedJob> PrepareJob(JobRequest request, const CoordinatorOptions& options);

}  // namespace pf
