// gRPC server assembly.
#include "server/coordinator_server.h"

#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/health_check_service_interface.h>
#include <grpcpp/security/server_credentials.h>
#include <grpcpp/server_builder.h>

#include <chrono>

#include "absl/strings/str_cat.h"

namespace pf {

CoordinatorServer::CoordinatorServer(Coordinator& coordinator)
    : coordinator_(coordinator), jobs_(coordinator, stopping_), work_(coordinator) {}

absl::StatusOr<std::unique_ptr<CoordinatorServer>> CoordinatorServer::Start(Coordinator& coordinator,
                                                                          const std::string& address) {
    std::unique_ptr<CoordinatorServer> server(new CoordinatorServer(coordinator));
    grpc::EnableDefaultHealthCheckService(true);
    grpc::reflection::InitProtoReflectionServerBuilderPlugin();
    grpc::ServerBuilder builder;
    // Plain text: TLS and tokens come with the deployment work (issue 7).
    builder.AddListeningPort(address, grpc::InsecureServerCredentials(), &server->port_);
    builder.RegisterService(&server->jobs_);
    builder.RegisterService(&server->work_);
    builder.SetMaxReceiveMessageSize(kMaxMessageBytes);
    builder.SetMaxSendMessageSize(kMaxMessageBytes);
    server->server_ = builder.BuildAndStart();
    if (!server->server_ || server->port_ == 0)
        return absl::UnavailableError(absl::StrCat("cannot listen on ", address, " (in use, or not an address here)"));
    return server;
}

CoordinatorServer::~CoordinatorServer() { Shutdown(); }

void CoordinatorServer::Shutdown() {
    if (!server_ || stopping_.exchange(true)) return;
    coordinator_.Shutdown();
    if (grpc::HealthCheckServiceInterface* health = server_->GetHealthCheckService()) health->Shutdown();
    // Handlers notice `stopping_` within a poll interval; calls still running after the
    // grace period are cancelled.
    server_->Shutdown(std::chrono::system_clock::now() + std::chrono::seconds(2));
    server_->Wait();
}

}  // namespace pf
