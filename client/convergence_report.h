// `--report DIR`: a render's convergence log as convergence.csv, the gnuplot script
// convergence.gp, and the log-log plots convergence.png and convergence.svg it draws, each
// with its fitted slopes (docs/convergence.md).
#pragma once

#include <CLI/CLI.hpp>
#include <span>
#include <string>

#include "absl/status/status.h"
#include "core/estimate/convergence.h"

namespace pf {

// --reference REF.exr and --report DIR, the same for `render`, `submit`, `watch` and `result`.
void AddReferenceOption(CLI::App* command, std::string* path);
void AddReportOption(CLI::App* command, std::string* dir);

// Before any work: makes `dir` and checks it can be written to, naming it otherwise.
absl::Status PrepareReportDir(const std::string& dir);

// The gnuplot script for a log, the template with the fits and title set in a header.
std::string ConvergencePlotScript(const std::string& title,
                                  std::span<const ConvergencePoint> points);

// Writes the CSV and the script, then runs gnuplot in `dir`. The CSV and script are written
// even when gnuplot is missing or fails; the error says which and how to plot by hand.
absl::Status WriteConvergenceReport(const std::string& dir, const std::string& title,
                                    std::span<const ConvergencePoint> points);

}  // namespace pf
