// How a worker or a client reaches the coordinator: TLS (the coordinator's certificate checked
// against a CA, optionally a certificate of our own for mutual TLS) or, for local use, plain
// text; and a bearer token sent with every call. Tokens come from a file or the environment,
// never from the command line, where `ps` would show them to every user of the machine.
#pragma once

#include <grpcpp/channel.h>

#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <vector>

#include "absl/status/statusor.h"

namespace pf {

// The metadata key a token travels in ("authorization: Bearer TOKEN").
inline constexpr char kTokenMetadataKey[] = "authorization";
inline constexpr char kTokenPrefix[] = "Bearer ";
// Shorter tokens are refused when read: guessable.
inline constexpr size_t kMinTokenLength = 16;

// The environment variables a client's and a worker's token may come from; the coordinator
// reads the tokens it accepts from the same names.
inline constexpr char kClientTokenEnv[] = "PHOTONFARM_CLIENT_TOKEN";
inline constexpr char kWorkerTokenEnv[] = "PHOTONFARM_WORKER_TOKEN";

struct Token {
    std::string name;  // for logs and per-client limits; never the secret
    std::string secret;
};

// Reads a file of tokens, one per line: "SECRET" or "NAME SECRET" ('#' starts a comment line,
// blank lines are skipped; an unnamed token is called "token N" after its line). Errors name
// the file and line: a token shorter than kMinTokenLength, a secret with characters outside
// printable ASCII, more than two fields, a file holding no token.
absl::StatusOr<std::vector<Token>> ReadTokenFile(const std::string& path);
// Tokens from `file` if given, else the one token in environment variable `env` (named after
// it), else none.
absl::StatusOr<std::vector<Token>> ReadTokens(const std::string& file, const char* env);

// A whole file (certificates, keys), naming `what` and the path in errors.
absl::StatusOr<std::string> ReadPemFile(const std::string& path, const std::string& what);

// Command-line choices, before the files are read.
struct ChannelSecurityFlags {
    bool plaintext = false;
    std::string ca_file;              // trusted roots (PEM); empty: the system's
    std::string cert_file, key_file;  // our certificate for mutual TLS; both or neither
    std::string server_name;  // the name the coordinator's certificate must hold; empty: the host's
    std::string token_file;   // empty: the token environment variable, if set
};

// Adds --plaintext, --tls-ca, --tls-cert, --tls-key, --tls-server-name and --token-file (each
// also from a PHOTONFARM_* variable) to `app`; `token_env` names where else the token may come
// from.
void AddChannelSecurityOptions(CLI::App* app, ChannelSecurityFlags* flags, const char* token_env);

struct ChannelSecurity {
    bool plaintext = false;
    std::string ca_pem, cert_pem, key_pem;
    std::string server_name;
    std::string token;  // empty: none sent
};

// Reads the files the flags name and the token (from its file or `token_env`).
absl::StatusOr<ChannelSecurity> LoadChannelSecurity(const ChannelSecurityFlags& flags,
                                                    const char* token_env);

// A channel to `address` (HOST:PORT) with the security given, the largest messages we send or
// accept (kMaxMessageBytes), and the token added to every call. Connects lazily.
std::shared_ptr<grpc::Channel> OpenChannel(const std::string& address,
                                           const ChannelSecurity& security);

}  // namespace pf
