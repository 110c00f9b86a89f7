// A job's checkpoints: its record and estimate taken under its locks, and a job rebuilt from
// them after a restart.
#include <spdlog/spdlog.h>

#include "absl/strings/str_cat.h"
#include "core/estimate/progressive_estimate.h"
#include "core/scene/scene_features.h"
#include "server/camera_passes.h"
#include "server/job.h"
#include "wire/proto_convert.h"

namespace pf {
namespace {

namespace v1 = photonfarm::v1;

// The kinds of a job's fixed parts (v1::FixedPart).
constexpr char kSceneKind[] = "scene";
constexpr char kEstimateKind[] = "estimate";

void AddFixedPart(const std::string& kind, std::shared_ptr<const Blob> blob,
                  JobCheckpointData& checkpoint) {
    v1::FixedPart& part = *checkpoint.record.add_fixed_parts();
    part.set_kind(kind);
    part.set_sha256(blob->digest);
    checkpoint.fixed[kind] = std::move(blob);
}

}  // namespace

JobCheckpointData Job::RecordLocked(Clock::time_point now) {
    JobCheckpointData checkpoint;
    v1::JobCheckpoint& record = checkpoint.record;
    record.set_job_id(id_);
    record.set_name(name_);
    record.set_owner(owner_);
    *record.mutable_settings() = ToProto(spec_);
    record.mutable_settings()->set_priority(priority_);
    if (durable_scene_)
        AddFixedPart(kSceneKind,
                     std::shared_ptr<const Blob>(durable_scene_, &durable_scene_->Get()),
                     checkpoint);
    if (reference_) *record.mutable_reference() = ToProto(*reference_);
    record.set_state(ToProto(state_));
    record.set_message(message_);
    for (const std::string& warning : warnings_) record.add_warnings(warning);
    record.set_elapsed_seconds(Seconds((state_ == JobState::kRunning ? now : ended_) - started_));
    record.set_scene_features(scene_features_);
    for (const ConvergencePoint& point : convergence_.Points())
        *record.add_convergence() = ToProto(point);
    record.set_sequence(++checkpoint_sequence_);
    return checkpoint;
}

void Job::SaveEstimateLocked(JobCheckpointData& checkpoint) {
    if (!fixed_estimate_saved_) {  // once per job: it never changes
        ByteWriter fixed;
        if (estimate_->SaveFixed(fixed))
            fixed_estimate_ = std::make_shared<const Blob>(Blob::Of(std::move(fixed.Bytes())));
        fixed_estimate_saved_ = true;
    }
    if (fixed_estimate_) AddFixedPart(kEstimateKind, fixed_estimate_, checkpoint);
    ByteWriter writer;
    estimate_->Save(writer, fixed_estimate_ ? FixedPart::kApart : FixedPart::kIncluded);
    checkpoint.estimate = std::move(writer.Bytes());
}

absl::StatusOr<JobCheckpointData> Job::Checkpoint(Clock::time_point now) {
    {
        std::lock_guard estimate_lock(estimate_mutex_);
        if (estimate_ &&
            std::pair(estimate_->Epoch(), estimate_->BatchesFolded()) == checkpointed_at_)
            return absl::AlreadyExistsError(
                absl::StrCat("job ", id_, ": nothing folded since its last checkpoint"));
    }
    JobCheckpointData checkpoint;
    {
        std::lock_guard lock(mutex_);
        if (state_ != JobState::kRunning)
            return absl::FailedPreconditionError(absl::StrCat("job ", id_, " has ended"));
        checkpoint = RecordLocked(now);
    }
    // The estimate a moment later than the record: between two folds, which is all a resumed
    // job needs (the record's log may lack the latest epoch's point).
    std::lock_guard estimate_lock(estimate_mutex_);
    if (!estimate_) return absl::FailedPreconditionError(absl::StrCat("job ", id_, " has ended"));
    SaveEstimateLocked(checkpoint);
    checkpointed_at_ = {estimate_->Epoch(), estimate_->BatchesFolded()};
    return checkpoint;
}

std::optional<JobCheckpointData> Job::TakeFinalCheckpoint() {
    std::lock_guard lock(mutex_);
    std::optional<JobCheckpointData> final_state = std::move(final_checkpoint_);
    final_checkpoint_.reset();
    return final_state;
}

absl::StatusOr<std::shared_ptr<Job>> Job::Restore(const JobCheckpointData& checkpoint,
                                                  const SceneLimits& limits,
                                                  Clock::time_point now) {
    const v1::JobCheckpoint& record = checkpoint.record;
    const auto lost = [&](const std::string& what) {
        return absl::DataLossError(absl::StrCat("checkpoint of job ", record.job_id(), ": ", what));
    };
    for (const v1::FixedPart& part : record.fixed_parts())
        if (part.kind() != kSceneKind && part.kind() != kEstimateKind)
            return lost(absl::StrCat("a fixed part of unknown kind '", part.kind(), "'"));
    const auto fixed_part = [&](const char* kind) -> std::shared_ptr<const Blob> {
        const auto found = checkpoint.fixed.find(kind);
        return found == checkpoint.fixed.end() ? nullptr : found->second;
    };
    const std::shared_ptr<const Blob> scene_part = fixed_part(kSceneKind);
    const std::shared_ptr<const Blob> estimate_part = fixed_part(kEstimateKind);
    if (!scene_part) return lost("no scene");
    v1::SceneBundle bundle_message;
    if (!bundle_message.ParseFromString(scene_part->bytes)) return lost("unreadable scene bundle");
    absl::StatusOr<SceneBundle> bundle = FromProto(bundle_message);
    if (!bundle.ok()) return lost(std::string(bundle.status().message()));
    absl::StatusOr<JobSpec> spec = FromProto(record.settings());
    if (!spec.ok()) return lost(std::string(spec.status().message()));
    if (!(record.elapsed_seconds() >= 0 && record.elapsed_seconds() < 1e9))
        return lost("elapsed time out of range");
    absl::StatusOr<Scene> scene = LoadScene(
        *bundle, bundle->main_file, {limits, nullptr, true, spec->environment, spec->camera});
    if (!scene.ok()) return scene.status();
    ByteReader reader(checkpoint.estimate);
    ByteReader fixed_reader(estimate_part ? std::string_view(estimate_part->bytes) : "");
    absl::StatusOr<std::unique_ptr<Estimate>> estimate =
        LoadEstimate(reader, estimate_part ? &fixed_reader : nullptr);
    if (!estimate.ok()) return lost(std::string(estimate.status().message()));
    if (!reader.AtEnd()) return lost("bytes after the estimate");
    if ((*estimate)->Kind() != spec->integrator)
        return lost(absl::StrCat("a ", std::string(IntegratorName((*estimate)->Kind())),
                                 " estimate for a ", std::string(IntegratorName(spec->integrator)),
                                 " job"));

    PreparedJob prepared;
    prepared.name = record.name();
    prepared.owner = record.owner();
    prepared.spec = *spec;
    prepared.priority = record.settings().priority();
    const bool stochastic = TracesHitPointsEachEpoch(spec->integrator);
    auto payload =
        std::make_shared<JobPayload>(std::move(*scene),
                                     stochastic ? std::make_shared<const std::vector<HitPoint>>()
                                                : (*estimate)->SharedHitPoints(),
                                     *spec);
    if (stochastic) {  // its next epochs' passes are traced here again
        absl::StatusOr<CameraPassSettings> film = FilmFor(*spec, payload->scene);
        if (!film.ok()) return lost(std::string(film.status().message()));
        film->features = AnalyseFeatures(payload->scene, payload->emitters);
        absl::StatusOr<EpochCameraPass> passes = EpochCameraPasses(payload, *film);
        if (!passes.ok()) return passes.status();
        static_cast<ProgressiveEstimate&>(**estimate).SetEpochCameraPass(std::move(*passes));
    }
    prepared.payload = std::move(payload);
    prepared.estimate = std::move(*estimate);
    prepared.bundle = std::move(*bundle);
    prepared.warnings.assign(record.warnings().begin(), record.warnings().end());
    if (record.has_reference()) {
        absl::StatusOr<Image> reference = FromProto(record.reference());
        if (!reference.ok()) return lost(absl::StrCat("reference: ", reference.status().message()));
        prepared.reference = std::make_shared<const Image>(std::move(*reference));
    }
    prepared.scene_features = record.scene_features();
    prepared.checkpointed = true;
    prepared.checkpointed_scene = scene_part;
    prepared.checkpointed_estimate = estimate_part;
    const Estimate& restored = *prepared.estimate;
    const uint64_t epochs = restored.Epoch(), photons = restored.PhotonsEmitted(),
                   discarded = restored.NonfiniteDiscarded();
    const uint64_t samples = restored.CameraSamples();
    const uint32_t restored_folded = restored.BatchesFolded();
    const uint64_t pixels = prepared.reference ? prepared.reference->pixels.size() : 0;
    const auto started = now - std::chrono::duration_cast<Clock::duration>(
                                   std::chrono::duration<double>(record.elapsed_seconds()));
    auto job = std::make_shared<Job>(record.job_id(), std::move(prepared), started);
    job->checkpointed_at_ = {epochs, restored_folded};
    {
        std::lock_guard lock(job->mutex_);
        job->checkpoint_sequence_ = record.sequence();
        for (const v1::ConvergencePoint& point : record.convergence())
            job->convergence_.Add(FromProto(point, pixels));
        job->epochs_merged_ = epochs;
        job->photons_merged_ = photons;
        job->camera_samples_ = samples;
        job->nonfinite_discarded_ = discarded;
        if (!job->convergence_.Points().empty()) {
            const ConvergencePoint& last = job->convergence_.Points().back();
            if (last.estimated) job->estimated_error_ = last.estimated->RelativeError();
            job->measured_error_ = last.measured;
        }
        if (record.state() == v1::JOB_STATE_RUNNING) return job;
        const JobState state = record.state() == v1::JOB_STATE_DONE        ? JobState::kDone
                               : record.state() == v1::JOB_STATE_CANCELLED ? JobState::kCancelled
                                                                           : JobState::kFailed;
        job->EndLocked(state, record.message(), now);
    }
    job->ReleaseInputs();        // the final image, from the state saved
    job->TakeFinalCheckpoint();  // already on disk
    return job;
}

}  // namespace pf
