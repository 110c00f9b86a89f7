// Status code mapping.
#include "wire/rpc_status.h"

#include <grpc/support/log.h>
#include <spdlog/spdlog.h>

#include <chrono>

#include "absl/strings/str_cat.h"
#include "absl/synchronization/mutex.h"

namespace pf {
namespace {

grpc::StatusCode ToGrpcCode(absl::StatusCode code) {
    switch (code) {
        case absl::StatusCode::kOk:
            return grpc::StatusCode::OK;
        case absl::StatusCode::kCancelled:
            return grpc::StatusCode::CANCELLED;
        case absl::StatusCode::kInvalidArgument:
            return grpc::StatusCode::INVALID_ARGUMENT;
        case absl::StatusCode::kDeadlineExceeded:
            return grpc::StatusCode::DEADLINE_EXCEEDED;
        case absl::StatusCode::kNotFound:
            return grpc::StatusCode::NOT_FOUND;
        case absl::StatusCode::kAlreadyExists:
            return grpc::StatusCode::ALREADY_EXISTS;
        case absl::StatusCode::kPermissionDenied:
            return grpc::StatusCode::PERMISSION_DENIED;
        case absl::StatusCode::kResourceExhausted:
            return grpc::StatusCode::RESOURCE_EXHAUSTED;
        case absl::StatusCode::kFailedPrecondition:
            return grpc::StatusCode::FAILED_PRECONDITION;
        case absl::StatusCode::kAborted:
            return grpc::StatusCode::ABORTED;
        case absl::StatusCode::kOutOfRange:
            return grpc::StatusCode::OUT_OF_RANGE;
        case absl::StatusCode::kUnimplemented:
            return grpc::StatusCode::UNIMPLEMENTED;
        case absl::StatusCode::kInternal:
            return grpc::StatusCode::INTERNAL;
        case absl::StatusCode::kUnavailable:
            return grpc::StatusCode::UNAVAILABLE;
        case absl::StatusCode::kDataLoss:
            return grpc::StatusCode::DATA_LOSS;
        case absl::StatusCode::kUnauthenticated:
            return grpc::StatusCode::UNAUTHENTICATED;
        case absl::StatusCode::kUnknown:
            break;
        default:
            break;
    }
    return grpc::StatusCode::UNKNOWN;
}

absl::StatusCode FromGrpcCode(grpc::StatusCode code) {
    switch (code) {
        case grpc::StatusCode::OK:
            return absl::StatusCode::kOk;
        case grpc::StatusCode::CANCELLED:
            return absl::StatusCode::kCancelled;
        case grpc::StatusCode::INVALID_ARGUMENT:
            return absl::StatusCode::kInvalidArgument;
        case grpc::StatusCode::DEADLINE_EXCEEDED:
            return absl::StatusCode::kDeadlineExceeded;
        case grpc::StatusCode::NOT_FOUND:
            return absl::StatusCode::kNotFound;
        case grpc::StatusCode::ALREADY_EXISTS:
            return absl::StatusCode::kAlreadyExists;
        case grpc::StatusCode::PERMISSION_DENIED:
            return absl::StatusCode::kPermissionDenied;
        case grpc::StatusCode::RESOURCE_EXHAUSTED:
            return absl::StatusCode::kResourceExhausted;
        case grpc::StatusCode::FAILED_PRECONDITION:
            return absl::StatusCode::kFailedPrecondition;
        case grpc::StatusCode::ABORTED:
            return absl::StatusCode::kAborted;
        case grpc::StatusCode::OUT_OF_RANGE:
            return absl::StatusCode::kOutOfRange;
        case grpc::StatusCode::UNIMPLEMENTED:
            return absl::StatusCode::kUnimplemented;
        case grpc::StatusCode::INTERNAL:
            return absl::StatusCode::kInternal;
        case grpc::StatusCode::UNAVAILABLE:
            return absl::StatusCode::kUnavailable;
        case grpc::StatusCode::DATA_LOSS:
            return absl::StatusCode::kDataLoss;
        case grpc::StatusCode::UNAUTHENTICATED:
            return absl::StatusCode::kUnauthenticated;
        default:
            break;
    }
    return absl::StatusCode::kUnknown;
}

}  // namespace

void SetDeadline(grpc::ClientContext* context, double seconds) {
    context->set_deadline(std::chrono::system_clock::now() +
                          std::chrono::duration_cast<std::chrono::system_clock::duration>(
                              std::chrono::duration<double>(seconds)));
}

int HttpStatusCode(absl::StatusCode code) {
    switch (code) {
        case absl::StatusCode::kOk:
            return 200;
        case absl::StatusCode::kInvalidArgument:
        case absl::StatusCode::kOutOfRange:
            return 400;
        case absl::StatusCode::kUnauthenticated:
            return 401;
        case absl::StatusCode::kPermissionDenied:
            return 403;
        case absl::StatusCode::kNotFound:
            return 404;
        case absl::StatusCode::kAlreadyExists:
        case absl::StatusCode::kAborted:
        case absl::StatusCode::kFailedPrecondition:
            return 409;
        case absl::StatusCode::kResourceExhausted:
            return 429;
        case absl::StatusCode::kCancelled:
            return 499;
        case absl::StatusCode::kUnimplemented:
            return 501;
        case absl::StatusCode::kUnavailable:
            return 503;
        case absl::StatusCode::kDeadlineExceeded:
            return 504;
        case absl::StatusCode::kInternal:
        case absl::StatusCode::kDataLoss:
        case absl::StatusCode::kUnknown:
        default:
            return 500;
    }
}

grpc::Status ToGrpcStatus(const absl::Status& status) {
    if (status.ok()) return grpc::Status::OK;
    return grpc::Status(ToGrpcCode(status.code()), std::string(status.message()));
}

absl::Status FromGrpcStatus(const grpc::Status& status, const std::string& peer) {
    if (status.ok()) return absl::OkStatus();
    std::string message = status.error_message();
    if (status.error_code() == grpc::StatusCode::UNAVAILABLE ||
        status.error_code() == grpc::StatusCode::DEADLINE_EXCEEDED)
        message = absl::StrCat("cannot reach ", peer, " (", message, ")");
    else
        message = absl::StrCat(peer, ": ", message);
    return absl::Status(FromGrpcCode(status.error_code()), message);
}

void SetUpGrpc() {
    gpr_set_log_function([](gpr_log_func_args* args) {
        spdlog::debug("grpc: {} ({}:{})", args->message, args->file, args->line);
    });
    absl::SetMutexDeadlockDetectionMode(absl::OnDeadlockCycle::kIgnore);
}

}  // namespace pf
