// Channels to the coordinator: credentials, token files, the token interceptor.
#include "wire/secure_channel.h"

#include <grpcpp/create_channel.h>
#include <grpcpp/security/credentials.h>
#include <grpcpp/support/client_interceptor.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "absl/strings/strip.h"
#include "wire/rpc_status.h"

namespace pf {
namespace {

bool PrintableAscii(const std::string& text) {
    for (char c : text)
        if (c <= ' ' || c > '~') return false;
    return true;
}

absl::Status CheckSecret(const std::string& secret, const std::string& where) {
    if (secret.size() < kMinTokenLength)
        return absl::InvalidArgumentError(
            absl::StrCat(where, ": the token is ", secret.size(), " characters; use at least ",
                         kMinTokenLength, " (for example `openssl rand -hex 32`)"));
    if (!PrintableAscii(secret))
        return absl::InvalidArgumentError(
            absl::StrCat(where, ": a token may hold printable ASCII only, no spaces"));
    return absl::OkStatus();
}

// Adds the token to every call's metadata, so no call site can forget it.
class TokenInterceptor final : public grpc::experimental::Interceptor {
public:
    explicit TokenInterceptor(const std::string* header) : header_(header) {}
    void Intercept(grpc::experimental::InterceptorBatchMethods* methods) override {
        if (methods->QueryInterceptionHookPoint(
                grpc::experimental::InterceptionHookPoints::PRE_SEND_INITIAL_METADATA))
            methods->GetSendInitialMetadata()->insert({kTokenMetadataKey, *header_});
        methods->Proceed();
    }

private:
    const std::string* header_;
};

class TokenInterceptorFactory final : public grpc::experimental::ClientInterceptorFactoryInterface {
public:
    explicit TokenInterceptorFactory(const std::string& token)
        : header_(absl::StrCat(kTokenPrefix, token)) {}
    grpc::experimental::Interceptor* CreateClientInterceptor(
        grpc::experimental::ClientRpcInfo*) override {
        return new TokenInterceptor(&header_);
    }

private:
    const std::string header_;
};

}  // namespace

absl::StatusOr<std::string> ReadPemFile(const std::string& path, const std::string& what) {
    std::ifstream file(path, std::ios::binary);
    if (!file) return absl::NotFoundError(absl::StrCat(what, " ", path, ": cannot open"));
    std::ostringstream content;
    content << file.rdbuf();
    if (content.str().empty())
        return absl::InvalidArgumentError(absl::StrCat(what, " ", path, ": empty"));
    return content.str();
}

absl::StatusOr<std::vector<Token>> ReadTokenFile(const std::string& path) {
    std::ifstream file(path);
    if (!file) return absl::NotFoundError(absl::StrCat("token file ", path, ": cannot open"));
    std::vector<Token> tokens;
    std::string line;
    for (int number = 1; std::getline(file, line); ++number) {
        const std::string where = absl::StrCat(path, ":", number);
        std::vector<std::string> fields =
            absl::StrSplit(line, absl::ByAnyChar(" \t\r"), absl::SkipEmpty());
        if (fields.empty() || fields[0].starts_with("#")) continue;
        if (fields.size() > 2)
            return absl::InvalidArgumentError(
                absl::StrCat(where, ": expected \"SECRET\" or \"NAME SECRET\", found ",
                             fields.size(), " fields"));
        Token token = fields.size() == 2 ? Token{fields[0], fields[1]}
                                         : Token{absl::StrCat("token ", number), fields[0]};
        if (absl::Status status = CheckSecret(token.secret, where); !status.ok()) return status;
        tokens.push_back(std::move(token));
    }
    if (tokens.empty())
        return absl::InvalidArgumentError(absl::StrCat("token file ", path, ": holds no token"));
    return tokens;
}

absl::StatusOr<std::vector<Token>> ReadTokens(const std::string& file, const char* env) {
    if (!file.empty()) return ReadTokenFile(file);
    const char* value = std::getenv(env);
    if (value == nullptr || *value == '\0') return std::vector<Token>{};
    std::string secret(absl::StripAsciiWhitespace(value));
    if (absl::Status status = CheckSecret(secret, env); !status.ok()) return status;
    return std::vector<Token>{{env, std::move(secret)}};
}

void AddChannelSecurityOptions(CLI::App* app, ChannelSecurityFlags* flags, const char* token_env) {
    app->add_flag("--plaintext", flags->plaintext,
                  "No TLS: for a coordinator on this machine or a private network only (tokens "
                  "cross in clear)")
        ->envname("PHOTONFARM_PLAINTEXT");
    app->add_option("--tls-ca", flags->ca_file,
                    "CA certificates (PEM) the coordinator's certificate must chain to "
                    "(default: the system's)")
        ->envname("PHOTONFARM_TLS_CA");
    app->add_option("--tls-cert", flags->cert_file,
                    "Our certificate chain (PEM), for a coordinator that asks for one")
        ->envname("PHOTONFARM_TLS_CLIENT_CERT");
    app->add_option("--tls-key", flags->key_file, "The private key (PEM) of --tls-cert")
        ->envname("PHOTONFARM_TLS_CLIENT_KEY");
    app->add_option(
           "--tls-server-name", flags->server_name,
           "The name the coordinator's certificate must hold (default: the host in the address)")
        ->envname("PHOTONFARM_TLS_SERVER_NAME");
    app->add_option("--token-file", flags->token_file,
                    absl::StrCat("File holding our token (default: the ", token_env,
                                 " environment variable)"))
        ->envname(absl::StrCat(token_env, "_FILE"));
}

absl::StatusOr<ChannelSecurity> LoadChannelSecurity(const ChannelSecurityFlags& flags,
                                                    const char* token_env) {
    ChannelSecurity security;
    security.plaintext = flags.plaintext;
    if (flags.cert_file.empty() != flags.key_file.empty())
        return absl::InvalidArgumentError("--tls-cert and --tls-key: give both or neither");
    if (flags.plaintext && !(flags.ca_file.empty() && flags.cert_file.empty()))
        return absl::InvalidArgumentError(
            "--plaintext: cannot be combined with --tls-ca, --tls-cert or --tls-key");
    if (!flags.ca_file.empty()) {
        absl::StatusOr<std::string> pem = ReadPemFile(flags.ca_file, "--tls-ca");
        if (!pem.ok()) return pem.status();
        security.ca_pem = std::move(*pem);
    }
    if (!flags.cert_file.empty()) {
        absl::StatusOr<std::string> cert = ReadPemFile(flags.cert_file, "--tls-cert");
        if (!cert.ok()) return cert.status();
        absl::StatusOr<std::string> key = ReadPemFile(flags.key_file, "--tls-key");
        if (!key.ok()) return key.status();
        security.cert_pem = std::move(*cert);
        security.key_pem = std::move(*key);
    }
    security.server_name = flags.server_name;
    absl::StatusOr<std::vector<Token>> tokens = ReadTokens(flags.token_file, token_env);
    if (!tokens.ok()) return tokens.status();
    if (tokens->size() > 1)
        return absl::InvalidArgumentError(absl::StrCat("--token-file ", flags.token_file,
                                                       ": holds ", tokens->size(),
                                                       " tokens; ours must be one"));
    if (!tokens->empty()) security.token = tokens->front().secret;
    return security;
}

std::shared_ptr<grpc::Channel> OpenChannel(const std::string& address,
                                           const ChannelSecurity& security) {
    grpc::ChannelArguments args;
    args.SetMaxReceiveMessageSize(kMaxMessageBytes);
    args.SetMaxSendMessageSize(kMaxMessageBytes);
    // Reconnect within seconds of a coordinator's restart, not gRPC's default of up to 2 min.
    // (GRPC_ARG_MIN_RECONNECT_BACKOFF_MS stays at its default: it is also the time a connection
    // attempt, TLS handshake included, may take.)
    args.SetInt(GRPC_ARG_INITIAL_RECONNECT_BACKOFF_MS, 250);
    args.SetInt(GRPC_ARG_MAX_RECONNECT_BACKOFF_MS, 2000);
    std::shared_ptr<grpc::ChannelCredentials> credentials;
    if (security.plaintext) {
        credentials = grpc::InsecureChannelCredentials();
    } else {
        grpc::SslCredentialsOptions options;
        options.pem_root_certs = security.ca_pem;
        options.pem_cert_chain = security.cert_pem;
        options.pem_private_key = security.key_pem;
        credentials = grpc::SslCredentials(options);
        if (!security.server_name.empty()) args.SetSslTargetNameOverride(security.server_name);
    }
    if (security.token.empty()) return grpc::CreateCustomChannel(address, credentials, args);
    std::vector<std::unique_ptr<grpc::experimental::ClientInterceptorFactoryInterface>>
        interceptors;
    interceptors.push_back(std::make_unique<TokenInterceptorFactory>(security.token));
    return grpc::experimental::CreateCustomChannelWithInterceptors(address, credentials, args,
                                                                   std::move(interceptors));
}

}  // namespace pf
