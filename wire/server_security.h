// The coordinator's side of transport security: what protects its port (TLS, mutual TLS for
// workers, bearer tokens per role), the command-line flags that choose it, and the gRPC
// credentials it listens with. The checks of each call are server/access_control.h's.
#pragma once

#include <grpcpp/security/server_credentials.h>

#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "wire/secure_channel.h"

namespace pf {

struct ServerSecurity {
    // No TLS. Tokens, if any, are still checked, but cross the network in clear.
    bool plaintext = false;
    std::string cert_pem, key_pem;  // the coordinator's certificate chain and key
    // When set, a worker must present a certificate signed by one of these CAs (mutual TLS);
    // clients need none.
    std::string worker_ca_pem;
    // Accepted tokens per role. Empty lists are allowed only in plain-text mode, and then
    // anyone may call anything.
    std::vector<Token> client_tokens, worker_tokens;
};

// The credentials to listen with.
std::shared_ptr<grpc::ServerCredentials> MakeServerCredentials(const ServerSecurity& security);

// Command-line choices, before the files are read.
struct ServerSecurityFlags {
    bool plaintext = false;
    std::string cert_file, key_file, worker_ca_file, client_token_file, worker_token_file;
};

// Adds --plaintext, --tls-cert, --tls-key, --worker-ca, --client-token-file and
// --worker-token-file (each also from a PHOTONFARM_* variable) to `app`.
void AddServerSecurityOptions(CLI::App& app, ServerSecurityFlags* flags);
// Reads the files the flags name and the tokens (from their files or the token variables);
// INVALID_ARGUMENT for --plaintext with certificates, errors naming the flag and file.
absl::StatusOr<ServerSecurity> LoadServerSecurity(const ServerSecurityFlags& flags);
// What protects the port, in the log; plain text loudly.
void LogServerSecurity(const ServerSecurity& security, const std::string& host, int port);

// The credentials to listen with.
std::shared_ptr<grpc::ServerCredentials> MakeServerCredentials(const ServerSecurity& security);

}  // namespace pf
