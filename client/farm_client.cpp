// Jobs service calls.
#include "client/farm_client.h"

#include <grpcpp/client_context.h>

#include <chrono>

#include "absl/strings/str_cat.h"
#include "core/util/command_line.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "wire/proto_convert.h"
#include "wire/rpc_status.h"

namespace pf {
namespace {

namespace v1 = photonfarm::v1;

// Unary calls other than submit answer at once; submit runs the camera pass first.
constexpr double kCallSeconds = 30;
constexpr double kSubmitSeconds = 600;

}  // namespace

void AddServerOption(CLI::App* command, ServerFlags* server) {
    command->add_option("--server", server->address, "Coordinator address HOST:PORT")
        ->envname("PHOTONFARM_SERVER")
        ->required()
        ->check(HostAndPort(1));
    AddChannelSecurityOptions(command, &server->security, kClientTokenEnv);
}

FarmClient::FarmClient(std::string address, std::shared_ptr<grpc::Channel> channel)
    : peer_(absl::StrCat("coordinator at ", address)),
      channel_(std::move(channel)),
      stub_(v1::Jobs::NewStub(channel_)) {}

absl::StatusOr<FarmClient> FarmClient::Connect(const ServerFlags& server, double timeout_seconds) {
    absl::StatusOr<ChannelSecurity> security =
        LoadChannelSecurity(server.security, kClientTokenEnv);
    if (!security.ok()) return security.status();
    return Connect(server.address, *security, timeout_seconds);
}

absl::StatusOr<FarmClient> FarmClient::Connect(const std::string& address,
                                               const ChannelSecurity& security,
                                               double timeout_seconds) {
    std::shared_ptr<grpc::Channel> channel = OpenChannel(address, security);
    const auto deadline = std::chrono::system_clock::now() +
                          std::chrono::duration_cast<std::chrono::system_clock::duration>(
                              std::chrono::duration<double>(timeout_seconds));
    if (!channel->WaitForConnected(deadline))
        return absl::UnavailableError(absl::StrCat(
            "cannot reach the coordinator at ", address, " (no ",
            security.plaintext ? "plain-text" : "TLS", " connection within ", timeout_seconds,
            " s: nothing listening, ",
            security.plaintext
                ? "or it serves TLS"
                : "a certificate not from --tls-ca or not for this name, or --plaintext there",
            ")"));
    return FarmClient(address, std::move(channel));
}

template <typename Response, typename Request, typename Method>
absl::StatusOr<Response> FarmClient::Unary(Method method, const Request& request, double seconds) {
    grpc::ClientContext context;
    SetDeadline(&context, seconds);
    Response response;
    if (grpc::Status status = (stub_.get()->*method)(&context, request, &response); !status.ok())
        return FromGrpcStatus(status, peer_);
    return response;
}

absl::StatusOr<v1::JobStatus> FarmClient::Submit(const v1::SubmitJobRequest& request) {
    absl::StatusOr<v1::SubmitJobResponse> response =
        Unary<v1::SubmitJobResponse>(&v1::Jobs::Stub::SubmitJob, request, kSubmitSeconds);
    if (!response.ok()) return response.status();
    return response->status();
}

absl::StatusOr<v1::JobStatus> FarmClient::Cancel(const std::string& job_id) {
    v1::CancelJobRequest request;
    request.set_job_id(job_id);
    absl::StatusOr<v1::CancelJobResponse> response =
        Unary<v1::CancelJobResponse>(&v1::Jobs::Stub::CancelJob, request, kCallSeconds);
    if (!response.ok()) return response.status();
    return response->status();
}

absl::StatusOr<v1::ListJobsResponse> FarmClient::ListJobs() {
    return Unary<v1::ListJobsResponse>(&v1::Jobs::Stub::ListJobs, v1::ListJobsRequest(),
                                       kCallSeconds);
}

absl::StatusOr<v1::ListWorkersResponse> FarmClient::ListWorkers() {
    return Unary<v1::ListWorkersResponse>(&v1::Jobs::Stub::ListWorkers, v1::ListWorkersRequest(),
                                          kCallSeconds);
}

absl::StatusOr<v1::GetResultResponse> FarmClient::GetResult(const std::string& job_id) {
    v1::GetResultRequest request;
    request.set_job_id(job_id);
    return Unary<v1::GetResultResponse>(&v1::Jobs::Stub::GetResult, request, kSubmitSeconds);
}

absl::Status FarmClient::CheckHealth() {
    grpc::ClientContext context;
    SetDeadline(&context, kCallSeconds);
    grpc::health::v1::HealthCheckResponse response;
    const grpc::Status status = grpc::health::v1::Health::NewStub(channel_)->Check(
        &context, grpc::health::v1::HealthCheckRequest(), &response);
    if (!status.ok()) return FromGrpcStatus(status, peer_);
    if (response.status() != grpc::health::v1::HealthCheckResponse::SERVING)
        return absl::UnavailableError(absl::StrCat(
            peer_, ": health ",
            grpc::health::v1::HealthCheckResponse::ServingStatus_Name(response.status())));
    return absl::OkStatus();
}

absl::StatusOr<JobConvergence> FarmClient::Convergence(const std::string& job_id) {
    v1::GetConvergenceRequest request;
    request.set_job_id(job_id);
    absl::StatusOr<v1::GetConvergenceResponse> response =
        Unary<v1::GetConvergenceResponse>(&v1::Jobs::Stub::GetConvergence, request, kCallSeconds);
    if (!response.ok()) return response.status();
    JobConvergence convergence{response->status().name(), {}};
    for (const v1::ConvergencePoint& point : response->points())
        convergence.points.push_back(FromProto(point, response->pixels()));
    return convergence;
}

absl::StatusOr<v1::Snapshot> FarmClient::Watch(
    const std::string& job_id, double interval_seconds, bool images,
    const std::function<bool(const v1::Snapshot&)>& on_snapshot, double deadline_seconds) {
    grpc::ClientContext context;
    if (deadline_seconds > 0) SetDeadline(&context, deadline_seconds);
    v1::WatchJobRequest request;
    request.set_job_id(job_id);
    request.set_interval_seconds(interval_seconds);
    request.set_images(images);
    std::unique_ptr<grpc::ClientReader<v1::Snapshot>> reader = stub_->WatchJob(&context, request);
    v1::Snapshot snapshot, last;
    bool stopped = false;
    while (reader->Read(&snapshot)) {
        const bool go_on = on_snapshot(snapshot);
        last = std::move(snapshot);
        if (!go_on) {
            stopped = true;
            context.TryCancel();
            while (reader->Read(&snapshot)) {
            }
            break;
        }
    }
    const grpc::Status status = reader->Finish();
    if (status.ok() || stopped) return last;
    if (status.error_code() == grpc::StatusCode::DEADLINE_EXCEEDED && deadline_seconds > 0)
        return absl::DeadlineExceededError(absl::StrCat(
            peer_, ": job ", job_id, " did not end within ", deadline_seconds,
            " s; last seen: ", last.has_status() ? StatusLine(last.status()) : "no snapshot"));
    return FromGrpcStatus(status, peer_);
}

std::string StatusLine(const v1::JobStatus& status) {
    std::string line = absl::StrCat(StateName(status.state()), ", ", status.epochs(), " epochs, ",
                                    status.photons(), " photons, ", status.workers_active(),
                                    " workers active, ", status.elapsed_seconds(), " s");
    if (status.has_estimated_error())
        absl::StrAppend(&line, ", estimated error ", status.estimated_error());
    if (!status.message().empty()) absl::StrAppend(&line, ", ", status.message());
    return line;
}

std::string StateName(v1::JobState state) {
    switch (state) {
        case v1::JOB_STATE_RUNNING:
            return "running";
        case v1::JOB_STATE_DONE:
            return "done";
        case v1::JOB_STATE_CANCELLED:
            return "cancelled";
        case v1::JOB_STATE_FAILED:
            return "failed";
        default:
            return "unknown";
    }
}

}  // namespace pf
