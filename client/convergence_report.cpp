// Convergence report: CSV, gnuplot script, plots.
#include "client/convergence_report.h"

#include <spdlog/spdlog.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_replace.h"
#include "client/convergence_plot.gp.h"
#include "core/util/file_io.h"

namespace pf {
namespace {

std::string FitVariables(const std::string& name, const std::optional<PowerLaw>& fit) {
    return absl::StrFormat("%s_ok = %d\n%s_slope = %.9g\n%s_log_scale = %.9g\n", name, fit ? 1 : 0,
                           name, fit ? fit->slope : 0.0, name, fit ? fit->log_scale : 0.0);
}

// Runs `gnuplot script` with `dir` as its working directory; its messages go to our stderr.
absl::Status RunGnuplot(const std::string& dir, const std::string& script) {
    const pid_t pid = fork();
    if (pid < 0)
        return absl::UnavailableError(absl::StrCat("cannot start gnuplot: ", std::strerror(errno)));
    if (pid == 0) {
        if (chdir(dir.c_str()) != 0) _exit(126);
        execlp("gnuplot", "gnuplot", script.c_str(), static_cast<char*>(nullptr));
        _exit(127);
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    const std::string script_path = absl::StrCat(dir, "/", script);
    if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
        return absl::FailedPreconditionError(
            absl::StrCat("gnuplot not found, so no plot: install gnuplot-nox "
                         "(deploy/install-deps.sh does) and run `gnuplot ",
                         script, "` in ", dir));
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        return absl::InternalError(
            absl::StrCat("gnuplot failed on ", script_path, " (see its messages above)"));
    return absl::OkStatus();
}

}  // namespace

void AddReferenceOption(CLI::App* command, std::string* path) {
    command
        ->add_option("--reference", *path,
                     "Measure every epoch against this EXR (RMSE, relative MSE, NaN/Inf pixels): "
                     "the render's size, "
                     "e.g. a long render with another --photon-stream (docs/convergence.md)")
        ->check(CLI::ExistingFile);
}

void AddReportOption(CLI::App* command, std::string* dir) {
    command->add_option(
        "--report", *dir,
        "Write the convergence log into this folder: convergence.csv and log-log plots of error "
        "against "
        "time and photons with fitted slopes (convergence.png, .svg; needs gnuplot)");
}

absl::Status PrepareReportDir(const std::string& dir) {
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    if (error)
        return absl::UnavailableError(
            absl::StrCat(dir, ": cannot make the report folder: ", error.message()));
    if (access(dir.c_str(), W_OK) != 0)
        return absl::UnavailableError(absl::StrCat(dir, ": cannot write to the report folder"));
    return absl::OkStatus();
}

std::string ConvergencePlotScript(const std::string& title,
                                  std::span<const ConvergencePoint> points) {
    const ConvergenceFits fits = FitConvergence(points);
    const bool has_reference =
        std::any_of(points.begin(), points.end(), [](const auto& p) { return p.measured; });
    // gnuplot's enhanced text reads _ and ^ as sub- and superscripts.
    const std::string quoted = absl::StrReplaceAll(
        title, {{"\\", "\\\\"}, {"\"", "\\\""}, {"_", "\\\\_"}, {"^", "\\\\^"}});
    return absl::StrCat(
        "# Written by photonfarm --report.\n", "title = \"", quoted, "\"\n",
        "has_reference = ", has_reference ? 1 : 0, "\n",
        WorkIsCameraSamples(points) ? "work = \"camera_samples\"\nwork_label = \"camera samples\"\n"
                                    : "work = \"photons\"\nwork_label = \"photons emitted\"\n",
        FitVariables("est_t", fits.estimated_vs_seconds),
        FitVariables("est_n", fits.estimated_vs_photons),
        FitVariables("ref_t", fits.measured_vs_seconds),
        FitVariables("ref_n", fits.measured_vs_photons), "\n",
        absl::string_view(kConvergencePlotScript.data(), kConvergencePlotScript.size()));
}

absl::Status WriteConvergenceReport(const std::string& dir, const std::string& title,
                                    std::span<const ConvergencePoint> points) {
    const std::string csv = absl::StrCat(dir, "/convergence.csv");
    if (absl::Status status = WriteConvergenceCsv(csv, points); !status.ok()) return status;
    const std::string script = "convergence.gp";
    if (absl::Status status = WriteFileAtomically(absl::StrCat(dir, "/", script),
                                                  ConvergencePlotScript(title, points));
        !status.ok())
        return status;
    spdlog::info("wrote {} ({} points)", csv, points.size());
    // Before a second epoch a render without a reference has no error yet, and log axes with
    // no point make gnuplot fail.
    if (std::none_of(points.begin(), points.end(),
                     [](const ConvergencePoint& p) { return p.estimated || p.measured; })) {
        spdlog::info(
            "no plot in {}: no error known yet (the estimate needs two epochs; "
            "--reference measures from the first)",
            dir);
        return absl::OkStatus();
    }
    if (absl::Status status = RunGnuplot(dir, script); !status.ok()) return status;
    spdlog::info("wrote {0}/convergence.png and {0}/convergence.svg", dir);
    return absl::OkStatus();
}

}  // namespace pf
