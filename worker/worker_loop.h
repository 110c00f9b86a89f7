// A worker's one job: lease batches, run them on a backend, report the tallies. The same loop
// serves photonfarm-worker (over gRPC) and the embedded `photonfarm render` (in process).
#pragma once

#include <cstdint>
#include <list>
#include <memory>
#include <string>

#include "absl/status/statusor.h"
#include "worker/backend.h"
#include "worker/work_source.h"

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
    // on the calling TBB arena, so about the arena's thread count).
    WorkerLoop(WorkSource& source, std::string backend, uint32_t chunks_per_lease);

    // One lease: runs and reports what it got. Returns the number of batches run, 0 when no
    // work was offered; errors from the source (unreachable) or the backend.
    absl::StatusOr<size_t> Step();

    const WorkerStats& Stats() const { return stats_; }

private:
    // A job's backend, kept across leases and rebuilt only when the job or epoch changes.
    struct JobBackend {
        std::string job_id;
        std::shared_ptr<const JobPayload> job;
        std::unique_ptr<Backend> backend;
        uint64_t epoch = UINT64_MAX;
    };
    absl::StatusOr<JobBackend*> BackendFor(const WorkGrant& grant);

    WorkSource& source_;
    std::string backend_name_;
    uint32_t chunks_per_lease_;
    std::list<JobBackend> backends_;  // most recently used first, a few jobs at most
    WorkerStats stats_;
};

}  // namespace pf
