// Progress bar and summary formatting.
#include "client/progress_display.h"

#include <unistd.h>

#include <string>

#include "absl/strings/str_format.h"

namespace pf {
namespace {

constexpr double kPlainLineInterval = 5.0;  // seconds between lines when not on a terminal

std::string Count(double value) {
    if (value >= 1e9) return absl::StrFormat("%.2fG", value / 1e9);
    if (value >= 1e6) return absl::StrFormat("%.2fM", value / 1e6);
    if (value >= 1e3) return absl::StrFormat("%.1fk", value / 1e3);
    return absl::StrFormat("%.0f", value);
}

std::string Status(const RenderProgress& p) {
    std::string status;
    if (GathersAtHitPoints(p.integrator)) {
        const double rate = p.seconds > 0 ? p.photons / p.seconds : 0;
        status = absl::StrFormat("%s photons, epoch %d, %.1f s, %s photons/s",
                                 Count(double(p.photons)), p.epochs, p.seconds, Count(rate));
    } else {  // path, pm: camera samples are the work; pm's photons are its maps', traced once
        const double rate = p.seconds > 0 ? p.camera_samples / p.seconds : 0;
        status = absl::StrFormat("%s samples, epoch %d, %.1f s, %s samples/s",
                                 Count(double(p.camera_samples)), p.epochs, p.seconds, Count(rate));
        if (p.photons > 0)
            status += absl::StrFormat(", maps of %s photons", Count(double(p.photons)));
    }
    if (p.estimated_error) status += absl::StrFormat(", error ~%.2g%%", 100 * *p.estimated_error);
    if (p.measured_error)
        status += absl::StrFormat(", against the reference %.2g%%", 100 * *p.measured_error);
    if (p.workers > 0) status += absl::StrFormat(", %d workers", p.workers);
    if (p.nonfinite_discarded > 0)
        status += absl::StrFormat(", %d NaN/Inf values discarded", p.nonfinite_discarded);
    return status;
}

}  // namespace

ProgressDisplay::ProgressDisplay(std::FILE* out) : out_(out), terminal_(isatty(fileno(out)) != 0) {}

void ProgressDisplay::Update(const RenderProgress& progress) {
    if (terminal_) {
        constexpr int kWidth = 30;
        const int filled = static_cast<int>(progress.fraction * kWidth);
        std::fprintf(out_, "\r[%s%s] %3d%% %s\033[K", std::string(filled, '#').c_str(),
                     std::string(kWidth - filled, '.').c_str(),
                     static_cast<int>(progress.fraction * 100), Status(progress).c_str());
        std::fflush(out_);
    } else if (progress.seconds - last_line_seconds_ >= kPlainLineInterval) {
        last_line_seconds_ = progress.seconds;
        std::fprintf(out_, "progress: %3d%% %s\n", static_cast<int>(progress.fraction * 100),
                     Status(progress).c_str());
        std::fflush(out_);
    }
}

void ProgressDisplay::Finish() {
    if (terminal_) std::fprintf(out_, "\n");
    std::fflush(out_);
}

void ProgressDisplay::Finish(const RenderOutcome& outcome) {
    if (terminal_) std::fprintf(out_, "\n");
    const RenderProgress& p = outcome.progress;
    const double seconds = p.seconds - outcome.camera_pass_seconds;
    const std::string memory =
        absl::StrFormat("peak memory %.0f MB", double(outcome.peak_memory_bytes) / 1e6);
    if (!GathersAtHitPoints(p.integrator)) {
        std::fprintf(out_, "done: %s; %s\n", Status(p).c_str(), memory.c_str());
        std::fflush(out_);
        return;
    }
    std::fprintf(out_, "done: %s; %s hit points, camera pass %.2f s, %s photon segments/s, %s\n",
                 Status(p).c_str(), Count(double(outcome.hit_points)).c_str(),
                 outcome.camera_pass_seconds, Count(seconds > 0 ? p.segments / seconds : 0).c_str(),
                 memory.c_str());
    std::fflush(out_);
}

}  // namespace pf
