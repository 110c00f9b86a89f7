// The coordinator as a child process (coordinator_process.h).
#include "bench/farm_load/coordinator_process.h"

#include <httplib.h>
#include <signal.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "absl/strings/strip.h"

namespace pf::load {
namespace {

constexpr double kStartSeconds = 30;

std::string ReadText(const std::string& path) {
    std::ifstream file(path);
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
}

// "Name:   123 kB" in /proc/PID/status, in the unit given (kB: bytes).
uint64_t StatusField(const std::string& status, absl::string_view name) {
    for (absl::string_view line : absl::StrSplit(status, '\n')) {
        if (!absl::ConsumePrefix(&line, name) || !absl::ConsumePrefix(&line, ":")) continue;
        const std::vector<absl::string_view> words =
            absl::StrSplit(line, ' ', absl::SkipWhitespace());
        uint64_t value = 0;
        if (words.empty() || !absl::SimpleAtoi(words[0], &value)) return 0;
        return words.size() > 1 && words[1] == "kB" ? value * 1024 : value;
    }
    return 0;
}

}  // namespace

absl::StatusOr<ProcessSample> SampleProcess(pid_t pid) {
    const std::string proc = absl::StrCat("/proc/", pid);
    const std::string stat = ReadText(proc + "/stat");
    // Fields after the command's closing parenthesis: state is the 3rd field, utime the 14th.
    const size_t close = stat.rfind(')');
    if (close == std::string::npos) return absl::NotFoundError(absl::StrCat("no process ", pid));
    const std::vector<absl::string_view> fields =
        absl::StrSplit(absl::string_view(stat).substr(close + 2), ' ');
    uint64_t user = 0, system = 0;
    if (fields.size() < 13 || !absl::SimpleAtoi(fields[11], &user) ||
        !absl::SimpleAtoi(fields[12], &system))
        return absl::DataLossError(absl::StrCat(proc, "/stat: unreadable"));
    ProcessSample sample;
    sample.cpu_seconds = static_cast<double>(user + system) / sysconf(_SC_CLK_TCK);
    const std::string status = ReadText(proc + "/status");
    sample.rss_bytes = StatusField(status, "VmRSS");
    sample.peak_rss_bytes = StatusField(status, "VmHWM");
    sample.threads = static_cast<uint32_t>(StatusField(status, "Threads"));
    std::error_code error;
    for (auto it = std::filesystem::directory_iterator(proc + "/fd", error);
         !error && it != std::filesystem::directory_iterator(); it.increment(error))
        ++sample.fds;
    return sample;
}

double MergeHistogram::Quantile(double fraction) const {
    for (const auto& [bound, cumulative] : buckets)
        if (cumulative >= fraction * count) return bound;
    return buckets.empty() ? 0 : buckets.back().first;
}

absl::StatusOr<std::unique_ptr<CoordinatorProcess>> CoordinatorProcess::Start(
    std::string binary, std::vector<std::string> flags) {
    std::unique_ptr<CoordinatorProcess> process(
        new CoordinatorProcess(std::move(binary), std::move(flags)));
    if (absl::Status started = process->Launch("127.0.0.1:0"); !started.ok()) return started;
    return process;
}

CoordinatorProcess::~CoordinatorProcess() = default;

absl::Status CoordinatorProcess::Launch(const std::string& listen) {
    std::vector<std::string> argv = {binary_, "--listen", listen, "--metrics-listen",
                                     "127.0.0.1:0"};
    argv.insert(argv.end(), flags_.begin(), flags_.end());
    process_ = std::make_unique<testing::ChildProcess>(argv);
    port_ = metrics_port_ = 0;
    while (port_ == 0 || metrics_port_ == 0) {
        std::optional<std::string> line = process_->ReadLine(kStartSeconds);
        if (!line)
            return absl::UnavailableError(
                absl::StrCat("photonfarm-coordinator did not start on ", listen));
        absl::string_view rest = *line;
        int* port = absl::ConsumePrefix(&rest, "listening on ") ? &port_
                    : absl::ConsumePrefix(&rest, "metrics on ") ? &metrics_port_
                                                                : nullptr;
        if (port && !absl::SimpleAtoi(rest.substr(rest.rfind(':') + 1), port))
            return absl::DataLossError(
                absl::StrCat("photonfarm-coordinator printed '", *line, "'"));
    }
    return absl::OkStatus();
}

std::string CoordinatorProcess::Address() const { return absl::StrCat("127.0.0.1:", port_); }

absl::StatusOr<MergeHistogram> CoordinatorProcess::ScrapeMerges() const {
    httplib::Client client("127.0.0.1", metrics_port_);
    client.set_read_timeout(10, 0);
    httplib::Result response = client.Get("/metrics");
    if (!response || response->status != 200)
        return absl::UnavailableError("the coordinator's /metrics did not answer");
    MergeHistogram histogram;
    for (absl::string_view line : absl::StrSplit(response->body, '\n')) {
        if (!absl::ConsumePrefix(&line, "photonfarm_merge_seconds")) continue;
        const size_t space = line.rfind(' ');
        double value = 0;
        if (space == absl::string_view::npos || !absl::SimpleAtod(line.substr(space + 1), &value))
            continue;
        if (absl::StartsWith(line, "_count")) histogram.count = value;
        if (absl::StartsWith(line, "_sum")) histogram.sum = value;
        absl::string_view bound = line.substr(0, space);
        double le = 0;
        if (absl::ConsumePrefix(&bound, "_bucket{le=\"") && absl::ConsumeSuffix(&bound, "\"}"))
            histogram.buckets.emplace_back(
                bound == "+Inf" ? INFINITY : (absl::SimpleAtod(bound, &le) ? le : 0), value);
    }
    return histogram;
}

absl::Status CoordinatorProcess::CrashAndRestart() {
    process_->Signal(SIGKILL);
    process_->Wait(kStartSeconds);
    return Launch(absl::StrCat("127.0.0.1:", port_));
}

absl::StatusOr<int> CoordinatorProcess::Stop() {
    process_->Signal(SIGTERM);
    std::optional<int> code = process_->Wait(kStartSeconds);
    if (!code) return absl::DeadlineExceededError("photonfarm-coordinator did not stop on SIGTERM");
    return *code;
}

}  // namespace pf::load
