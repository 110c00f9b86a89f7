// A WorkSource over a Coordinator in the same process: what the embedded `photonfarm render`
// runs its worker loop against. Leases hand over the job's inputs in memory; nothing is
// encoded or copied.
#pragma once

#include <string>

#include "core/job/work_source.h"
#include "server/coordinator.h"

namespace pf {

class InProcessSource final : public WorkSource {
public:
    // Registers a worker with `coordinator` (which must outlive this) and unregisters it on
    // destruction. `wait_seconds`: how long a lease waits for work.
    InProcessSource(Coordinator& coordinator, const WorkerRegistration& registration,
                    double wait_seconds);
    ~InProcessSource() override;

    absl::StatusOr<WorkGrant> Lease(uint32_t chunks) override;
    absl::StatusOr<TallyVerdict> Report(const std::string& job_id, BatchResult result) override;

private:
    Coordinator& coordinator_;
    double wait_seconds_;
    absl::StatusOr<std::string> worker_id_;
};

}  // namespace pf
