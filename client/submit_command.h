// `photonfarm submit` and `photonfarm watch`: send a scene to a farm and follow its job.
#pragma once

#include <CLI/CLI.hpp>

namespace pf {

void AddSubmitCommand(CLI::App& app, int* exit_code);
void AddWatchCommand(CLI::App& app, int* exit_code);

}  // namespace pf
