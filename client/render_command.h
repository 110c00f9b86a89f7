// `photonfarm render`: renders a scene on this machine, with no server.
#pragma once

#include <CLI/CLI.hpp>

namespace pf {

// Registers the subcommand on `app`; its callback sets *exit_code.
void AddRenderCommand(CLI::App& app, int* exit_code);

}  // namespace pf
