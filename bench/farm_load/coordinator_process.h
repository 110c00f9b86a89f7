// farm_load's coordinator: the real photonfarm-coordinator binary as a child process on
// 127.0.0.1 (TLS, worker certificates, tokens), its CPU, memory, threads and file
// descriptors read from /proc, its merge histogram from its /metrics, and a crash (SIGKILL)
// followed by a restart on the same port from its checkpoints.
#pragma once

#include <sys/types.h>

#include <memory>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "tests/support/child_process.h"

namespace pf::load {

// What /proc says of a process at one moment.
struct ProcessSample {
    double cpu_seconds = 0;  // user + system, since it started
    uint64_t rss_bytes = 0, peak_rss_bytes = 0;
    uint32_t threads = 0, fds = 0;
};
absl::StatusOr<ProcessSample> SampleProcess(pid_t pid);

// The coordinator's merge-latency histogram (photonfarm_merge_seconds) at one moment.
struct MergeHistogram {
    std::vector<std::pair<double, double>> buckets;  // (upper bound, cumulative count)
    double count = 0, sum = 0;
    // The bucket bound below which `fraction` of the merges fell (an upper estimate).
    double Quantile(double fraction) const;
};

class CoordinatorProcess {
public:
    // `binary`: photonfarm-coordinator; `flags`: its flags but --listen and --metrics-listen.
    static absl::StatusOr<std::unique_ptr<CoordinatorProcess>> Start(
        std::string binary, std::vector<std::string> flags);
    ~CoordinatorProcess();

    std::string Address() const;  // 127.0.0.1:PORT
    pid_t Pid() const { return process_->Pid(); }
    absl::StatusOr<MergeHistogram> ScrapeMerges() const;
    // Kills it with SIGKILL (no checkpoint written at exit) and starts it again on the same port.
    absl::Status CrashAndRestart();
    // SIGTERM, as an operator stops it; its exit code.
    absl::StatusOr<int> Stop();

private:
    CoordinatorProcess(std::string binary, std::vector<std::string> flags)
        : binary_(std::move(binary)), flags_(std::move(flags)) {}
    absl::Status Launch(const std::string& listen);

    const std::string binary_;
    const std::vector<std::string> flags_;
    std::unique_ptr<testing::ChildProcess> process_;
    int port_ = 0, metrics_port_ = 0;
};

}  // namespace pf::load
