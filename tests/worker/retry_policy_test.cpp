// The worker's retry policy: which errors it waits out, and back-off that doubles to its cap
// with jitter in [b/2, b].
#include "worker/retry_policy.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "tests/support/test_env.h"

namespace pf {
namespace {

TEST(RetryPolicyTest, WaitsOutTheCoordinatorAndTheNetworkButNotRefusals) {
    for (const absl::Status& status :
         {absl::UnavailableError("x"), absl::DeadlineExceededError("x"), absl::NotFoundError("x"),
          absl::DataLossError("x"), absl::ResourceExhaustedError("x"), absl::AbortedError("x"),
          absl::CancelledError("x")})
        EXPECT_TRUE(Retryable(status)) << status;
    for (const absl::Status& status :
         {absl::UnauthenticatedError("x"), absl::PermissionDeniedError("x"),
          absl::InvalidArgumentError("x"), absl::InternalError("x"),
          absl::FailedPreconditionError("x")})
        EXPECT_FALSE(Retryable(status)) << status;
}

TEST(RetryPolicyTest, BackoffDoublesToItsCapWithJitterAndResets) {
    const uint64_t seed = testing::TestSeed();
    RecordProperty("seed", std::to_string(seed));
    Backoff backoff(seed);
    double ceiling = kFirstBackoffSeconds;
    for (int attempt = 0; attempt < 12; ++attempt) {
        const double wait = backoff.NextWait();
        EXPECT_GE(wait, ceiling / 2) << "attempt " << attempt;
        EXPECT_LE(wait, ceiling) << "attempt " << attempt;
        ceiling = std::min(2 * ceiling, kMaxBackoffSeconds);
    }
    EXPECT_EQ(ceiling, kMaxBackoffSeconds);  // the cap was reached and held
    backoff.Reset();
    const double first = backoff.NextWait();
    EXPECT_GE(first, kFirstBackoffSeconds / 2);
    EXPECT_LE(first, kFirstBackoffSeconds);
}

}  // namespace
}  // namespace pf
