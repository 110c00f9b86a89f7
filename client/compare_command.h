// `photonfarm compare IMAGE REFERENCE`: how far an EXR image is from a reference.
#pragma once

#include <CLI/CLI.hpp>

namespace pf {

// Registers the subcommand on `app`; its callback sets *exit_code.
void AddCompareCommand(CLI::App& app, int* exit_code);

}  // namespace pf
