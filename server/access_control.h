// Who may call the coordinator: TLS for the transport (with optional mutual TLS for workers)
// and bearer tokens for the two roles. A client's token opens the Jobs service, a worker's the
// Work service; neither opens the other. Health checks and reflection stay open, for probes
// and grpcurl. Thread-safe once built.
#pragma once

#include <grpcpp/security/server_credentials.h>
#include <grpcpp/server_context.h>

#include <memory>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "worker/secure_channel.h"

namespace pf {

enum class Role { kClient, kWorker };

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

class AccessControl {
public:
    explicit AccessControl(ServerSecurity security);

    // The caller's name if its token opens `role`'s service: the token's name, or its address
    // where no tokens are configured. UNAUTHENTICATED without a valid token (or, for a worker
    // under mutual TLS, without a verified certificate); PERMISSION_DENIED for the other
    // role's token.
    absl::StatusOr<std::string> Authorize(const grpc::ServerContext& context, Role role) const;
    // Nobody is checked (plain text and no tokens).
    bool Open() const;

private:
    struct Digest {
        std::string name;
        std::string sha256;  // of the secret: compared in constant time, never the secret itself
    };
    static std::vector<Digest> Digests(const std::vector<Token>& tokens);
    // The token's name if it is among `accepted`.
    static const std::string* Find(const std::vector<Digest>& accepted, const std::string& sha256);

    const bool plaintext_;
    const bool worker_certificates_;
    const std::vector<Digest> client_tokens_, worker_tokens_;
};

// The address part of a peer string ("ipv4:10.0.0.3:51234" -> "10.0.0.3").
std::string PeerHost(const std::string& peer);

}  // namespace pf
