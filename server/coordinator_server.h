// The coordinator's gRPC server: the Jobs and Work services, the standard health service
// (grpc.health.v1, for probes) and server reflection (for grpcurl), with bounded messages.
#pragma once

#include <grpcpp/server.h>

#include <atomic>
#include <memory>
#include <string>

#include "absl/status/statusor.h"
#include "server/coordinator.h"
#include "server/jobs_service.h"
#include "server/work_service.h"
#include "worker/rpc_status.h"

namespace pf {

class CoordinatorServer {
public:
    // Listens on `address` ("host:port"; port 0 picks a free one). UNAVAILABLE if it cannot bind.
    static absl::StatusOr<std::unique_ptr<CoordinatorServer>> Start(Coordinator& coordinator, const std::string& address);
    ~CoordinatorServer();

    int Port() const { return port_; }
    // Stops taking calls, ends watch streams and lease waits, and waits for handlers to return.
    void Shutdown();

private:
    explicit CoordinatorServer(Coordinator& coordinator);

    Coordinator& coordinator_;
    std::atomic<bool> stopping_{false};
    JobsService jobs_;
    WorkService work_;
    std::unique_ptr<grpc::Server> server_;
    int port_ = 0;
};

}  // namespace pf
