// A worker's one job: lease batches, run them on a backend, report the tallies. The same loop
// serves photonfarm-worker (over gRPC) and the embedded `photonfarm render` (in process).
#pragma once

#include <condition_variable>
#include <cstdint>
#include <list>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "absl/status/statusor.h"
#include "core/job/work_source.h"
#include "worker/backend.h"

namespace pf {

struct WorkerStats {
    uint64_t batches_run = 0;
    uint64_t batches_refused = 0;  // reported but not accepted (another worker was first, ...)
    uint64_t photons = 0;
    uint64_t segments = 0;
};

class WorkerLoop {
public:
    // `chunks_per_lease`: how many chunks of photons to ask for at once (they run in parallel
    // on the calling TBB arena, so about the arena's thread count). `report_in_background`:
    // a thread of its own sends each lease's results while the next lease runs, so a slow
    // network does not idle the cores (a farm worker); otherwise Step reports before it
    // returns (the embedded render, whose report is the merge itself).
    WorkerLoop(WorkSource& source, std::string backend, uint32_t chunks_per_lease,
               bool report_in_background = false);
    ~WorkerLoop();  // sends what is still pending

    // One lease: runs what it got and reports it (or hands it to the reporting thread, once
    // that has sent the previous lease's results). Returns the number of batches run, 0 when
    // no work was offered; errors from the source (unreachable, also a failed background
    // report) or the backend.
    absl::StatusOr<size_t> Step();
    // Waits until every result is reported; the first report error since the last call.
    absl::Status Flush();

    WorkerStats Stats() const;

private:
    // A job's backend, kept across leases and rebuilt only when the job or epoch changes.
    struct JobBackend {
        std::string job_id;
        std::shared_ptr<const JobPayload> job;
        std::unique_ptr<Backend> backend;
        uint64_t epoch = UINT64_MAX;
    };
    absl::StatusOr<JobBackend*> BackendFor(const WorkGrant& grant);
    struct Pending {
        std::string job_id;
        std::vector<BatchResult> results;
    };
    absl::Status Report(Pending pending);
    void ReportInBackground();

    WorkSource& source_;
    std::string backend_name_;
    uint32_t chunks_per_lease_;
    std::list<JobBackend> backends_;  // most recently used first, a few jobs at most

    mutable std::mutex mutex_;  // guards what follows
    std::condition_variable changed_;
    WorkerStats stats_;
    std::optional<Pending> pending_;  // handed to the reporting thread, not yet sent
    bool reporting_ = false;          // the reporting thread is sending
    absl::Status report_error_;
    bool stopping_ = false;
    std::thread reporter_;
};

}  // namespace pf
