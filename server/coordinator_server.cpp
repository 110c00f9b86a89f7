// gRPC server assembly.
#include "server/coordinator_server.h"

#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/health_check_service_interface.h>
#include <grpcpp/security/server_credentials.h>
#include <grpcpp/server_builder.h>

#include <chrono>

#include "absl/strings/str_cat.h"

namespace pf {

CoordinatorServer::CoordinatorServer(Coordinator& coordinator, ServerSecurity security)
    : coordinator_(coordinator),
      access_(std::move(security)),
      jobs_(coordinator, access_, stopping_),
      work_(coordinator, access_) {}

absl::StatusOr<std::unique_ptr<CoordinatorServer>> CoordinatorServer::Start(
    Coordinator& coordinator, ServerOptions options) {
    const ServerSecurity& security = options.security;
    if (!security.plaintext) {
        if (security.cert_pem.empty() || security.key_pem.empty())
            return absl::InvalidArgumentError(
                "TLS needs a certificate and its key (--tls-cert, --tls-key), or --plaintext");
        if (security.client_tokens.empty() || security.worker_tokens.empty())
            return absl::InvalidArgumentError(absl::StrCat(
                "TLS needs tokens for clients and for workers (--client-token-file or ",
                kClientTokenEnv, ", --worker-token-file or ", kWorkerTokenEnv, ")"));
    }
    std::shared_ptr<grpc::ServerCredentials> credentials = MakeServerCredentials(security);
    std::unique_ptr<CoordinatorServer> server(
        new CoordinatorServer(coordinator, std::move(options.security)));
    grpc::EnableDefaultHealthCheckService(true);
    grpc::reflection::InitProtoReflectionServerBuilderPlugin();
    grpc::ServerBuilder builder;
    builder.AddListeningPort(options.address, credentials, &server->port_);
    builder.RegisterService(&server->jobs_);
    builder.RegisterService(&server->work_);
    builder.SetMaxReceiveMessageSize(options.max_message_bytes);
    builder.SetMaxSendMessageSize(kMaxMessageBytes);
    server->server_ = builder.BuildAndStart();
    if (!server->server_ || server->port_ == 0)
        return absl::UnavailableError(
            absl::StrCat("cannot listen on ", options.address,
                         " (in use, not an address here, or a bad certificate or key)"));
    return server;
}

CoordinatorServer::~CoordinatorServer() { Shutdown(); }

void CoordinatorServer::Shutdown() {
    if (!server_ || stopping_.exchange(true)) return;
    coordinator_.Shutdown();
    if (grpc::HealthCheckServiceInterface* health = server_->GetHealthCheckService())
        health->Shutdown();
    // Handlers notice `stopping_` within a poll interval; calls still running after the
    // grace period are cancelled.
    server_->Shutdown(std::chrono::system_clock::now() + std::chrono::seconds(2));
    server_->Wait();
}

}  // namespace pf
