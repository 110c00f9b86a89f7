// The photonfarm.v1.Work service: gRPC glue for workers over a Coordinator. Every tally is
// decoded as hostile (wire/proto_convert.h) before the coordinator sees it.
#pragma once

#include "photonfarm/v1/work.grpc.pb.h"
#include "server/access_control.h"
#include "server/coordinator.h"

namespace pf {

class WorkService final : public photonfarm::v1::Work::Service {
public:
    // Every call must hold a worker's token, and under mutual TLS a worker's certificate.
    WorkService(Coordinator& coordinator, const AccessControl& access)
        : coordinator_(coordinator), access_(access) {}

    grpc::Status RegisterWorker(grpc::ServerContext* context,
                                const photonfarm::v1::RegisterWorkerRequest* request,
                                photonfarm::v1::RegisterWorkerResponse* response) override;
    grpc::Status Heartbeat(grpc::ServerContext* context,
                           const photonfarm::v1::HeartbeatRequest* request,
                           photonfarm::v1::HeartbeatResponse* response) override;
    grpc::Status UnregisterWorker(grpc::ServerContext* context,
                                  const photonfarm::v1::UnregisterWorkerRequest* request,
                                  photonfarm::v1::UnregisterWorkerResponse* response) override;
    grpc::Status LeaseBatches(grpc::ServerContext* context,
                              const photonfarm::v1::LeaseBatchesRequest* request,
                              photonfarm::v1::LeaseBatchesResponse* response) override;
    grpc::Status FetchBlob(grpc::ServerContext* context,
                           const photonfarm::v1::FetchBlobRequest* request,
                           grpc::ServerWriter<photonfarm::v1::BlobChunk>* writer) override;
    grpc::Status ReportTally(grpc::ServerContext* context,
                             const photonfarm::v1::ReportTallyRequest* request,
                             photonfarm::v1::ReportTallyResponse* response) override;

private:
    grpc::Status Authorize(const grpc::ServerContext& context) const;

    Coordinator& coordinator_;
    const AccessControl& access_;
};

}  // namespace pf
