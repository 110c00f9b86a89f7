// The coordinator: jobs and workers, with no transport. Clients submit, watch and cancel jobs;
// workers register, lease batches and report results. The gRPC services (jobs_service.h,
// work_service.h) and the embedded renderer (in_process_source.h) both drive this class, so
// the farm and `photonfarm render` share one path. Thread-safe.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "absl/status/statusor.h"
#include "core/job/job_spec.h"
#include "core/job/work_source.h"
#include "core/scene/mesh_builder.h"
#include "core/scene/scene_bundle.h"
#include "server/checkpoint_store.h"
#include "server/job.h"

namespace pf {

// A job's weight in the lease choice: 2^priority, priorities beyond +-kPriorityWeightRange
// weighing as those bounds (docs/farm.md, "Scheduling and failures").
inline constexpr int kPriorityWeightRange = 30;
double PriorityWeight(int priority);

// Limits on what one client may ask of the coordinator; over one, RESOURCE_EXHAUSTED naming
// the coordinator's flag. The scene's own limits (triangles, textures) are SceneLimits.
struct ClientLimits {
    size_t max_jobs_per_client = 16;     // running at once, per client (token name or address)
    uint32_t max_watchers_per_job = 64;  // snapshot streams open at once on one job
    uint64_t max_bundle_bytes = kMaxBundleBytes;     // a scene with every file it references
    uint64_t max_render_pixels = uint64_t{1} << 24;  // width x height of a job's image
    uint32_t max_photons_per_batch = kMaxPhotonsPerBatch;
};

struct CoordinatorOptions {
    double heartbeat_seconds = 2;  // workers heartbeat this often
    double worker_timeout_seconds =
        10;                         // a worker silent this long is gone; its leases are re-handed
    double lease_seconds = 300;     // a batch not reported within this is handed out again
    double lease_wait_seconds = 1;  // a lease request waits this long for work to appear
    size_t max_running_jobs = 64;
    size_t finished_jobs_kept = 64;  // ended jobs (their final images) kept for GetResult
    // How errors name a job's settings: the farm's fields, or the embedded renderer's flags.
    SettingNames setting_names = SettingNames::kFields;
    // What a submitted scene may build (triangles, image sizes); over it, RESOURCE_EXHAUSTED.
    SceneLimits scene_limits;
    ClientLimits client_limits;
    // Checkpoints: every job's state is written here (checkpoint_store.h) every
    // `checkpoint_seconds`, when it ends and at shutdown; RestoreCheckpoints reads them back.
    // Empty: none.
    std::string checkpoint_dir;
    double checkpoint_seconds = 30;
    std::function<Clock::time_point()> now = [] { return Clock::now(); };  // tests drive time
};

struct JobRequest {
    std::string name;  // for listings; the main file's name if empty
    std::string
        owner;  // who submitted it, for the per-client limits: a token's name, or an address
    SceneBundle bundle;
    JobSpec spec;
    int priority = 0;  // higher first; equal priorities share workers fairly
    // When set, every epoch's image is measured against it for the convergence log; its size
    // must be the job's.
    std::shared_ptr<const Image> reference;
};

struct WorkerView {
    std::string worker_id;
    WorkerRegistration registration;
    double seconds_since_heartbeat = 0;
    double seconds_registered = 0;
    uint32_t batches_leased = 0;
    uint64_t batches_done = 0;      // results reported, accepted or not
    uint64_t photons_reported = 0;  // in those results
};

// Tallies refused, by reason, since the coordinator started.
struct RefusalCounts {
    uint64_t duplicate = 0, stale = 0, job_gone = 0, unknown_worker = 0, malformed = 0,
             not_leased = 0;
};

// A lease as the coordinator hands it out: the grant, and the job for its blobs.
struct CoordinatorLease {
    WorkGrant grant;
    std::shared_ptr<Job> job;                  // null when no work
    std::shared_ptr<const EpochInputs> epoch;  // null when no work
    double lease_seconds = 0;
};

class Coordinator {
public:
    explicit Coordinator(CoordinatorOptions options = {});
    ~Coordinator();

    const CoordinatorOptions& Options() const { return options_; }

    // Jobs. Submit loads the scene and runs the camera pass (on the calling TBB arena) before
    // it returns: INVALID_ARGUMENT for a bad scene or settings, naming the file or field.
    absl::StatusOr<JobProgress> Submit(JobRequest request);
    absl::StatusOr<std::shared_ptr<Job>> FindJob(const std::string& job_id) const;  // NOT_FOUND
    absl::StatusOr<JobProgress> Cancel(const std::string& job_id,
                                       const std::string& reason = "cancelled by a client");
    std::vector<JobProgress> ListJobs() const;

    // Workers. An unknown worker id is NOT_FOUND: the worker registers again.
    absl::StatusOr<std::string> RegisterWorker(const WorkerRegistration& registration);
    absl::Status Heartbeat(const std::string& worker_id);
    absl::StatusOr<uint32_t> UnregisterWorker(const std::string& worker_id);  // leases returned
    std::vector<WorkerView> ListWorkers() const;
    // Batches of one job covering about `chunks` chunks (at least one batch), of the job
    // holding the fewest photons out for its weight (PriorityWeight); waits up to
    // `wait_seconds` for work when there is none.
    absl::StatusOr<CoordinatorLease> Lease(const std::string& worker_id, uint32_t chunks,
                                           double wait_seconds);
    absl::StatusOr<TallyVerdict> Report(const std::string& worker_id, const std::string& job_id,
                                        BatchResult result);
    // A tally that failed to decode, counted with the refusals.
    void CountMalformed();
    RefusalCounts Refusals() const;
    // Photons in accepted reports since the coordinator started (each merged in its turn).
    uint64_t PhotonsAccepted() const;
    // Called with the seconds each accepted report took to be stored and merged (the batches
    // it made ready folded, the epoch finished if it was the last). Set before serving.
    void SetMergeObserver(std::function<void(double seconds)> observer);

    // A blob of a running job (scene, hit points, radii) by digest, or null.
    std::shared_ptr<const Blob> FindBlob(const std::string& digest) const;

    // Wakes every waiting lease; later waits return at once. For shutting down.
    void Shutdown();

    // Resumes the jobs checkpointed in options.checkpoint_dir (a coordinator that crashed or
    // stopped there): running ones go on where their checkpoint left them, ended ones keep
    // their final image. Call before serving. Returns how many jobs came back; a checkpoint
    // that cannot be read or loaded is logged and skipped.
    size_t RestoreCheckpoints();
    // Writes every job's checkpoint now (also done by the destructor, after the last fold).
    void WriteCheckpoints();

private:
    struct Worker {
        WorkerRegistration registration;
        Clock::time_point registered, last_seen;
        uint64_t batches_done = 0, photons_reported = 0;
    };
    Clock::time_point Now() const { return options_.now(); }
    Clock::duration Duration(double seconds) const;
    void ReapWorkersLocked(Clock::time_point now);
    void ForgetEndedJobsLocked();
    // A submission of `owner`'s, counted against the limits while it was prepared, is over.
    void EndSubmissionLocked(const std::string& owner);
    std::shared_ptr<Job> PickJobLocked(Clock::time_point now);
    void NotifyWork();  // wakes every waiting lease (a job came, went or changed)
    // Wakes a waiting lease per batch that became leasable (all of them when there are more
    // batches than waiters), not every waiter at every epoch's end.
    void WakeLeasesLocked(uint64_t batches);

    // The checkpoint thread: writes each running job every checkpoint_seconds and each ended
    // one once, and removes forgotten jobs' folders.
    void CheckpointLoop();
    // Ended jobs' final states and, when `running_too`, running jobs' current ones.
    void WriteCheckpoints(bool running_too);
    // The same for one job, under checkpoint_mutex_.
    void WriteCheckpointLocked(Job& job, bool running_too);

    const CoordinatorOptions options_;
    std::unique_ptr<CheckpointStore> checkpoints_;  // null without a checkpoint folder
    std::mutex checkpoint_mutex_;                   // one writer at a time
    std::vector<std::string> forgotten_;       // ended jobs whose checkpoints go (under mutex_)
    std::condition_variable checkpoint_wake_;  // with mutex_
    bool checkpoints_stopping_ = false;        // under mutex_
    std::thread checkpoint_thread_;
    mutable std::mutex mutex_;
    std::condition_variable work_available_;
    uint64_t lease_waiters_ = 0;     // leases waiting on work_available_
    Clock::time_point next_reap_{};  // ReapWorkersLocked walks the workers again from then
    std::map<std::string, std::shared_ptr<Job>> jobs_;  // by id
    std::map<std::string, size_t> submitting_;          // submissions being prepared, by owner
    std::vector<std::string> job_order_;  // submission order, for fairness ties and listings
    // The lease choice's state (PickJobLocked), by job id.
    struct JobShare {
        double weighted_photons = 0;  // photons leased / PriorityWeight, from where it joined
        bool active = false;          // it had batches to hand out at the last choice
    };
    std::map<std::string, JobShare> shares_;
    double share_floor_ = 0;  // where a job (re)joins: the least count among those that stayed
    std::map<std::string, Worker> workers_;
    RefusalCounts refusals_;
    uint64_t photons_accepted_ = 0;
    std::function<void(double)> merge_observer_;
    uint64_t next_id_ = 1;
    std::string id_salt_;
    bool shut_down_ = false;
};

}  // namespace pf
