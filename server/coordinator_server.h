// The coordinator's gRPC server: the Jobs and Work services, the standard health service
// (grpc.health.v1, for probes) and server reflection (for grpcurl), with bounded messages,
// TLS and tokens (access_control.h).
#pragma once

#include <grpcpp/server.h>

#include <atomic>
#include <memory>
#include <string>

#include "absl/status/statusor.h"
#include "server/access_control.h"
#include "server/coordinator.h"
#include "server/jobs_service.h"
#include "server/work_service.h"
#include "wire/rpc_status.h"

namespace pf {

struct ServerOptions {
    std::string address;  // "host:port"; port 0 picks a free one
    ServerSecurity security;
    // The largest message a peer may send; gRPC refuses larger ones with RESOURCE_EXHAUSTED.
    int max_message_bytes = kMaxMessageBytes;
};

class CoordinatorServer {
public:
    // UNAVAILABLE if it cannot bind; INVALID_ARGUMENT if TLS is asked for without a certificate,
    // or with neither client nor worker tokens.
    static absl::StatusOr<std::unique_ptr<CoordinatorServer>> Start(Coordinator& coordinator,
                                                                    ServerOptions options);
    ~CoordinatorServer();

    int Port() const { return port_; }
    // Who may call: the dashboard checks its callers with the same tokens.
    const AccessControl& Access() const { return access_; }
    // Stops taking calls, ends watch streams and lease waits, and waits for handlers to return.
    void Shutdown();

private:
    CoordinatorServer(Coordinator& coordinator, ServerSecurity security);

    Coordinator& coordinator_;
    std::atomic<bool> stopping_{false};
    const AccessControl access_;
    JobsService jobs_;
    WorkService work_;
    std::unique_ptr<grpc::Server> server_;
    int port_ = 0;
};

}  // namespace pf
