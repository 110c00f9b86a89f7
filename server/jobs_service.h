// The photonfarm.v1.Jobs service: gRPC glue for clients over a Coordinator.
#pragma once

#include <atomic>

#include "photonfarm/v1/jobs.grpc.pb.h"
#include "server/access_control.h"
#include "server/coordinator.h"

namespace pf {

class JobsService final : public photonfarm::v1::Jobs::Service {
public:
    // `stopping` ends watch streams early when the server shuts down. Every call must hold a
    // client's token (`access`).
    JobsService(Coordinator& coordinator, const AccessControl& access,
                const std::atomic<bool>& stopping)
        : coordinator_(coordinator), access_(access), stopping_(stopping) {}

    grpc::Status SubmitJob(grpc::ServerContext* context,
                           const photonfarm::v1::SubmitJobRequest* request,
                           photonfarm::v1::SubmitJobResponse* response) override;
    grpc::Status WatchJob(grpc::ServerContext* context,
                          const photonfarm::v1::WatchJobRequest* request,
                          grpc::ServerWriter<photonfarm::v1::Snapshot>* writer) override;
    grpc::Status CancelJob(grpc::ServerContext* context,
                           const photonfarm::v1::CancelJobRequest* request,
                           photonfarm::v1::CancelJobResponse* response) override;
    grpc::Status ListJobs(grpc::ServerContext* context,
                          const photonfarm::v1::ListJobsRequest* request,
                          photonfarm::v1::ListJobsResponse* response) override;
    grpc::Status GetResult(grpc::ServerContext* context,
                           const photonfarm::v1::GetResultRequest* request,
                           photonfarm::v1::GetResultResponse* response) override;
    grpc::Status GetConvergence(grpc::ServerContext* context,
                                const photonfarm::v1::GetConvergenceRequest* request,
                                photonfarm::v1::GetConvergenceResponse* response) override;
    grpc::Status ListWorkers(grpc::ServerContext* context,
                             const photonfarm::v1::ListWorkersRequest* request,
                             photonfarm::v1::ListWorkersResponse* response) override;

private:
    grpc::Status Authorize(const grpc::ServerContext& context) const;

    Coordinator& coordinator_;
    const AccessControl& access_;
    const std::atomic<bool>& stopping_;
};

}  // namespace pf
