// Who may call the coordinator: TLS for the transport (with optional mutual TLS for workers)
// and bearer tokens for the two roles. A client's token opens the Jobs service, a worker's the
// Work service; neither opens the other. Health checks and reflection stay open, for probes
// and grpcurl. Thread-safe once built.
#pragma once

#include <grpcpp/server_context.h>

#include <memory>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "wire/server_security.h"

namespace pf {

enum class Role { kClient, kWorker };

class AccessControl {
public:
    explicit AccessControl(ServerSecurity security);

    // The caller's name if its token opens `role`'s service: the token's name, or its address
    // where no tokens are configured. UNAUTHENTICATED without a valid token (or, for a worker
    // under mutual TLS, without a verified certificate); PERMISSION_DENIED for the other
    // role's token.
    absl::StatusOr<std::string> Authorize(const grpc::ServerContext& context, Role role) const;
    // The same check for a token from elsewhere (the dashboard's login, an HTTP bearer
    // header): the token's name; UNAUTHENTICATED for a missing (null) or unknown token,
    // PERMISSION_DENIED for the other role's. Only where TokensRequired(role).
    absl::StatusOr<std::string> AuthorizeToken(const std::string* secret, Role role) const;
    // Whether `role` must present a token (tokens are configured for it).
    bool TokensRequired(Role role) const;
    // The transport is TLS.
    bool Encrypted() const { return !plaintext_; }
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

// Equal strings of equal length, in time that does not depend on where they differ (secrets).
bool ConstantTimeEqual(const std::string& a, const std::string& b);

// The address part of a peer string ("ipv4:10.0.0.3:51234" -> "10.0.0.3").
std::string PeerHost(const std::string& peer);

}  // namespace pf
