// What every photonfarm executable does with its command line and its log: one logger on
// stderr whose lines name the program, a --log-level option, and one-line parse errors.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

namespace pf {

// Logs and errors go to stderr as "PROGRAM: LEVEL: message"; stdout stays free for results.
void SetUpLogging(const std::string& program);

// --log-level (trace, debug, info, warn, error, off; info by default), applied as it is parsed,
// before any subcommand's callback runs.
void AddLogLevelOption(CLI::App& app);

// Number checks that refuse NaN and Inf with a short message ("must be a finite number"):
// CLI11's ranges let NaN through, and print the largest double for PositiveNumber.
CLI::Validator FiniteNumber();
CLI::Validator FinitePositive();
CLI::Validator FiniteRange(double low, double high);

// Parses the command line (running the subcommands' callbacks). Returns the exit code to end
// with: 0 after --help, 2 after "PROGRAM: error: ... (see --help)" on stderr; nothing when
// parsing succeeded.
std::optional<int> ParseCommandLine(CLI::App& app, int argc, char** argv,
                                    const std::string& program);

}  // namespace pf
