// Work RPCs.
#include "server/work_service.h"

#include <algorithm>

#include "absl/strings/str_cat.h"
#include "wire/proto_convert.h"
#include "wire/rpc_status.h"

namespace pf {
namespace {

namespace v1 = photonfarm::v1;

// Blobs stream in chunks of this size (the proto promises at most 1 MiB).
constexpr size_t kChunkBytes = size_t{1} << 20;
// The most batches one lease may ask for.
constexpr uint32_t kMaxChunksPerLease = 1 << 16;

}  // namespace

grpc::Status WorkService::Authorize(const grpc::ServerContext& context) const {
    return ToGrpcStatus(access_.Authorize(context, Role::kWorker).status());
}

grpc::Status WorkService::RegisterWorker(grpc::ServerContext* context,
                                         const v1::RegisterWorkerRequest* request,
                                         v1::RegisterWorkerResponse* response) {
    if (grpc::Status denied = Authorize(*context); !denied.ok()) return denied;
    if (request->backend().empty() || request->backend().size() > 64)
        return ToGrpcStatus(absl::InvalidArgumentError(
            "backend: must name the worker's backend (at most 64 characters)"));
    if (request->version().size() > 64)
        return ToGrpcStatus(absl::InvalidArgumentError("version: too long"));
    absl::StatusOr<std::string> id = coordinator_.RegisterWorker(
        {request->backend(), request->threads(), request->version(), context->peer()});
    if (!id.ok()) return ToGrpcStatus(id.status());
    response->set_worker_id(*id);
    response->set_heartbeat_seconds(coordinator_.Options().heartbeat_seconds);
    response->set_lease_seconds(coordinator_.Options().lease_seconds);
    return grpc::Status::OK;
}

grpc::Status WorkService::Heartbeat(grpc::ServerContext* context,
                                    const v1::HeartbeatRequest* request, v1::HeartbeatResponse*) {
    if (grpc::Status denied = Authorize(*context); !denied.ok()) return denied;
    return ToGrpcStatus(coordinator_.Heartbeat(request->worker_id()));
}

grpc::Status WorkService::UnregisterWorker(grpc::ServerContext* context,
                                           const v1::UnregisterWorkerRequest* request,
                                           v1::UnregisterWorkerResponse* response) {
    if (grpc::Status denied = Authorize(*context); !denied.ok()) return denied;
    absl::StatusOr<uint32_t> returned = coordinator_.UnregisterWorker(request->worker_id());
    if (!returned.ok()) return ToGrpcStatus(returned.status());
    response->set_leases_returned(*returned);
    return grpc::Status::OK;
}

grpc::Status WorkService::LeaseBatches(grpc::ServerContext* context,
                                       const v1::LeaseBatchesRequest* request,
                                       v1::LeaseBatchesResponse* response) {
    if (grpc::Status denied = Authorize(*context); !denied.ok()) return denied;
    if (request->chunks() == 0 || request->chunks() > kMaxChunksPerLease)
        return ToGrpcStatus(absl::InvalidArgumentError(
            absl::StrCat("chunks: must lie in [1, ", kMaxChunksPerLease, "]")));
    absl::StatusOr<CoordinatorLease> lease = coordinator_.Lease(
        request->worker_id(), request->chunks(), coordinator_.Options().lease_wait_seconds);
    if (!lease.ok()) return ToGrpcStatus(lease.status());
    if (lease->grant.batches.empty()) {
        response->set_retry_seconds(0);  // the lease already waited for work: ask again at once
        return grpc::Status::OK;
    }
    std::shared_ptr<const LazyBlob> scene = lease->job->SceneBlob();
    std::shared_ptr<const LazyBlob> hit_points = lease->job->HitPointsBlob();
    if (!scene || !hit_points) return grpc::Status::OK;  // the job ended a moment ago
    // The blobs are encoded here, on first use, outside every lock.
    v1::JobInputs* job = response->mutable_job();
    job->set_job_id(lease->grant.job_id);
    job->set_prepared_scene_digest(scene->Get().digest);
    job->set_hit_points_digest(hit_points->Get().digest);
    job->set_hit_point_count(lease->job->HitPointCount());
    *job->mutable_settings() = ToProto(lease->grant.job->spec);
    response->set_radii_digest(lease->epoch->blob.Get().digest);
    for (const BatchSpec& spec : lease->grant.batches) *response->add_batches() = ToProto(spec);
    response->set_lease_seconds(lease->lease_seconds);
    return grpc::Status::OK;
}

grpc::Status WorkService::FetchBlob(grpc::ServerContext* context,
                                    const v1::FetchBlobRequest* request,
                                    grpc::ServerWriter<v1::BlobChunk>* writer) {
    if (grpc::Status denied = Authorize(*context); !denied.ok()) return denied;
    const std::shared_ptr<const Blob> blob = coordinator_.FindBlob(request->digest());
    if (!blob)
        return ToGrpcStatus(absl::NotFoundError(absl::StrCat(
            "digest: no blob '", request->digest().substr(0, 64), "' (its job may have ended)")));
    size_t offset = 0;
    do {
        if (context->IsCancelled())
            return grpc::Status(grpc::StatusCode::CANCELLED, "fetch cancelled");
        v1::BlobChunk chunk;
        if (offset == 0) chunk.set_total_bytes(blob->bytes.size());
        const size_t size = std::min(kChunkBytes, blob->bytes.size() - offset);
        chunk.set_data(blob->bytes.substr(offset, size));
        offset += size;
        if (!writer->Write(chunk))
            return grpc::Status(grpc::StatusCode::CANCELLED, "fetcher went away");
    } while (offset < blob->bytes.size());
    return grpc::Status::OK;
}

grpc::Status WorkService::ReportTally(grpc::ServerContext* context,
                                      const v1::ReportTallyRequest* request,
                                      v1::ReportTallyResponse* response) {
    if (grpc::Status denied = Authorize(*context); !denied.ok()) return denied;
    absl::StatusOr<std::shared_ptr<Job>> job = coordinator_.FindJob(request->job_id());
    if (!job.ok()) {  // the coordinator checks the worker and counts the refusal
        absl::StatusOr<TallyVerdict> verdict =
            coordinator_.Report(request->worker_id(), request->job_id(), {});
        if (!verdict.ok()) return ToGrpcStatus(verdict.status());
        response->set_verdict(ToProto(*verdict));
        return grpc::Status::OK;
    }
    const uint64_t hit_points = (*job)->Progress(coordinator_.Options().now()).hit_points;
    absl::StatusOr<BatchResult> result =
        FromProto(request->result(), static_cast<uint32_t>(hit_points),
                  static_cast<uint32_t>((*job)->ItemCount()));
    if (!result.ok()) {
        coordinator_.CountMalformed();
        return ToGrpcStatus(result.status());
    }
    absl::StatusOr<TallyVerdict> verdict =
        coordinator_.Report(request->worker_id(), request->job_id(), std::move(*result));
    if (!verdict.ok()) return ToGrpcStatus(verdict.status());
    response->set_verdict(ToProto(*verdict));
    return grpc::Status::OK;
}

}  // namespace pf
