// Recording a job's first epoch and replaying it (recorded_job.h).
#include "bench/farm_load/recorded_job.h"

#include <tbb/task_arena.h>

#include <chrono>
#include <optional>

#include "absl/strings/str_cat.h"
#include "core/job/work_source.h"
#include "server/coordinator.h"
#include "server/in_process_source.h"
#include "wire/proto_convert.h"
#include "worker/worker_loop.h"

namespace pf::load {
namespace {

namespace v1 = photonfarm::v1;

// A work source that hands the worker loop the first epoch's batches and keeps their results;
// later epochs it answers itself from those results, without the loop tracing anything.
class RecordingSource final : public WorkSource {
public:
    RecordingSource(WorkSource& inner, uint32_t batches_per_epoch)
        : inner_(inner), recorded_(batches_per_epoch) {}

    absl::StatusOr<WorkGrant> Lease(uint32_t chunks) override {
        while (true) {
            absl::StatusOr<WorkGrant> grant = inner_.Lease(chunks);
            if (!grant.ok() || grant->batches.empty() || grant->epoch == 0) return grant;
            for (const BatchSpec& spec : grant->batches) {
                const std::optional<BatchResult>& recorded = recorded_[InEpoch(spec)];
                if (!recorded) return absl::InternalError("a batch was not recorded");
                BatchResult replayed = *recorded;
                replayed.spec = spec;
                absl::StatusOr<TallyVerdict> verdict = inner_.Report(grant->job_id, replayed);
                if (!verdict.ok()) return verdict.status();
                if (*verdict != TallyVerdict::kAccepted)
                    return absl::InternalError("a replayed batch was refused");
            }
        }
    }

    absl::StatusOr<TallyVerdict> Report(const std::string& job_id, BatchResult result) override {
        if (result.spec.epoch == 0) recorded_[InEpoch(result.spec)] = result;
        return inner_.Report(job_id, std::move(result));
    }

    const std::vector<std::optional<BatchResult>>& Recorded() const { return recorded_; }

private:
    size_t InEpoch(const BatchSpec& spec) const { return spec.index % recorded_.size(); }

    WorkSource& inner_;
    std::vector<std::optional<BatchResult>> recorded_;
};

}  // namespace

v1::JobSettings LoadJobSettings(const JobShape& shape, uint64_t seed) {
    v1::JobSettings settings;
    settings.set_width(shape.width);
    settings.set_height(shape.height);
    settings.set_samples_per_pixel(1);
    settings.set_seed(seed);
    settings.set_alpha(2.0 / 3.0);
    settings.set_photons_per_batch(shape.photons_per_batch);
    settings.set_batches_per_epoch(shape.batches_per_epoch);
    settings.set_first_epoch_photons(uint64_t{shape.photons_per_batch} * shape.batches_per_epoch);
    settings.set_epoch_budget(shape.epochs);
    settings.set_integrator(v1::INTEGRATOR_PPM);
    return settings;
}

absl::StatusOr<RecordedJob> RecordJob(const SceneBundle& bundle, const v1::JobSettings& settings,
                                      int threads) {
    const auto start = std::chrono::steady_clock::now();
    absl::StatusOr<JobSpec> spec = FromProto(settings);
    if (!spec.ok()) return spec.status();
    Coordinator coordinator;
    tbb::task_arena arena(threads);
    RecordedJob recorded;
    absl::Status status;
    arena.execute([&] {
        absl::StatusOr<JobProgress> submitted =
            coordinator.Submit({"recording", "farm_load", bundle, *spec, 0, nullptr});
        if (!submitted.ok()) {
            status = submitted.status();
            return;
        }
        absl::StatusOr<std::shared_ptr<Job>> job = coordinator.FindJob(submitted->job_id);
        InProcessSource in_process(
            coordinator, {"cpu", static_cast<uint32_t>(threads), std::string(kPhotonfarmVersion)},
            0.05);
        RecordingSource source(in_process, settings.batches_per_epoch());
        {
            WorkerLoop loop(source, "cpu", static_cast<uint32_t>(threads));
            while ((*job)->Running()) {
                absl::StatusOr<size_t> ran = loop.Step();
                if (!ran.ok()) {
                    status = ran.status();
                    return;
                }
            }
        }
        const JobProgress progress = (*job)->Progress(Clock::now());
        if (progress.state != JobState::kDone) {
            status = absl::InternalError(
                absl::StrCat("the recorded job did not finish: ", progress.message));
            return;
        }
        recorded.reference = *(*job)->CurrentImage();
        recorded.photons = progress.photons;
        for (const std::optional<BatchResult>& result : source.Recorded())
            recorded.batches.push_back(ToProto(*result));
    });
    if (!status.ok()) return status;
    recorded.settings = settings;
    recorded.record_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return recorded;
}

v1::BatchResult ReplayedResult(const RecordedJob& job, const v1::BatchSpec& spec) {
    v1::BatchResult result = job.batches[spec.index() % job.batches.size()];
    *result.mutable_spec() = spec;
    return result;
}

}  // namespace pf::load
