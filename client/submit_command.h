// `photonfarm submit` and `photonfarm watch`: send a scene to a farm and follow its job.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "absl/status/status.h"
#include "client/farm_client.h"
#include "core/film/exr_io.h"

namespace pf {

// What a farm job's EXR files carry: job, scene, photons, epochs, seconds, estimated error.
ImageMetadata JobMetadata(const photonfarm::v1::JobStatus& status);
// `--report DIR` for a farm job: fetches its convergence log and writes the report.
absl::Status WriteJobReport(FarmClient& client, const std::string& job_id, const std::string& dir);

void AddSubmitCommand(CLI::App& app, int* exit_code);
void AddWatchCommand(CLI::App& app, int* exit_code);

}  // namespace pf
