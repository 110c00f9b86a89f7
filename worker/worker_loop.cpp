// The lease-run-report loop.
#include "worker/worker_loop.h"

#include <spdlog/spdlog.h>

#include <utility>

#include "absl/strings/str_cat.h"
#include "worker/backend_factory.h"

namespace pf {
namespace {

// Jobs whose backends (Embree scene, hit-point grid) stay built while others run: enough for
// a worker shared among a few jobs not to rebuild on every lease.
constexpr size_t kBackendsKept = 4;

// A backend's failure (a job too large for the GPU, a lost device) is this worker's to
// report, not the network's: FAILED_PRECONDITION, which the worker does not retry. It leaves,
// returning its leases, and the job goes on elsewhere.
absl::Status BackendError(const absl::Status& status, const std::string& backend,
                          const std::string& job_id) {
    return absl::FailedPreconditionError(
        absl::StrCat("the ", backend, " backend cannot run job ", job_id, ": ", status.message()));
}

}  // namespace

WorkerLoop::WorkerLoop(WorkSource& source, std::string backend, uint32_t chunks_per_lease,
                       bool report_in_background)
    : source_(source),
      backend_name_(std::move(backend)),
      chunks_per_lease_(std::max(1u, chunks_per_lease)) {
    if (report_in_background) reporter_ = std::thread([this] { ReportInBackground(); });
}

WorkerLoop::~WorkerLoop() {
    if (!reporter_.joinable()) return;
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
        changed_.notify_all();
    }
    reporter_.join();
}

WorkerStats WorkerLoop::Stats() const {
    std::lock_guard lock(mutex_);
    return stats_;
}

absl::Status WorkerLoop::Report(Pending pending) {
    for (BatchResult& result : pending.results) {
        const uint64_t index = result.spec.index;
        absl::StatusOr<TallyVerdict> verdict = source_.Report(pending.job_id, std::move(result));
        if (!verdict.ok()) return verdict.status();
        if (*verdict != TallyVerdict::kAccepted) {
            std::lock_guard lock(mutex_);
            ++stats_.batches_refused;
            spdlog::debug("batch {} of job {} refused ({})", index, pending.job_id,
                          static_cast<int>(*verdict));
        }
    }
    return absl::OkStatus();
}

void WorkerLoop::ReportInBackground() {
    std::unique_lock lock(mutex_);
    while (true) {
        changed_.wait(lock, [&] { return pending_.has_value() || stopping_; });
        if (!pending_) return;  // stopping, and everything is sent
        Pending pending = std::move(*pending_);
        pending_.reset();
        reporting_ = true;
        lock.unlock();
        absl::Status status = Report(std::move(pending));
        lock.lock();
        reporting_ = false;
        if (!status.ok() && report_error_.ok()) report_error_ = std::move(status);
        changed_.notify_all();
    }
}

absl::Status WorkerLoop::Flush() {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return !pending_ && !reporting_; });
    return std::exchange(report_error_, absl::OkStatus());
}

absl::StatusOr<WorkerLoop::JobBackend*> WorkerLoop::BackendFor(const WorkGrant& grant) {
    auto it = backends_.begin();
    while (it != backends_.end() && !(it->job_id == grant.job_id && it->job == grant.job)) ++it;
    if (it == backends_.end()) {
        absl::StatusOr<std::unique_ptr<Backend>> backend =
            CreateBackend(backend_name_, grant.job->scene);
        if (!backend.ok()) return BackendError(backend.status(), backend_name_, grant.job_id);
        const JobPayload& job = *grant.job;
        if (absl::Status status = (*backend)->BeginJob(
                {&job.scene, &job.emitters, *job.hit_points, job.seed, &job.spec});
            !status.ok())
            return BackendError(status, backend_name_, grant.job_id);
        backends_.push_front({grant.job_id, grant.job, std::move(*backend)});
        if (backends_.size() > kBackendsKept) backends_.pop_back();
    } else {
        backends_.splice(backends_.begin(), backends_, it);
    }
    JobBackend& current = backends_.front();
    if (current.epoch != grant.epoch) {
        if (absl::Status status = current.backend->BeginEpoch(grant.epoch, *grant.regions,
                                                              grant.epoch_hit_points.get());
            !status.ok())
            return BackendError(status, backend_name_, grant.job_id);
        current.epoch = grant.epoch;
    }
    return &current;
}

absl::StatusOr<size_t> WorkerLoop::Step() {
    if (reporter_.joinable()) {
        std::lock_guard lock(mutex_);
        if (!report_error_.ok()) return std::exchange(report_error_, absl::OkStatus());
    }
    absl::StatusOr<WorkGrant> grant = source_.Lease(chunks_per_lease_);
    if (!grant.ok()) return grant.status();
    if (grant->batches.empty()) return 0;
    absl::StatusOr<JobBackend*> backend = BackendFor(*grant);
    if (!backend.ok()) return backend.status();
    absl::StatusOr<std::vector<BatchResult>> results =
        (*backend)->backend->RunBatches(grant->batches);
    if (!results.ok()) return BackendError(results.status(), backend_name_, grant->job_id);
    Pending pending{grant->job_id, std::move(*results)};
    const size_t ran = pending.results.size();
    std::unique_lock lock(mutex_);
    for (const BatchResult& result : pending.results) {
        ++stats_.batches_run;
        stats_.photons += result.photons_emitted;
        stats_.segments += result.segments_traced;
    }
    if (!reporter_.joinable()) {
        lock.unlock();
        if (absl::Status status = Report(std::move(pending)); !status.ok()) return status;
        return ran;
    }
    // One lease's results wait at most: the next lease runs while they are sent.
    changed_.wait(lock, [&] { return !pending_; });
    pending_ = std::move(pending);
    changed_.notify_all();
    return ran;
}

}  // namespace pf
