// The lease-run-report loop.
#include "worker/worker_loop.h"

#include <spdlog/spdlog.h>

#include "worker/backend_factory.h"

namespace pf {
namespace {

// Jobs whose backends (Embree scene, hit-point grid) stay built while others run: enough for
// a worker shared among a few jobs not to rebuild on every lease.
constexpr size_t kBackendsKept = 4;

}  // namespace

WorkerLoop::WorkerLoop(WorkSource& source, std::string backend, uint32_t chunks_per_lease)
    : source_(source), backend_name_(std::move(backend)), chunks_per_lease_(std::max(1u, chunks_per_lease)) {}

absl::StatusOr<WorkerLoop::JobBackend*> WorkerLoop::BackendFor(const WorkGrant& grant) {
    auto it = backends_.begin();
    while (it != backends_.end() && !(it->job_id == grant.job_id && it->job == grant.job)) ++it;
    if (it == backends_.end()) {
        absl::StatusOr<std::unique_ptr<Backend>> backend = CreateBackend(backend_name_, grant.job->scene);
        if (!backend.ok()) return backend.status();
        const JobPayload& job = *grant.job;
        if (absl::Status status = (*backend)->BeginJob({&job.scene, &job.emitters, *job.hit_points, job.seed}); !status.ok())
            return status;
        backends_.push_front({grant.job_id, grant.job, std::move(*backend)});
        if (backends_.size() > kBackendsKept) backends_.pop_back();
    } else {
        backends_.splice(backends_.begin(), backends_, it);
    }
    JobBackend& current = backends_.front();
    if (current.epoch != grant.epoch) {
        current.backend->BeginEpoch(*grant.radius_sq);
        current.epoch = grant.epoch;
    }
    return &current;
}

absl::StatusOr<size_t> WorkerLoop::Step() {
    absl::StatusOr<WorkGrant> grant = source_.Lease(chunks_per_lease_);
    if (!grant.ok()) return grant.status();
    if (grant->batches.empty()) return 0;
    absl::StatusOr<JobBackend*> backend = BackendFor(*grant);
    if (!backend.ok()) return backend.status();
    std::vector<BatchResult> results = (*backend)->backend->RunBatches(grant->batches);
    for (BatchResult& result : results) {
        const uint64_t index = result.spec.index;
        ++stats_.batches_run;
        stats_.photons += result.photons_emitted;
        stats_.segments += result.segments_traced;
        absl::StatusOr<TallyVerdict> verdict = source_.Report(grant->job_id, std::move(result));
        if (!verdict.ok()) return verdict.status();
        if (*verdict != TallyVerdict::kAccepted) {
            ++stats_.batches_refused;
            spdlog::debug("batch {} of job {} refused ({})", index, grant->job_id, static_cast<int>(*verdict));
        }
    }
    return results.size();
}

}  // namespace pf
