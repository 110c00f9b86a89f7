// The one mapping between our statuses (absl::Status) and gRPC's, both ways. Codes carry
// over one for one, explicitly, so a bad scene stays INVALID_ARGUMENT, an unknown job
// NOT_FOUND, a limit RESOURCE_EXHAUSTED: never a blanket UNKNOWN.
#pragma once

#include <grpcpp/client_context.h>
#include <grpcpp/support/status.h>

#include <string>

#include "absl/status/status.h"

namespace pf {

// The largest gRPC message either way, for servers and channels alike: a scene bundle at its
// limit (1 GiB) with room for the request around it. gRPC refuses larger messages with
// RESOURCE_EXHAUSTED.
inline constexpr int kMaxMessageBytes = (1 << 30) + (16 << 20);

grpc::Status ToGrpcStatus(const absl::Status& status);
// The HTTP status the dashboard answers a refusal with (400, 401, 403, 404, 409, 429, 500,
// 503 ...), the same code for the same refusal as over gRPC.
int HttpStatusCode(absl::StatusCode code);
// A client call's deadline, `seconds` from now.
void SetDeadline(grpc::ClientContext* context, double seconds);
// `peer` names the other end in the message: "coordinator at 127.0.0.1:5000: ...".
absl::Status FromGrpcStatus(const grpc::Status& status, const std::string& peer);

// Sets gRPC up for a program, before its first call:
// - gRPC's own log lines (a failed TLS handshake, a dropped connection) go to our log at debug
//   level, so a user sees the one-line error the call returns rather than the library's noise;
//   --log-level debug shows them.
// - abseil's mutex deadlock detection is off: Debian builds abseil without NDEBUG, so every
//   absl::Mutex (gRPC's locks) also records its lock order in one global graph, about 5% of a
//   loaded coordinator's CPU (bench/farm_load, docs/farm.md).
void SetUpGrpc();

}  // namespace pf
