// The in-memory work source.
#include "server/in_process_source.h"

namespace pf {

InProcessSource::InProcessSource(Coordinator& coordinator, const WorkerRegistration& registration,
                                 double wait_seconds)
    : coordinator_(coordinator),
      wait_seconds_(wait_seconds),
      worker_id_(coordinator.RegisterWorker(registration)) {}

InProcessSource::~InProcessSource() {
    if (worker_id_.ok()) (void)coordinator_.UnregisterWorker(*worker_id_);
}

absl::StatusOr<WorkGrant> InProcessSource::Lease(uint32_t chunks) {
    if (!worker_id_.ok()) return worker_id_.status();
    absl::StatusOr<CoordinatorLease> lease = coordinator_.Lease(*worker_id_, chunks, wait_seconds_);
    if (!lease.ok()) return lease.status();
    return std::move(lease->grant);
}

absl::StatusOr<TallyVerdict> InProcessSource::Report(const std::string& job_id,
                                                     BatchResult result) {
    if (!worker_id_.ok()) return worker_id_.status();
    return coordinator_.Report(*worker_id_, job_id, std::move(result));
}

}  // namespace pf
