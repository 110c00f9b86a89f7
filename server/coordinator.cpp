// Job and worker bookkeeping and lease scheduling (jobs are prepared by job_preparation.h).
#include "server/coordinator.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <random>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "server/job_preparation.h"

namespace pf {
namespace {

std::string RandomHex(int digits) {
    std::random_device device;
    std::string hex;
    while (static_cast<int>(hex.size()) < digits) hex += absl::StrFormat("%08x", device());
    return hex.substr(0, digits);
}

}  // namespace

Coordinator::Coordinator(CoordinatorOptions options)
    : options_(std::move(options)), id_salt_(RandomHex(4)) {
    if (options_.checkpoint_dir.empty()) return;
    checkpoints_ = std::make_unique<CheckpointStore>(options_.checkpoint_dir);
    checkpoint_thread_ = std::thread([this] { CheckpointLoop(); });
}

Coordinator::~Coordinator() {
    Shutdown();
    if (!checkpoints_) return;
    {
        std::lock_guard lock(mutex_);
        checkpoints_stopping_ = true;
        checkpoint_wake_.notify_all();
    }
    checkpoint_thread_.join();
    WriteCheckpoints();  // the jobs as they stand at the end, to be resumed by the next coordinator
}

void Coordinator::CheckpointLoop() {
    std::unique_lock lock(mutex_);
    Clock::time_point next = Clock::now() + Duration(options_.checkpoint_seconds);
    while (!checkpoints_stopping_) {
        // Woken early when a job ends (its final state is written at once) or is forgotten.
        checkpoint_wake_.wait_until(lock, next);
        if (checkpoints_stopping_) break;
        const bool due = Clock::now() >= next;
        if (due) next = Clock::now() + Duration(options_.checkpoint_seconds);
        lock.unlock();
        WriteCheckpoints(due);
        lock.lock();
    }
}

void Coordinator::WriteCheckpoints() { WriteCheckpoints(true); }

void Coordinator::WriteCheckpoints(bool running_too) {
    if (!checkpoints_) return;
    std::lock_guard writer(checkpoint_mutex_);
    std::vector<std::shared_ptr<Job>> jobs;
    std::vector<std::string> forgotten;
    {
        std::lock_guard lock(mutex_);
        for (const std::string& id : job_order_) jobs.push_back(jobs_.at(id));
        forgotten.swap(forgotten_);
    }
    for (const std::string& id : forgotten) checkpoints_->Remove(id);
    for (const std::shared_ptr<Job>& job : jobs) WriteCheckpointLocked(*job, running_too);
}

void Coordinator::WriteCheckpointLocked(Job& job, bool running_too) {
    const auto seconds = [](Clock::duration d) { return std::chrono::duration<double>(d).count(); };
    const auto start = Clock::now();
    std::optional<JobCheckpointData> checkpoint = job.TakeFinalCheckpoint();
    if (!checkpoint && running_too) {
        absl::StatusOr<JobCheckpointData> running = job.Checkpoint(Now());
        if (running.ok()) checkpoint = std::move(*running);
    }
    if (!checkpoint) return;
    const auto saved = Clock::now();
    if (absl::Status status = checkpoints_->Write(*checkpoint); !status.ok()) {
        spdlog::error("job {}: checkpoint not written: {}", job.Id(),
                      std::string(status.message()));
        return;
    }
    // Its own bytes; the fixed parts it names are written once per job.
    spdlog::debug(
        "job {}: checkpoint {} saved in {:.3f} s, written in {:.3f} s ({:.1f} MB)", job.Id(),
        checkpoint->record.sequence(), seconds(saved - start), seconds(Clock::now() - saved),
        double(checkpoint->record.ByteSizeLong() + checkpoint->estimate.size()) / (1 << 20));
}

size_t Coordinator::RestoreCheckpoints() {
    if (!checkpoints_) return 0;
    std::vector<JobCheckpointData> checkpoints = checkpoints_->ReadAll();
    // In submission order (the number in "job-N-..."), for fairness ties and listings.
    const auto number = [](const JobCheckpointData& checkpoint) {
        uint64_t n = 0;
        std::sscanf(checkpoint.record.job_id().c_str(), "job-%" SCNu64, &n);
        return n;
    };
    std::sort(checkpoints.begin(), checkpoints.end(),
              [&](const auto& a, const auto& b) { return number(a) < number(b); });
    size_t restored = 0;
    for (const JobCheckpointData& checkpoint : checkpoints) {
        const std::string& id = checkpoint.record.job_id();
        absl::StatusOr<std::shared_ptr<Job>> job =
            Job::Restore(checkpoint, options_.scene_limits, Now());
        if (!job.ok()) {
            spdlog::error("job {}: not resumed: {}", id, std::string(job.status().message()));
            continue;
        }
        const JobProgress progress = (*job)->Progress(Now());
        spdlog::info("job {} resumed from checkpoint {}: {}, epoch {}, {} photons", id,
                     checkpoint.record.sequence(),
                     progress.state == JobState::kRunning ? "running" : "ended", progress.epochs,
                     progress.photons);
        std::lock_guard lock(mutex_);
        if (jobs_.contains(id)) continue;
        jobs_[id] = *job;
        job_order_.push_back(id);
        next_id_ = std::max(next_id_, number(checkpoint) + 1);
        ++restored;
    }
    NotifyWork();
    return restored;
}

void Coordinator::EndSubmissionLocked(const std::string& owner) {
    if (--submitting_[owner] == 0) submitting_.erase(owner);
}

Clock::duration Coordinator::Duration(double seconds) const {
    return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

absl::StatusOr<JobProgress> Coordinator::Submit(JobRequest request) {
    const std::string owner = request.owner;
    {
        // Submissions being prepared count against the limits (they are checked here, the
        // job is added after its camera pass): concurrent submissions of one client must not
        // all pass (bench/farm_load saw a client run 3 jobs under a limit of 2).
        std::lock_guard lock(mutex_);
        size_t running = 0, owned = submitting_[owner];
        for (const auto& [submitting_owner, count] : submitting_) running += count;
        for (const auto& [id, job] : jobs_) {
            const bool job_running = job->Running();
            running += job_running;
            owned += job_running && job->Owner() == owner;
        }
        if (running >= options_.max_running_jobs ||
            owned >= options_.client_limits.max_jobs_per_client) {
            if (submitting_[owner] == 0) submitting_.erase(owner);
            if (running >= options_.max_running_jobs)
                return absl::ResourceExhaustedError(absl::StrCat("the coordinator runs ", running,
                                                                 " jobs, its limit (--max-jobs)"));
            return absl::ResourceExhaustedError(
                absl::StrCat("client '", owner, "' runs ", owned,
                             " jobs, this coordinator's limit (--max-jobs-per-client)"));
        }
        ++submitting_[owner];
    }
    const Clock::time_point submitted = Now();  // a job's clock includes its camera pass
    absl::StatusOr<PreparedJob> prepared = PrepareJob(std::move(request), options_);
    if (!prepared.ok()) {
        std::lock_guard lock(mutex_);
        EndSubmissionLocked(owner);
        return prepared.status();
    }
    prepared->checkpointed = checkpoints_ != nullptr;
    std::shared_ptr<Job> job;
    {
        std::lock_guard lock(mutex_);
        // An epoch's chunks are all the work there is until it is merged: fewer than the
        // workers' threads leave threads idle.
        uint64_t threads = 0;
        for (const auto& [id, worker] : workers_) threads += worker.registration.threads;
        const BatchLayout& layout = prepared->spec.layout;
        const uint64_t chunks = uint64_t{layout.batches_per_epoch} *
                                ChunkCount(MakeBatchSpec(layout, layout.GrowingEpochs(), 0, 0));
        if (GathersAtHitPoints(prepared->spec.integrator) && chunks < threads)
            prepared->warnings.push_back(
                absl::StrFormat("an epoch runs as %d chunks of photons but the workers have %d "
                                "threads, so at most %d of them "
                                "work at once: ask for more photons per epoch (batches_per_epoch x "
                                "photons_per_batch, %d photons "
                                "per chunk; see docs/farm.md)",
                                chunks, threads, chunks, kPhotonsPerChunk));
        const std::string id = absl::StrCat("job-", next_id_++, "-", id_salt_);
        job = std::make_shared<Job>(id, std::move(*prepared), submitted);
        EndSubmissionLocked(owner);
        jobs_[id] = job;
        job_order_.push_back(id);
        ForgetEndedJobsLocked();
    }
    if (checkpoints_) {  // before the client hears of it: a crash must not lose an accepted job
        std::lock_guard writer(checkpoint_mutex_);
        WriteCheckpointLocked(*job, true);
    }
    spdlog::info("job {} submitted", job->Id());
    for (const std::string& warning : job->Progress(Now()).warnings)
        spdlog::warn("job {}: {}", job->Id(), warning);
    NotifyWork();
    return job->Progress(Now());
}

absl::StatusOr<std::shared_ptr<Job>> Coordinator::FindJob(const std::string& job_id) const {
    std::lock_guard lock(mutex_);
    auto it = jobs_.find(job_id);
    if (it == jobs_.end())
        return absl::NotFoundError(absl::StrCat("job_id: no job '", job_id, "'"));
    return it->second;
}

absl::StatusOr<JobProgress> Coordinator::Cancel(const std::string& job_id,
                                                const std::string& reason) {
    absl::StatusOr<std::shared_ptr<Job>> job = FindJob(job_id);
    if (!job.ok()) return job.status();
    if ((*job)->Cancel(reason, Now())) spdlog::info("job {} cancelled: {}", job_id, reason);
    NotifyWork();
    if (checkpoints_) {
        std::lock_guard lock(mutex_);
        checkpoint_wake_.notify_all();
    }
    return (*job)->Progress(Now());
}

std::vector<JobProgress> Coordinator::ListJobs() const {
    std::lock_guard lock(mutex_);
    std::vector<JobProgress> jobs;
    for (const std::string& id : job_order_) jobs.push_back(jobs_.at(id)->Progress(Now()));
    return jobs;
}

void Coordinator::ForgetEndedJobsLocked() {
    size_t ended = 0;
    for (const std::string& id : job_order_)
        ended += jobs_.at(id)->Progress(Now()).state != JobState::kRunning;
    for (auto it = job_order_.begin();
         it != job_order_.end() && ended > options_.finished_jobs_kept;) {
        if (jobs_.at(*it)->Progress(Now()).state != JobState::kRunning) {
            if (checkpoints_) forgotten_.push_back(*it);
            shares_.erase(*it);
            jobs_.erase(*it);
            it = job_order_.erase(it);
            --ended;
        } else {
            ++it;
        }
    }
}

absl::StatusOr<std::string> Coordinator::RegisterWorker(const WorkerRegistration& registration) {
    if (registration.version != kPhotonfarmVersion)
        return absl::FailedPreconditionError(
            absl::StrCat("version: worker runs photonfarm ", registration.version,
                         ", the coordinator ", std::string(kPhotonfarmVersion)));
    std::lock_guard lock(mutex_);
    ReapWorkersLocked(Now());
    // Unguessable, since it is all a worker's later calls show: one worker cannot act for another.
    const std::string id = absl::StrCat("worker-", next_id_++, "-", RandomHex(16));
    workers_[id] = {registration, Now(), Now()};
    spdlog::info("worker {} registered ({}, {} threads, from {})", id, registration.backend,
                 registration.threads,
                 registration.peer.empty() ? "this process" : registration.peer);
    return id;
}

absl::Status Coordinator::Heartbeat(const std::string& worker_id) {
    std::lock_guard lock(mutex_);
    ReapWorkersLocked(Now());
    auto it = workers_.find(worker_id);
    if (it == workers_.end())
        return absl::NotFoundError(absl::StrCat("worker_id: unknown worker '", worker_id, "'"));
    it->second.last_seen = Now();
    return absl::OkStatus();
}

absl::StatusOr<uint32_t> Coordinator::UnregisterWorker(const std::string& worker_id) {
    std::lock_guard lock(mutex_);
    if (workers_.erase(worker_id) == 0)
        return absl::NotFoundError(absl::StrCat("worker_id: unknown worker '", worker_id, "'"));
    uint32_t returned = 0;
    for (const auto& [id, job] : jobs_) returned += job->ReleaseLeases(worker_id);
    spdlog::info("worker {} left, returning {} leases", worker_id, returned);
    WakeLeasesLocked(returned);
    return returned;
}

void Coordinator::ReapWorkersLocked(Clock::time_point now) {
    // Every lease and heartbeat comes here: a walk over every worker each time would cost
    // the coordinator workers x calls per second, so it walks a tenth of a timeout apart.
    if (now < next_reap_) return;
    next_reap_ = now + Duration(options_.worker_timeout_seconds / 10);
    for (auto it = workers_.begin(); it != workers_.end();) {
        if (now - it->second.last_seen > Duration(options_.worker_timeout_seconds)) {
            uint32_t released = 0;
            for (const auto& [id, job] : jobs_) released += job->ReleaseLeases(it->first);
            spdlog::warn("worker {} silent for {:.0f} s: gone; {} leases handed out again",
                         it->first, options_.worker_timeout_seconds, released);
            it = workers_.erase(it);
            WakeLeasesLocked(released);
        } else {
            ++it;
        }
    }
}

std::vector<WorkerView> Coordinator::ListWorkers() const {
    std::lock_guard lock(mutex_);
    const Clock::time_point now = Now();
    std::vector<WorkerView> views;
    for (const auto& [id, worker] : workers_) {
        WorkerView view{id,
                        worker.registration,
                        std::chrono::duration<double>(now - worker.last_seen).count(),
                        std::chrono::duration<double>(now - worker.registered).count(),
                        0,
                        worker.batches_done,
                        worker.photons_reported};
        for (const auto& [job_id, job] : jobs_) view.batches_leased += job->LeasedBy(id, now);
        views.push_back(std::move(view));
    }
    return views;
}

double PriorityWeight(int priority) {
    return std::ldexp(1.0, std::clamp(priority, -kPriorityWeightRange, kPriorityWeightRange));
}

std::shared_ptr<Job> Coordinator::PickJobLocked(Clock::time_point now) {
    // Weighted fair sharing of the workers (start-time fair queueing): each job counts the
    // photons it was leased divided by its weight, 2^priority, and the job that would stand
    // lowest after one more batch goes next. So while jobs have batches to hand out, one of
    // priority p + 1 is leased twice the photons of one of priority p, and none waits for
    // another to finish. A job without batches to hand out (at its epoch's end, or new) rejoins
    // at the least count among those that kept theirs: it earns no credit while it waits.
    struct Candidate {
        std::shared_ptr<Job> job;
        Job::LeaseLoad load;
        JobShare* share;
    };
    std::vector<Candidate> candidates;
    double floor = std::numeric_limits<double>::infinity();
    for (const std::string& id : job_order_) {  // oldest first: ties go to the older job
        const std::shared_ptr<Job>& job = jobs_.at(id);
        JobShare& share = shares_[id];
        const Job::LeaseLoad load = job->Load(now);
        if (load.leasable == 0) {
            share.active = false;
            continue;
        }
        if (share.active) floor = std::min(floor, share.weighted_photons);
        candidates.push_back({job, load, &share});
    }
    if (std::isfinite(floor)) share_floor_ = std::max(share_floor_, floor);
    std::shared_ptr<Job> best;
    double best_finish = 0;
    for (const Candidate& candidate : candidates) {
        JobShare& share = *candidate.share;
        if (!share.active) share.weighted_photons = std::max(share.weighted_photons, share_floor_);
        share.active = true;
        const double finish =
            share.weighted_photons +
            candidate.load.batch_photons / PriorityWeight(candidate.job->Priority());
        if (!best || finish < best_finish) {
            best = candidate.job;
            best_finish = finish;
        }
    }
    return best;
}

absl::StatusOr<CoordinatorLease> Coordinator::Lease(const std::string& worker_id, uint32_t chunks,
                                                    double wait_seconds) {
    std::unique_lock lock(mutex_);
    const Clock::time_point until = Clock::now() + Duration(wait_seconds);
    CoordinatorLease lease;
    lease.lease_seconds = options_.lease_seconds;
    while (true) {
        const Clock::time_point now = Now();
        ReapWorkersLocked(now);
        auto worker = workers_.find(worker_id);
        if (worker == workers_.end())
            return absl::NotFoundError(absl::StrCat("worker_id: unknown worker '", worker_id, "'"));
        worker->second.last_seen = now;
        if (std::shared_ptr<Job> job = PickJobLocked(now)) {
            Job::Lease granted =
                job->LeaseBatches(worker_id, chunks, now, now + Duration(options_.lease_seconds));
            if (!granted.batches.empty()) {
                uint64_t photons = 0;
                for (const BatchSpec& spec : granted.batches) photons += spec.photons;
                shares_[job->Id()].weighted_photons += photons / PriorityWeight(job->Priority());
                lease.grant = {job->Id(),
                               std::move(granted.payload),
                               granted.epoch->epoch,
                               granted.epoch->regions,
                               std::move(granted.batches),
                               granted.epoch->hit_points};
                lease.epoch = std::move(granted.epoch);
                lease.job = std::move(job);
                return lease;
            }
        }
        // Looked once more after the wait ends, timed out or not: a wake-up meant for this
        // thread may come as it times out (WakeLeasesLocked wakes one waiter per new batch).
        if (shut_down_ || Clock::now() >= until) return lease;
        ++lease_waiters_;
        work_available_.wait_until(lock, until);
        --lease_waiters_;
    }
}

absl::StatusOr<TallyVerdict> Coordinator::Report(const std::string& worker_id,
                                                 const std::string& job_id, BatchResult result) {
    std::shared_ptr<Job> job;
    {
        std::lock_guard lock(mutex_);
        auto worker = workers_.find(worker_id);
        if (worker == workers_.end()) {
            ++refusals_.unknown_worker;
            return absl::NotFoundError(
                absl::StrCat("worker_id: unknown worker '", worker_id, "'; register again"));
        }
        worker->second.last_seen = Now();
        ++worker->second.batches_done;
        worker->second.photons_reported += result.photons_emitted;
        auto it = jobs_.find(job_id);
        if (it == jobs_.end()) {
            ++refusals_.job_gone;
            return TallyVerdict::kJobGone;
        }
        job = it->second;
    }
    const uint64_t photons = result.photons_emitted;
    const auto start = Clock::now();
    absl::StatusOr<Job::ReportOutcome> outcome = job->Report(worker_id, std::move(result), Now());
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    std::lock_guard lock(mutex_);
    if (outcome.ok() && outcome->verdict == TallyVerdict::kAccepted) {
        photons_accepted_ += photons;
        if (merge_observer_) merge_observer_(seconds);
    }
    if (!outcome.ok()) {
        ++refusals_.malformed;
        return outcome.status();
    }
    switch (outcome->verdict) {
        case TallyVerdict::kAccepted:
            break;
        case TallyVerdict::kDuplicate:
            ++refusals_.duplicate;
            break;
        case TallyVerdict::kStale:
            ++refusals_.stale;
            break;
        case TallyVerdict::kJobGone:
            ++refusals_.job_gone;
            break;
        case TallyVerdict::kNotLeased:
            ++refusals_.not_leased;
            break;
    }
    if (outcome->epoch_finished) {
        WakeLeasesLocked(job->Leasable(Now()));
        if (checkpoints_ && !job->Running()) checkpoint_wake_.notify_all();  // its final state, now
    }
    return outcome->verdict;
}

void Coordinator::CountMalformed() {
    std::lock_guard lock(mutex_);
    ++refusals_.malformed;
}

RefusalCounts Coordinator::Refusals() const {
    std::lock_guard lock(mutex_);
    return refusals_;
}

uint64_t Coordinator::PhotonsAccepted() const {
    std::lock_guard lock(mutex_);
    return photons_accepted_;
}

void Coordinator::SetMergeObserver(std::function<void(double seconds)> observer) {
    std::lock_guard lock(mutex_);
    merge_observer_ = std::move(observer);
}

std::shared_ptr<const Blob> Coordinator::FindBlob(const std::string& digest) const {
    std::vector<std::shared_ptr<Job>> jobs;
    {
        std::lock_guard lock(mutex_);
        for (const auto& [id, job] : jobs_) jobs.push_back(job);
    }
    for (const std::shared_ptr<Job>& job : jobs)
        if (std::shared_ptr<const Blob> blob = job->FindBlob(digest)) return blob;
    return nullptr;
}

void Coordinator::NotifyWork() {
    std::lock_guard lock(mutex_);
    work_available_.notify_all();
}

void Coordinator::WakeLeasesLocked(uint64_t batches) {
    if (batches >= lease_waiters_) return work_available_.notify_all();
    for (uint64_t i = 0; i < batches; ++i) work_available_.notify_one();
}

void Coordinator::Shutdown() {
    std::lock_guard lock(mutex_);
    shut_down_ = true;
    work_available_.notify_all();
}

}  // namespace pf
