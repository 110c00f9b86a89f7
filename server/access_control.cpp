// Token and certificate checks.
#include "server/access_control.h"

#include <grpcpp/security/auth_context.h>

#include "absl/strings/str_cat.h"
#include "core/util/sha256.h"

namespace pf {
namespace {

const char* RoleName(Role role) { return role == Role::kClient ? "client" : "worker"; }

}  // namespace

AccessControl::AccessControl(ServerSecurity security)
    : plaintext_(security.plaintext),
      worker_certificates_(!security.plaintext && !security.worker_ca_pem.empty()),
      client_tokens_(Digests(security.client_tokens)),
      worker_tokens_(Digests(security.worker_tokens)) {}

std::vector<AccessControl::Digest> AccessControl::Digests(const std::vector<Token>& tokens) {
    std::vector<Digest> digests;
    for (const Token& token : tokens) digests.push_back({token.name, Sha256Hex(token.secret)});
    return digests;
}

const std::string* AccessControl::Find(const std::vector<Digest>& accepted,
                                       const std::string& sha256) {
    const std::string* name = nullptr;
    for (const Digest& digest : accepted)  // every entry, match or not: no early exit to time
        if (ConstantTimeEqual(digest.sha256, sha256) && name == nullptr) name = &digest.name;
    return name;
}

bool AccessControl::Open() const {
    return plaintext_ && client_tokens_.empty() && worker_tokens_.empty();
}

absl::StatusOr<std::string> AccessControl::Authorize(const grpc::ServerContext& context,
                                                     Role role) const {
    if (role == Role::kWorker && worker_certificates_) {
        const std::shared_ptr<const grpc::AuthContext> auth = context.auth_context();
        if (!auth || !auth->IsPeerAuthenticated())
            return absl::UnauthenticatedError(
                "this coordinator requires workers to present a TLS certificate signed by its "
                "worker CA (--tls-cert, --tls-key)");
    }
    if (!TokensRequired(role)) return PeerHost(context.peer());  // an open role: plain text
    const auto& metadata = context.client_metadata();
    const auto header = metadata.find(kTokenMetadataKey);
    if (header == metadata.end()) return AuthorizeToken(nullptr, role);
    const std::string value(header->second.data(), header->second.size());
    if (!value.starts_with(kTokenPrefix))
        return absl::UnauthenticatedError(absl::StrCat(
            "the ", kTokenMetadataKey, " header must read \"", kTokenPrefix, "TOKEN\""));
    const std::string secret = value.substr(sizeof(kTokenPrefix) - 1);
    return AuthorizeToken(&secret, role);
}

bool AccessControl::TokensRequired(Role role) const {
    return !(role == Role::kClient ? client_tokens_ : worker_tokens_).empty();
}

absl::StatusOr<std::string> AccessControl::AuthorizeToken(const std::string* secret,
                                                          Role role) const {
    if (secret == nullptr)
        return absl::UnauthenticatedError(
            absl::StrCat("no token: a ", RoleName(role), " must send one (--token-file)"));
    const std::vector<Digest>& accepted = role == Role::kClient ? client_tokens_ : worker_tokens_;
    const std::string sha256 = Sha256Hex(*secret);
    if (const std::string* name = Find(accepted, sha256)) return *name;
    const std::vector<Digest>& other = role == Role::kClient ? worker_tokens_ : client_tokens_;
    if (Find(other, sha256) != nullptr)
        return absl::PermissionDeniedError(
            absl::StrCat("a ", RoleName(role == Role::kClient ? Role::kWorker : Role::kClient),
                         "'s token does not open the ", RoleName(role), "s' service"));
    return absl::UnauthenticatedError("the token is not valid here");
}

bool ConstantTimeEqual(const std::string& a, const std::string& b) {
    if (a.size() != b.size()) return false;
    unsigned char difference = 0;
    for (size_t i = 0; i < a.size(); ++i) difference |= static_cast<unsigned char>(a[i] ^ b[i]);
    return difference == 0;
}

std::string PeerHost(const std::string& peer) {
    std::string_view host = peer;
    if (const size_t scheme = host.find(':');
        scheme != std::string_view::npos && !host.starts_with("["))
        host.remove_prefix(scheme + 1);  // "ipv4:" or "ipv6:"
    if (const size_t port = host.rfind(':'); port != std::string_view::npos)
        host = host.substr(0, port);
    return std::string(host);
}

}  // namespace pf
