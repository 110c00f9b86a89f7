// Jobs RPCs: decode and check the request, call the coordinator, encode the answer.
#include "server/jobs_service.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "server/job_views.h"
#include "wire/proto_convert.h"
#include "wire/rpc_status.h"

namespace pf {
namespace {

namespace v1 = photonfarm::v1;

// A watch stream checks for cancellation (client gone, server stopping) at least this often.
constexpr auto kWatchPoll = std::chrono::milliseconds(250);

grpc::Status Invalid(const absl::Status& status) { return ToGrpcStatus(status); }

}  // namespace

grpc::Status JobsService::Authorize(const grpc::ServerContext& context) const {
    return ToGrpcStatus(access_.Authorize(context, Role::kClient).status());
}

grpc::Status JobsService::SubmitJob(grpc::ServerContext* context,
                                    const v1::SubmitJobRequest* request,
                                    v1::SubmitJobResponse* response) {
    absl::StatusOr<std::string> owner = access_.Authorize(*context, Role::kClient);
    if (!owner.ok()) return ToGrpcStatus(owner.status());
    if (!request->has_scene()) return Invalid(absl::InvalidArgumentError("scene: missing"));
    absl::StatusOr<SceneBundle> bundle = FromProto(request->scene());
    if (!bundle.ok()) return Invalid(bundle.status());
    absl::StatusOr<JobSpec> spec = FromProto(request->settings());
    if (!spec.ok()) return Invalid(spec.status());
    std::shared_ptr<const Image> reference;
    if (request->has_reference()) {
        absl::StatusOr<Image> image = FromProto(request->reference());
        if (!image.ok())
            return Invalid(
                absl::InvalidArgumentError(absl::StrCat("reference: ", image.status().message())));
        reference = std::make_shared<const Image>(std::move(*image));
    }
    absl::StatusOr<JobProgress> progress =
        coordinator_.Submit({request->name(), std::move(*owner), std::move(*bundle), *spec,
                             request->settings().priority(), std::move(reference)});
    if (!progress.ok()) return ToGrpcStatus(progress.status());
    *response->mutable_status() = ToProto(*progress);
    return grpc::Status::OK;
}

grpc::Status JobsService::WatchJob(grpc::ServerContext* context, const v1::WatchJobRequest* request,
                                   grpc::ServerWriter<v1::Snapshot>* writer) {
    if (grpc::Status denied = Authorize(*context); !denied.ok()) return denied;
    if (!(std::isfinite(request->interval_seconds()) && request->interval_seconds() >= 0))
        return Invalid(
            absl::InvalidArgumentError("interval_seconds: must be a non-negative number"));
    absl::StatusOr<std::shared_ptr<Job>> job = coordinator_.FindJob(request->job_id());
    if (!job.ok()) return ToGrpcStatus(job.status());
    const uint32_t max_watchers = coordinator_.Options().client_limits.max_watchers_per_job;
    if (!(*job)->AddWatcher(max_watchers))
        return ToGrpcStatus(absl::ResourceExhaustedError(
            absl::StrCat("job ", request->job_id(), " has ", max_watchers,
                         " watchers, this coordinator's limit (--max-watchers-per-job)")));
    const std::unique_ptr<Job, void (*)(Job*)> watcher(
        job->get(), [](Job* watched) { watched->RemoveWatcher(); });
    const auto interval = std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(std::min(request->interval_seconds(), 3600.0)));
    uint64_t version = (*job)->Version();
    while (true) {
        // Always the latest state: a watcher that reads slowly skips snapshots, never queues them.
        const JobProgress progress = (*job)->Progress(coordinator_.Options().now());
        v1::Snapshot snapshot;
        *snapshot.mutable_status() = ToProto(progress);
        if (request->images())
            if (std::shared_ptr<const Image> image = (*job)->CurrentImage())
                *snapshot.mutable_image() = ToProto(*image);
        if (!writer->Write(snapshot))
            return grpc::Status(grpc::StatusCode::CANCELLED, "watcher went away");
        if (progress.state != JobState::kRunning) return grpc::Status::OK;
        const Clock::time_point next = Clock::now() + interval;
        bool changed = false;
        while (!changed || Clock::now() < next) {
            if (context->IsCancelled() || stopping_.load())
                return grpc::Status(grpc::StatusCode::UNAVAILABLE,
                                    "the coordinator is shutting down");
            const Clock::time_point until =
                std::min(changed ? next : Clock::time_point::max(), Clock::now() + kWatchPoll);
            const uint64_t now_version = (*job)->WaitForChange(version, until);
            changed = changed || now_version != version;
            version = now_version;
            if (changed &&
                (*job)->Progress(coordinator_.Options().now()).state != JobState::kRunning)
                break;
        }
    }
}

grpc::Status JobsService::CancelJob(grpc::ServerContext* context,
                                    const v1::CancelJobRequest* request,
                                    v1::CancelJobResponse* response) {
    if (grpc::Status denied = Authorize(*context); !denied.ok()) return denied;
    absl::StatusOr<JobProgress> progress = coordinator_.Cancel(request->job_id());
    if (!progress.ok()) return ToGrpcStatus(progress.status());
    *response->mutable_status() = ToProto(*progress);
    return grpc::Status::OK;
}

grpc::Status JobsService::ListJobs(grpc::ServerContext* context, const v1::ListJobsRequest*,
                                   v1::ListJobsResponse* response) {
    if (grpc::Status denied = Authorize(*context); !denied.ok()) return denied;
    *response = JobListView(coordinator_);
    return grpc::Status::OK;
}

grpc::Status JobsService::GetResult(grpc::ServerContext* context,
                                    const v1::GetResultRequest* request,
                                    v1::GetResultResponse* response) {
    if (grpc::Status denied = Authorize(*context); !denied.ok()) return denied;
    absl::StatusOr<std::shared_ptr<Job>> job = coordinator_.FindJob(request->job_id());
    if (!job.ok()) return ToGrpcStatus(job.status());
    *response->mutable_status() = ToProto((*job)->Progress(coordinator_.Options().now()));
    if (std::shared_ptr<const Image> image = (*job)->CurrentImage())
        *response->mutable_image() = ToProto(*image);
    return grpc::Status::OK;
}

grpc::Status JobsService::GetConvergence(grpc::ServerContext* context,
                                         const v1::GetConvergenceRequest* request,
                                         v1::GetConvergenceResponse* response) {
    if (grpc::Status denied = Authorize(*context); !denied.ok()) return denied;
    absl::StatusOr<std::shared_ptr<Job>> job = coordinator_.FindJob(request->job_id());
    if (!job.ok()) return ToGrpcStatus(job.status());
    *response = ConvergenceView(**job, coordinator_.Options().now());
    return grpc::Status::OK;
}

grpc::Status JobsService::ListWorkers(grpc::ServerContext* context, const v1::ListWorkersRequest*,
                                      v1::ListWorkersResponse* response) {
    if (grpc::Status denied = Authorize(*context); !denied.ok()) return denied;
    *response = WorkerListView(coordinator_);
    return grpc::Status::OK;
}

}  // namespace pf
