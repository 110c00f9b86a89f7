// The client side of a coordinator's Jobs service, for the command line: the server address
// (flag or environment), a connection that fails fast and clearly, and each call with its
// errors as one-line statuses.
#pragma once

#include <grpcpp/channel.h>

#include <CLI/CLI.hpp>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "core/estimate/convergence.h"
#include "photonfarm/v1/jobs.grpc.pb.h"
#include "wire/secure_channel.h"

namespace pf {

// Where the coordinator is and how to reach it, as the command line gives it.
struct ServerFlags {
    std::string address;
    ChannelSecurityFlags security;
};

// Adds --server ADDR (or PHOTONFARM_SERVER), the TLS options and --token-file (or
// PHOTONFARM_CLIENT_TOKEN) to `command`.
void AddServerOption(CLI::App* command, ServerFlags* server);

// A job's convergence log, for `--report`.
struct JobConvergence {
    std::string name;
    std::vector<ConvergencePoint> points;
};

class FarmClient {
public:
    // Waits up to `timeout_seconds` for the coordinator: UNAVAILABLE naming it if it cannot be
    // reached (nothing listening, or a TLS handshake that failed).
    static absl::StatusOr<FarmClient> Connect(const std::string& address,
                                              const ChannelSecurity& security,
                                              double timeout_seconds = 5);
    // Reads the files the flags name first.
    static absl::StatusOr<FarmClient> Connect(const ServerFlags& server,
                                              double timeout_seconds = 5);

    absl::StatusOr<photonfarm::v1::JobStatus> Submit(
        const photonfarm::v1::SubmitJobRequest& request);
    absl::StatusOr<photonfarm::v1::JobStatus> Cancel(const std::string& job_id);
    absl::StatusOr<photonfarm::v1::ListJobsResponse> ListJobs();
    absl::StatusOr<photonfarm::v1::ListWorkersResponse> ListWorkers();
    absl::StatusOr<photonfarm::v1::GetResultResponse> GetResult(const std::string& job_id);
    absl::StatusOr<JobConvergence> Convergence(const std::string& job_id);
    // The standard health service (grpc.health.v1, no token needed): OK when it answers
    // SERVING, UNAVAILABLE naming the status otherwise.
    absl::Status CheckHealth();
    // Streams snapshots to `on_snapshot` until the job ends or `on_snapshot` returns false
    // (the cancel path: the stream is cancelled at once); returns the last one. The coordinator
    // sends a snapshot only when the job changes, so a stalled job sends none: with
    // `deadline_seconds` > 0 the watch gives up that many seconds after it began with
    // DEADLINE_EXCEEDED naming the job and its last state seen. 0 (the command line's watch):
    // no deadline, since a user's watch of a long job must last as long as the job.
    absl::StatusOr<photonfarm::v1::Snapshot> Watch(
        const std::string& job_id, double interval_seconds, bool images,
        const std::function<bool(const photonfarm::v1::Snapshot&)>& on_snapshot,
        double deadline_seconds = 0);

private:
    FarmClient(std::string address, std::shared_ptr<grpc::Channel> channel);
    // One unary call of the Jobs service with a deadline `seconds` away.
    template <typename Response, typename Request, typename Method>
    absl::StatusOr<Response> Unary(Method method, const Request& request, double seconds);

    std::string peer_;  // "coordinator at ADDR", for messages
    std::shared_ptr<grpc::Channel> channel_;
    std::shared_ptr<photonfarm::v1::Jobs::Stub> stub_;
};

// A job's state in words: "running", "done", ...
std::string StateName(photonfarm::v1::JobState state);
// A job's status in one line, for messages: state, epochs, photons, workers, seconds, the
// estimated error once known, and why it ended where it failed or was cancelled.
std::string StatusLine(const photonfarm::v1::JobStatus& status);

}  // namespace pf
