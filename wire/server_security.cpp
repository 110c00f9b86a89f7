// The coordinator's transport security: flags, files, credentials.
#include "wire/server_security.h"

#include <spdlog/spdlog.h>

#include <tuple>

#include "absl/strings/str_cat.h"

namespace pf {

void AddServerSecurityOptions(CLI::App& app, ServerSecurityFlags* flags) {
    app.add_flag(
           "--plaintext", flags->plaintext,
           "No TLS, for this machine or a private network only: everything crosses in clear, and "
           "without tokens anyone who reaches the port may submit, cancel or report")
        ->envname("PHOTONFARM_PLAINTEXT");
    app.add_option("--tls-cert", flags->cert_file, "The coordinator's certificate chain (PEM)")
        ->envname("PHOTONFARM_TLS_CERT");
    app.add_option("--tls-key", flags->key_file, "The private key (PEM) of --tls-cert")
        ->envname("PHOTONFARM_TLS_KEY");
    app.add_option(
           "--worker-ca", flags->worker_ca_file,
           "Mutual TLS: workers must present a certificate signed by one of these CAs (PEM)")
        ->envname("PHOTONFARM_WORKER_CA");
    app.add_option(
           "--client-token-file", flags->client_token_file,
           absl::StrCat(
               "Tokens that open the Jobs service, one per line, \"SECRET\" or \"NAME SECRET\" "
               "(default: the one in ",
               kClientTokenEnv, ")"))
        ->envname(absl::StrCat(kClientTokenEnv, "_FILE"));
    app.add_option("--worker-token-file", flags->worker_token_file,
                   absl::StrCat("Tokens that open the Work service, likewise (default: the one in ",
                                kWorkerTokenEnv, ")"))
        ->envname(absl::StrCat(kWorkerTokenEnv, "_FILE"));
}

absl::StatusOr<ServerSecurity> LoadServerSecurity(const ServerSecurityFlags& flags) {
    ServerSecurity security;
    security.plaintext = flags.plaintext;
    if (flags.plaintext &&
        !(flags.cert_file.empty() && flags.key_file.empty() && flags.worker_ca_file.empty()))
        return absl::InvalidArgumentError(
            "--plaintext: cannot be combined with --tls-cert, --tls-key or --worker-ca");
    for (const auto& [file, what, pem] :
         {std::tuple{&flags.cert_file, "--tls-cert", &security.cert_pem},
          std::tuple{&flags.key_file, "--tls-key", &security.key_pem},
          std::tuple{&flags.worker_ca_file, "--worker-ca", &security.worker_ca_pem}}) {
        if (file->empty()) continue;
        absl::StatusOr<std::string> content = ReadPemFile(*file, what);
        if (!content.ok()) return content.status();
        *pem = std::move(*content);
    }
    absl::StatusOr<std::vector<Token>> client =
        ReadTokens(flags.client_token_file, kClientTokenEnv);
    if (!client.ok()) return client.status();
    absl::StatusOr<std::vector<Token>> worker =
        ReadTokens(flags.worker_token_file, kWorkerTokenEnv);
    if (!worker.ok()) return worker.status();
    security.client_tokens = std::move(*client);
    security.worker_tokens = std::move(*worker);
    return security;
}

void LogServerSecurity(const ServerSecurity& security, const std::string& host, int port) {
    if (!security.plaintext) {
        spdlog::info("listening on {}:{} with TLS{}; {} client and {} worker tokens", host, port,
                     security.worker_ca_pem.empty() ? "" : " (workers present certificates)",
                     security.client_tokens.size(), security.worker_tokens.size());
        return;
    }
    spdlog::warn(
        "listening on {}:{} in PLAIN TEXT (--plaintext): no encryption, for local use only", host,
        port);
    if (security.client_tokens.empty() && security.worker_tokens.empty())
        spdlog::warn(
            "NO TOKENS: anyone who reaches port {} may submit and cancel jobs and report tallies",
            port);
    else
        spdlog::warn("tokens are checked but cross the network in clear");
}

std::shared_ptr<grpc::ServerCredentials> MakeServerCredentials(const ServerSecurity& security) {
    if (security.plaintext) return grpc::InsecureServerCredentials();
    // Ask every peer for a certificate and verify any that comes, but require none: clients
    // connect without one; Authorize refuses a worker that has none when workers must.
    grpc::SslServerCredentialsOptions options(security.worker_ca_pem.empty()
                                                  ? GRPC_SSL_DONT_REQUEST_CLIENT_CERTIFICATE
                                                  : GRPC_SSL_REQUEST_CLIENT_CERTIFICATE_AND_VERIFY);
    options.pem_root_certs = security.worker_ca_pem;
    options.pem_key_cert_pairs.push_back({security.key_pem, security.cert_pem});
    return grpc::SslServerCredentials(options);
}

}  // namespace pf
