// One render job on the coordinator: its inputs (shared in memory with in-process workers,
// served as content-addressed blobs to remote ones), the current epoch's batch slots and
// their leases, and the progressive estimate the results fold into. Thread-safe.
//
// Determinism: a result for a slot is accepted once, from whoever delivers it first (every
// worker computes the same bytes for a batch), and results fold into the estimate strictly in
// batch-index order, so the image for a seed and layout does not depend on who ran what.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"
#include "core/estimate/convergence.h"
#include "core/estimate/estimate.h"
#include "core/film/film_response.h"
#include "core/film/image.h"
#include "core/job/job_progress.h"
#include "core/job/job_spec.h"
#include "core/job/work_source.h"
#include "core/scene/scene_bundle.h"
#include "core/scene_io/scene_loader.h"
#include "server/checkpoint_store.h"
#include "wire/blob_codec.h"

namespace pf {

using Clock = std::chrono::steady_clock;

inline double Seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

// A blob encoded on first use, once, whichever thread asks first; or one given ready.
class LazyBlob {
public:
    explicit LazyBlob(std::function<std::string()> encode) : encode_(std::move(encode)) {}
    explicit LazyBlob(Blob blob) : blob_(std::move(blob)), encoded_(true) {}
    const Blob& Get() const;
    const Blob* IfEncoded() const {
        return encoded_.load(std::memory_order_acquire) ? &blob_ : nullptr;
    }

private:
    std::function<std::string()> encode_;
    mutable std::once_flag once_;
    mutable Blob blob_;
    mutable std::atomic<bool> encoded_{false};
};

// The inputs of one epoch's photon pass: the squared search radii.
struct EpochInputs {
    explicit EpochInputs(uint64_t epoch_in, GatherRegions regions_in);
    uint64_t epoch;
    std::shared_ptr<const GatherRegions> regions;
    LazyBlob blob;  // EncodeGatherRegions(regions)
    // sppm: the epoch's camera pass's hit points (WorkGrant::epoch_hit_points); null for the
    // others.
    std::shared_ptr<const std::vector<HitPoint>> hit_points;
};

// What a job's constructor needs: prepared by Coordinator::Submit (scene loaded, camera pass run).
struct PreparedJob {
    std::string name, owner;
    JobSpec spec;
    int priority = 0;
    SceneBundle bundle;
    std::shared_ptr<const JobPayload> payload;
    std::unique_ptr<Estimate> estimate;
    std::vector<std::string> warnings;
    std::shared_ptr<const Image> reference;  // measured against after every epoch, when set
    std::string scene_features;              // SceneFeatures::ToString of the scene
    // The coordinator keeps checkpoints: the job's final state is kept for one when it ends
    // (TakeFinalCheckpoint).
    bool checkpointed = false;
    // A job restored from a checkpoint: the fixed parts it named (the scene bundle's bytes, the
    // estimate's fixed part or null), so that the job's later checkpoints name the same files.
    std::shared_ptr<const Blob> checkpointed_scene, checkpointed_estimate;
};

class Job {
public:
    // `submitted`: when the job arrived, the start of its clock (the camera pass counts).
    Job(std::string id, PreparedJob prepared, Clock::time_point submitted);

    const std::string& Id() const { return id_; }
    const std::string& Owner() const { return owner_; }
    int Priority() const { return priority_; }
    Integrator Kind() const { return spec_.integrator; }
    // Its settings, the film size and layout resolved (PrepareJob).
    const JobSpec& Spec() const { return spec_; }
    // The hit points batches gather at (0 for the integrators that render pixels).
    uint64_t HitPointCount() const { return hit_point_count_; }
    // What a batch's sample slice indexes, in the job's largest epoch: the slots of its camera
    // pass, or pixels (Estimate::ItemCount). A slice of a given epoch is checked against the
    // epoch's own batches when its result is folded.
    uint64_t ItemCount() const { return item_count_; }
    bool Running() const;

    // Snapshot streams open on this job: AddWatcher is false when `limit` are open already.
    bool AddWatcher(uint32_t limit);
    void RemoveWatcher();

    // Blobs a remote worker fetches: the prepared scene (EncodeSceneBlob: what tracing needs,
    // parsed here once) and the hit points. Null once the job has ended.
    std::shared_ptr<const LazyBlob> SceneBlob() const;
    std::shared_ptr<const LazyBlob> HitPointsBlob() const;
    // The blob with this digest among the job's encoded ones (scene, hit points, current
    // radii), or null.
    std::shared_ptr<const Blob> FindBlob(const std::string& digest) const;

    struct Lease {
        std::shared_ptr<const JobPayload> payload;
        std::shared_ptr<const EpochInputs> epoch;
        std::vector<BatchSpec> batches;
    };
    // Slots that may be leased now: neither reported nor under a live lease.
    uint32_t Leasable(Clock::time_point now) const;
    // What the lease choice weighs (Coordinator::PickJobLocked), in one look: the slots
    // leasable now and a batch's photons this epoch.
    struct LeaseLoad {
        uint32_t leasable = 0;
        uint32_t batch_photons = 0;
    };
    LeaseLoad Load(Clock::time_point now) const;
    uint32_t Leased(Clock::time_point now) const;  // under a live lease
    uint32_t LeasedBy(const std::string& worker, Clock::time_point now) const;
    // Leases slots to `worker` until `deadline`, lowest index first, until their chunks cover
    // `chunks` (at least one slot).
    Lease LeaseBatches(const std::string& worker, uint32_t chunks, Clock::time_point now,
                       Clock::time_point deadline);
    // A worker that left or went silent: its slots may be leased again at once.
    uint32_t ReleaseLeases(const std::string& worker);

    struct ReportOutcome {
        TallyVerdict verdict;
        bool epoch_finished = false;  // new work exists (or the job ended)
    };
    // A result for a slot of the current epoch, accepted once. INVALID_ARGUMENT when its spec
    // does not match the slot's (a forged or corrupted result), or it names hit points the job
    // does not have.
    absl::StatusOr<ReportOutcome> Report(const std::string& worker, BatchResult result,
                                         Clock::time_point now);

    // Ends a running job; its image as of the last merged epoch stays. False if already ended.
    bool Cancel(const std::string& reason, Clock::time_point now);

    // Checkpoints (job_checkpoint.cpp). A running job's state now, between two folds: its
    // record and estimate, copied under the job's locks (written by the caller, outside them).
    // FAILED_PRECONDITION once the job has ended; ALREADY_EXISTS when nothing was folded since
    // the last one.
    absl::StatusOr<JobCheckpointData> Checkpoint(Clock::time_point now);
    // An ended job's last state, once, for a job with PreparedJob::checkpointed.
    std::optional<JobCheckpointData> TakeFinalCheckpoint();
    // A job as a checkpoint left it: running jobs go on from the state saved (the epoch's
    // batches folded before it are not handed out again), ended ones hold their final image.
    // DATA_LOSS or the scene's load error when the checkpoint cannot be such a job.
    static absl::StatusOr<std::shared_ptr<Job>> Restore(const JobCheckpointData& checkpoint,
                                                        const SceneLimits& limits,
                                                        Clock::time_point now);

    JobProgress Progress(Clock::time_point now) const;
    // Changes with every merged epoch and state change; WaitForChange returns the current
    // version once it differs from `seen`, or at `until`.
    uint64_t Version() const;
    uint64_t WaitForChange(uint64_t seen, Clock::time_point until) const;
    // The image as of the last merged epoch (resolved once per epoch however many ask).
    std::shared_ptr<const Image> CurrentImage() const;
    // One point per merged epoch: seconds, photons, the estimated error and, with a reference,
    // the measured one.
    std::vector<ConvergencePoint> Convergence() const;
    bool HasReference() const { return reference_ != nullptr; }

private:
    struct Slot {
        BatchSpec spec;
        std::pair<uint64_t, uint64_t> emission_shape;  // Estimate::EmissionShape of spec
        std::string worker;                            // holding the lease
        std::vector<std::string>
            lessees;  // every worker that held it this epoch: who may report it
        Clock::time_point deadline{};
        bool leased = false;
        std::optional<BatchResult> result;  // reported, waiting for its turn to fold
        bool folded = false;
    };
    bool LeasableLocked(const Slot& slot, Clock::time_point now) const;
    void StartEpochLocked(GatherRegions regions);
    // Folds the results that are next in order, and finishes the epoch when all are in.
    // Called by the thread that stored a result; one thread folds at a time.
    bool FoldReadyLocked(std::unique_lock<std::mutex>& lock, Clock::time_point now);
    void EndLocked(JobState state, std::string message, Clock::time_point now);
    // The checkpoint record as of now, with the scene as a fixed part (not the estimate);
    // under mutex_.
    JobCheckpointData RecordLocked(Clock::time_point now);
    // Adds the estimate's state and its fixed part (saved once per job) to `checkpoint`;
    // under estimate_mutex_, with the estimate alive.
    void SaveEstimateLocked(JobCheckpointData& checkpoint);
    void ReleaseInputs();  // after the end: keep the final image, free the rest
    // Under estimate_mutex_, with the estimate alive. Resolves the current epoch's image into
    // image_ unless done already.
    void ResolveLocked() const;
    // The current image against the reference; none without one.
    std::optional<ImageDifference> MeasureLocked() const;

    const std::string id_;
    const std::string name_;
    const std::string owner_;
    const JobSpec spec_;
    const int priority_;
    const Clock::time_point started_;
    const uint64_t hit_point_count_;  // 0 for the integrators that render pixels
    const uint64_t item_count_;       // the most a batch's sample slice indexes (ItemCount)
    const double initial_radius_;
    const std::string scene_features_;
    const std::shared_ptr<const Image> reference_;

    std::atomic<uint32_t> watchers_{0};

    mutable std::mutex mutex_;  // guards everything below but the estimate and image
    mutable std::condition_variable changed_;
    JobState state_ = JobState::kRunning;
    std::string message_;
    std::vector<std::string> warnings_;  // from submission, and one if no light reached anything
    Clock::time_point ended_{};
    uint64_t version_ = 0;
    uint64_t epochs_merged_ = 0, photons_merged_ = 0, nonfinite_discarded_ = 0, camera_samples_ = 0;
    std::optional<double> estimated_error_;
    std::optional<ImageDifference> measured_error_;  // the last point's, with a reference
    ConvergenceLog convergence_;
    std::shared_ptr<const JobPayload> payload_;
    // What the film makes of the estimate (the scene's; kept apart from the payload, which is
    // released when the job ends, before its last image is resolved).
    FilmResponse film_;
    std::shared_ptr<const LazyBlob> scene_blob_, hit_points_blob_;
    std::shared_ptr<const EpochInputs> epoch_;
    std::vector<Slot> slots_;
    uint32_t next_fold_ = 0;
    bool folding_ = false;
    std::map<std::string, Clock::time_point> workers_seen_;
    // Checkpoints: the scene a record holds (kept past the job's end until its final state is
    // taken), the record's sequence number, and the final state once the job has ended.
    const bool checkpointed_;
    std::shared_ptr<const LazyBlob> durable_scene_;
    uint64_t checkpoint_sequence_ = 0;
    // The estimate's (epoch, batches folded) at the last checkpoint: an idle job is not
    // written again. Under estimate_mutex_.
    std::pair<uint64_t, uint32_t> checkpointed_at_{UINT64_MAX, 0};
    std::optional<JobCheckpointData> final_checkpoint_;

    mutable std::mutex estimate_mutex_;   // guards the estimate, its fixed part and the image cache
    std::unique_ptr<Estimate> estimate_;  // null once the job has ended
    // The estimate's fixed part (Estimate::SaveFixed), saved with the first checkpoint; null
    // where it has none.
    std::shared_ptr<const Blob> fixed_estimate_;
    bool fixed_estimate_saved_ = false;
    mutable std::shared_ptr<const Image> image_;
    mutable uint64_t image_epoch_ = UINT64_MAX;
};

}  // namespace pf
