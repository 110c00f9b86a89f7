// Slots, leases and the in-order fold of one job.
#include "server/job.h"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "absl/strings/str_cat.h"
#include "wire/proto_convert.h"

namespace pf {
namespace {

// A worker counts as active on a job while it holds a lease or reported within this long.
constexpr auto kActiveWindow = std::chrono::seconds(10);

bool SameSpec(const BatchSpec& a, const BatchSpec& b) {
    return a.index == b.index && a.epoch == b.epoch && a.photons == b.photons &&
           a.sample_begin == b.sample_begin && a.sample_end == b.sample_end;
}

}  // namespace

const Blob& LazyBlob::Get() const {
    if (const Blob* blob = IfEncoded()) return *blob;
    std::call_once(once_, [this] {
        blob_ = Blob::Of(encode_());
        encoded_.store(true, std::memory_order_release);
    });
    return blob_;
}

EpochInputs::EpochInputs(uint64_t epoch_in, GatherRegions regions_in)
    : epoch(epoch_in),
      regions(std::make_shared<const GatherRegions>(std::move(regions_in))),
      blob([regions = regions] { return EncodeGatherRegions(*regions); }) {}

Job::Job(std::string id, PreparedJob prepared, Clock::time_point submitted)
    : id_(std::move(id)),
      name_(std::move(prepared.name)),
      owner_(std::move(prepared.owner)),
      spec_(prepared.spec),
      priority_(prepared.priority),
      started_(submitted),
      hit_point_count_(GathersAtHitPoints(prepared.estimate->Kind())
                           ? prepared.estimate->SharedHitPoints()->size()
                           : 0),
      item_count_(GathersAtHitPoints(prepared.estimate->Kind())
                      ? uint64_t(prepared.spec.width) * uint64_t(prepared.spec.height) *
                            uint64_t(MaxEpochSamplesPerPixel(prepared.spec)) *
                            SlotsPerCameraSample(prepared.spec)
                      : prepared.estimate->ItemCount()),
      initial_radius_(prepared.estimate->InitialRadius()),
      scene_features_(std::move(prepared.scene_features)),
      reference_(std::move(prepared.reference)),
      payload_(std::move(prepared.payload)),
      film_(payload_ ? payload_->scene.film : FilmResponse{}),
      checkpointed_(prepared.checkpointed),
      estimate_(std::move(prepared.estimate)),
      fixed_estimate_(std::move(prepared.checkpointed_estimate)),
      fixed_estimate_saved_(fixed_estimate_ != nullptr) {
    // Workers get the prepared scene (parsed here once); checkpoints keep the bundle, which a
    // restarted coordinator parses again.
    scene_blob_ = std::make_shared<const LazyBlob>(
        [payload = payload_] { return EncodeSceneBlob(payload->scene); });
    hit_points_blob_ = std::make_shared<const LazyBlob>(
        [payload = payload_] { return EncodeHitPoints(*payload->hit_points); });
    if (checkpointed_ && prepared.checkpointed_scene)
        durable_scene_ = std::make_shared<const LazyBlob>(*prepared.checkpointed_scene);
    else if (checkpointed_)
        durable_scene_ = std::make_shared<const LazyBlob>(
            [bundle = std::make_shared<const SceneBundle>(std::move(prepared.bundle))] {
                return ToProto(*bundle).SerializeAsString();
            });
    std::lock_guard lock(mutex_);
    warnings_ = std::move(prepared.warnings);
    StartEpochLocked(estimate_->Regions());
}

std::shared_ptr<const LazyBlob> Job::SceneBlob() const {
    std::lock_guard lock(mutex_);
    return scene_blob_;
}

std::shared_ptr<const LazyBlob> Job::HitPointsBlob() const {
    std::lock_guard lock(mutex_);
    return hit_points_blob_;
}

std::shared_ptr<const Blob> Job::FindBlob(const std::string& digest) const {
    std::lock_guard lock(mutex_);
    if (state_ != JobState::kRunning) return nullptr;
    // Only blobs already encoded can have been announced to a worker, so none is encoded here.
    auto match = [&](const std::shared_ptr<const void>& owner,
                     const LazyBlob& lazy) -> std::shared_ptr<const Blob> {
        const Blob* blob = lazy.IfEncoded();
        return blob != nullptr && blob->digest == digest ? std::shared_ptr<const Blob>(owner, blob)
                                                         : nullptr;
    };
    for (const std::shared_ptr<const LazyBlob>& lazy : {scene_blob_, hit_points_blob_})
        if (std::shared_ptr<const Blob> blob = match(lazy, *lazy)) return blob;
    return match(epoch_, epoch_->blob);
}

void Job::StartEpochLocked(GatherRegions regions) {
    const uint64_t epoch = estimate_->Epoch();
    auto inputs = std::make_shared<EpochInputs>(epoch, std::move(regions));
    if (TracesHitPointsEachEpoch(estimate_->Kind()))
        inputs->hit_points = estimate_->SharedHitPoints();
    epoch_ = std::move(inputs);
    slots_.clear();
    for (const BatchSpec& spec : estimate_->EpochBatches())
        slots_.push_back({spec, estimate_->EmissionShape(spec)});
    // A job restored from a checkpoint may have folded some of the epoch's batches already.
    next_fold_ = estimate_->BatchesFolded();
    for (uint32_t i = 0; i < next_fold_; ++i) slots_[i].folded = true;
}

bool Job::LeasableLocked(const Slot& slot, Clock::time_point now) const {
    return !slot.folded && !slot.result && (!slot.leased || slot.deadline <= now);
}

uint32_t Job::Leasable(Clock::time_point now) const {
    std::lock_guard lock(mutex_);
    if (state_ != JobState::kRunning) return 0;
    return static_cast<uint32_t>(std::count_if(
        slots_.begin(), slots_.end(), [&](const Slot& s) { return LeasableLocked(s, now); }));
}

Job::LeaseLoad Job::Load(Clock::time_point now) const {
    std::lock_guard lock(mutex_);
    LeaseLoad load;
    if (state_ != JobState::kRunning) return load;
    for (const Slot& slot : slots_) {
        load.batch_photons = slot.spec.photons;
        load.leasable += LeasableLocked(slot, now);
    }
    return load;
}

uint32_t Job::Leased(Clock::time_point now) const {
    std::lock_guard lock(mutex_);
    return static_cast<uint32_t>(std::count_if(slots_.begin(), slots_.end(), [&](const Slot& s) {
        return s.leased && !s.result && !s.folded && s.deadline > now;
    }));
}

uint32_t Job::LeasedBy(const std::string& worker, Clock::time_point now) const {
    std::lock_guard lock(mutex_);
    return static_cast<uint32_t>(std::count_if(slots_.begin(), slots_.end(), [&](const Slot& s) {
        return s.leased && s.worker == worker && !s.result && !s.folded && s.deadline > now;
    }));
}

Job::Lease Job::LeaseBatches(const std::string& worker, uint32_t chunks, Clock::time_point now,
                             Clock::time_point deadline) {
    std::lock_guard lock(mutex_);
    Lease lease;
    if (state_ != JobState::kRunning) return lease;
    uint64_t granted = 0;
    for (Slot& slot : slots_) {
        if (granted >= chunks) break;
        if (!LeasableLocked(slot, now)) continue;
        granted += ChunkCount(slot.spec);
        slot.leased = true;
        slot.worker = worker;
        slot.deadline = deadline;
        if (std::find(slot.lessees.begin(), slot.lessees.end(), worker) == slot.lessees.end())
            slot.lessees.push_back(worker);
        lease.batches.push_back(slot.spec);
    }
    if (!lease.batches.empty()) {
        lease.payload = payload_;
        lease.epoch = epoch_;
        workers_seen_[worker] = now;
    }
    return lease;
}

uint32_t Job::ReleaseLeases(const std::string& worker) {
    std::lock_guard lock(mutex_);
    uint32_t released = 0;
    for (Slot& slot : slots_)
        if (slot.leased && slot.worker == worker && !slot.result && !slot.folded) {
            slot.leased = false;
            ++released;
        }
    workers_seen_.erase(worker);
    return released;
}

absl::StatusOr<Job::ReportOutcome> Job::Report(const std::string& worker, BatchResult result,
                                               Clock::time_point now) {
    std::unique_lock lock(mutex_);
    if (state_ != JobState::kRunning) return ReportOutcome{TallyVerdict::kJobGone};
    const uint64_t epoch = epoch_->epoch;
    const uint64_t first = epoch * spec_.layout.batches_per_epoch;
    // Another epoch's result: one merged already, or one from before the coordinator restarted
    // from a checkpoint (whose epochs may run ahead of the one resumed).
    if (result.spec.epoch != epoch) return ReportOutcome{TallyVerdict::kStale};
    if (result.spec.index < first || result.spec.index - first >= slots_.size())
        return absl::InvalidArgumentError(
            absl::StrCat("result.spec: epoch ", epoch, " has no batch ", result.spec.index));
    Slot& slot = slots_[result.spec.index - first];
    if (!SameSpec(slot.spec, result.spec))
        return absl::InvalidArgumentError(
            absl::StrCat("result.spec: does not match batch ", slot.spec.index));
    for (uint32_t hit_point : result.tally.hit_point)
        if (hit_point >= hit_point_count_)
            return absl::InvalidArgumentError(
                absl::StrCat("result.tally: hit point ", hit_point, " of ", hit_point_count_));
    // Only a worker that held the slot may fill it: a result cannot be checked but by running
    // the batch again, so one from a worker never given the batch is refused unread.
    if (std::find(slot.lessees.begin(), slot.lessees.end(), worker) == slot.lessees.end())
        return ReportOutcome{TallyVerdict::kNotLeased};
    if (slot.result || slot.folded) return ReportOutcome{TallyVerdict::kDuplicate};
    // ppm's share of the epoch's emission pass: the slice's pixels and their hit points.
    if (const auto [pixels, covered] = slot.emission_shape;
        result.emission.size() != pixels || result.coverage.size() != covered)
        return absl::InvalidArgumentError(
            absl::StrCat("result.emission: ", result.emission.size(), " pixels and ",
                         result.coverage.size(), " hit points covered for batch ", slot.spec.index,
                         ", which has ", pixels, " and ", covered));
    slot.result = std::move(result);
    workers_seen_[worker] = now;
    return ReportOutcome{TallyVerdict::kAccepted, FoldReadyLocked(lock, now)};
}

bool Job::FoldReadyLocked(std::unique_lock<std::mutex>& lock, Clock::time_point now) {
    if (folding_) return false;  // the thread folding now will pick this result up
    folding_ = true;
    bool finished = false;
    while (state_ == JobState::kRunning) {
        if (next_fold_ < slots_.size()) {
            Slot& slot = slots_[next_fold_];
            if (!slot.result) break;
            BatchResult result = std::move(*slot.result);
            slot.result.reset();
            slot.folded = true;
            ++next_fold_;
            lock.unlock();
            {
                std::lock_guard estimate_lock(estimate_mutex_);
                if (estimate_) estimate_->FoldBatch(result);
            }
            lock.lock();
            continue;
        }
        // Every batch of the epoch is folded: update the estimate and start the next epoch.
        GatherRegions regions;
        uint64_t photons = 0, discarded = 0, samples = 0;
        bool reached = true, black = false;
        ErrorEstimate error;
        std::optional<ImageDifference> measured;
        lock.unlock();
        {
            std::lock_guard estimate_lock(estimate_mutex_);
            if (estimate_) {
                estimate_->FinishEpoch();
                regions = estimate_->Regions();
                photons = estimate_->PhotonsEmitted();
                samples = estimate_->CameraSamples();
                discarded = estimate_->NonfiniteDiscarded();
                reached = estimate_->LightReachedAnything();
                // Where photons and light samples reached nothing, whether camera paths found
                // light of their own (emitters, and light through glossy and specular bounces).
                if (!reached) {
                    const Image image = estimate_->Resolve();
                    black = std::all_of(image.pixels.begin(), image.pixels.end(),
                                        [](const Rgb& pixel) { return IsBlack(pixel); });
                }
                error = estimate_->EstimateError();
                // In the image's units, as the film (pbrt's iso, shutter) scales it.
                error.rmse *= film_.Gain();
                error.bias_rmse *= film_.Gain();
                measured = MeasureLocked();
            }
        }
        lock.lock();
        if (state_ != JobState::kRunning) break;
        ++epochs_merged_;
        photons_merged_ = photons;
        camera_samples_ = samples;
        nonfinite_discarded_ = discarded;
        if (error.known) estimated_error_ = error.RelativeError();
        measured_error_ = measured;
        convergence_.Add({Seconds(now - started_), epochs_merged_, photons_merged_,
                          error.known ? std::optional(error) : std::nullopt, measured,
                          reference_ ? reference_->pixels.size() : 0, camera_samples_});
        ++version_;
        finished = true;
        if (BudgetFraction(spec_, photons_merged_, epochs_merged_, Seconds(now - started_),
                           estimated_error_) >= 1.0) {
            // Without hit points (a camera that sees no diffuse surface) photons have nothing
            // to reach: the image is what camera paths find, right unless it is black.
            const bool without_hit_points =
                GathersAtHitPoints(spec_.integrator) && hit_point_count_ == 0;
            if (!reached && (!without_hit_points || black)) {
                warnings_.push_back(
                    without_hit_points
                        ? absl::StrCat("the camera sees no diffuse surface, and its paths found no "
                                       "light directly or through glossy and specular bounces "
                                       "in ",
                                       photons_merged_, " photons: the image is black")
                        : absl::StrCat("no light reached anything the camera sees in ",
                                       photons_merged_,
                                       " photons: the image is emission only (a light shut "
                                       "inside a closed object, or a camera that sees only unlit "
                                       "surfaces?)"));
                spdlog::warn("job {}: {}", id_, warnings_.back());
            }
            EndLocked(JobState::kDone, "", now);
            break;
        }
        StartEpochLocked(std::move(regions));
        break;
    }
    folding_ = false;
    changed_.notify_all();
    if (state_ != JobState::kRunning) {
        lock.unlock();
        ReleaseInputs();
        lock.lock();
    }
    return finished;
}

void Job::EndLocked(JobState state, std::string message, Clock::time_point now) {
    state_ = state;
    message_ = std::move(message);
    ended_ = now;
    ++version_;
    // Leases end with the job; inputs are freed by ReleaseInputs, outside this lock.
    slots_.clear();
    epoch_.reset();
    payload_.reset();
    scene_blob_.reset();
    hit_points_blob_.reset();
    workers_seen_.clear();
    changed_.notify_all();
}

void Job::ReleaseInputs() {
    std::optional<JobCheckpointData> final_state;
    if (checkpointed_) {
        std::lock_guard lock(mutex_);
        final_state = RecordLocked(ended_);
    }
    {
        std::lock_guard estimate_lock(estimate_mutex_);
        if (!estimate_) return;
        if (final_state) SaveEstimateLocked(*final_state);
        ResolveLocked();
        estimate_.reset();
        fixed_estimate_.reset();  // the final state holds it until written
    }
    std::lock_guard lock(mutex_);
    final_checkpoint_ = std::move(final_state);
    durable_scene_.reset();
}

bool Job::Cancel(const std::string& reason, Clock::time_point now) {
    {
        std::lock_guard lock(mutex_);
        if (state_ != JobState::kRunning) return false;
        EndLocked(JobState::kCancelled, reason, now);
    }
    ReleaseInputs();
    return true;
}

bool Job::Running() const {
    std::lock_guard lock(mutex_);
    return state_ == JobState::kRunning;
}

bool Job::AddWatcher(uint32_t limit) {
    uint32_t watchers = watchers_.load();
    do {
        if (watchers >= limit) return false;
    } while (!watchers_.compare_exchange_weak(watchers, watchers + 1));
    return true;
}

void Job::RemoveWatcher() { watchers_.fetch_sub(1); }

JobProgress Job::Progress(Clock::time_point now) const {
    std::lock_guard lock(mutex_);
    JobProgress progress;
    progress.job_id = id_;
    progress.owner = owner_;
    progress.name = name_;
    progress.state = state_;
    progress.priority = priority_;
    progress.epochs = epochs_merged_;
    progress.photons = photons_merged_;
    progress.integrator = spec_.integrator;
    progress.camera_samples = camera_samples_;
    progress.hit_points = hit_point_count_;
    progress.initial_radius = initial_radius_;
    progress.scene_features = scene_features_;
    const Clock::time_point end = state_ == JobState::kRunning ? now : ended_;
    progress.elapsed_seconds = Seconds(end - started_);
    progress.photons_per_second =
        progress.elapsed_seconds > 0 ? photons_merged_ / progress.elapsed_seconds : 0;
    progress.budget_fraction = state_ == JobState::kDone
                                   ? 1.0
                                   : BudgetFraction(spec_, photons_merged_, epochs_merged_,
                                                    progress.elapsed_seconds, estimated_error_);
    progress.estimated_error = estimated_error_;
    progress.measured_error = measured_error_;
    progress.nonfinite_discarded = nonfinite_discarded_;
    for (const auto& [worker, seen] : workers_seen_)
        if (now - seen < kActiveWindow) ++progress.workers_active;
    for (const Slot& slot : slots_) {
        progress.batches_pending += LeasableLocked(slot, now);
        progress.batches_leased +=
            slot.leased && !slot.result && !slot.folded && slot.deadline > now;
    }
    progress.message = message_;
    progress.warnings = warnings_;
    return progress;
}

uint64_t Job::Version() const {
    std::lock_guard lock(mutex_);
    return version_;
}

uint64_t Job::WaitForChange(uint64_t seen, Clock::time_point until) const {
    std::unique_lock lock(mutex_);
    changed_.wait_until(lock, until, [&] { return version_ != seen; });
    return version_;
}

void Job::ResolveLocked() const {
    if (image_epoch_ == estimate_->Epoch()) return;
    Image image = estimate_->Resolve();
    film_.Apply(&image);  // the scene's film: pbrt's iso, shutter, white balance
    image_ = std::make_shared<const Image>(std::move(image));
    image_epoch_ = estimate_->Epoch();
}

std::optional<ImageDifference> Job::MeasureLocked() const {
    if (!reference_) return std::nullopt;
    ResolveLocked();
    const absl::StatusOr<ImageDifference> difference = CompareImages(*image_, *reference_);
    return difference.ok() ? std::optional(*difference)
                           : std::nullopt;  // sizes were checked at submission
}

std::vector<ConvergencePoint> Job::Convergence() const {
    std::lock_guard lock(mutex_);
    return convergence_.Points();
}

std::shared_ptr<const Image> Job::CurrentImage() const {
    std::lock_guard estimate_lock(estimate_mutex_);
    if (estimate_) ResolveLocked();
    return image_;
}

}  // namespace pf
