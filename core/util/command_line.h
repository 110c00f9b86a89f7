// What every photonfarm executable does with its command line and its log: one logger on
// stderr whose lines name the program, a --log-level option, and one-line parse errors.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
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

// Whole numbers, checked on the text before CLI11 converts it (CLI11 reads "-5" into an
// unsigned field as 2^64 - 5, and "99999999999" into an int as a bare "could not convert"):
// a sign where none is allowed, a fraction, overflow and anything past [low, high] are refused
// naming the range, e.g. "--seed: must be a whole number in [0, 18446744073709551615], not
// '-1'".
CLI::Validator WholeNumber(uint64_t low, uint64_t high);
CLI::Validator SignedWholeNumber(int64_t low, int64_t high);
// A count with an optional decimal unit (k = 10^3, M = 10^6, G = 10^9, T = 10^12, any case;
// "1.5M" is 1500000), whole and in [low, high]; unknown units are refused naming those known.
// The text becomes the plain number for CLI11 to convert.
CLI::Validator CountWithUnit(uint64_t low, uint64_t high);
// HOST:PORT with a port number in [lowest_port, 65535]: 0 where a listener may ask for any
// free port, 1 where a client connects. IPv6 hosts in brackets ("[::1]:50051").
CLI::Validator HostAndPort(int lowest_port);

// Parses the command line (running the subcommands' callbacks). Returns the exit code to end
// with: 0 after --help, 2 after "PROGRAM: error: ... (see --help)" on stderr; nothing when
// parsing succeeded.
std::optional<int> ParseCommandLine(CLI::App& app, int argc, char** argv,
                                    const std::string& program);

}  // namespace pf
