// `photonfarm cancel`, `jobs`, `workers`, `result` and `health`: managing a farm from the
// command line.
#pragma once

#include <CLI/CLI.hpp>

namespace pf {

void AddJobCommands(CLI::App& app, int* exit_code);

}  // namespace pf
