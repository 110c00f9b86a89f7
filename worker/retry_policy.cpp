// The worker's retry policy; see retry_policy.h.
#include "worker/retry_policy.h"

#include <algorithm>

namespace pf {

bool Retryable(const absl::Status& status) {
    return absl::IsUnavailable(status) || absl::IsDeadlineExceeded(status) ||
           absl::IsNotFound(status) || absl::IsDataLoss(status) ||
           absl::IsResourceExhausted(status) || absl::IsAborted(status) ||
           absl::IsCancelled(status);
}

double Backoff::NextWait() {
    const double wait = ceiling_ * std::uniform_real_distribution<double>(0.5, 1.0)(jitter_);
    ceiling_ = std::min(ceiling_ * 2, kMaxBackoffSeconds);
    return wait;
}

}  // namespace pf
