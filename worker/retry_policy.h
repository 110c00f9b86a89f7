// How a worker rides out a coordinator that is away: which errors it waits out, and how long
// it waits between tries (exponential back-off with jitter, so that a restarted coordinator is
// not stormed by every worker at once, yet found again within kMaxBackoffSeconds).
#pragma once

#include <cstdint>
#include <random>

#include "absl/status/status.h"

namespace pf {

// A restarted coordinator is found again within this (plus the channel's own reconnect), yet
// a thousand waiting workers ask it less than a thousand times a second.
inline constexpr double kMaxBackoffSeconds = 2;
inline constexpr double kFirstBackoffSeconds = 0.25;

// Errors worth waiting out (the coordinator restarting, the network, a lease refused for
// now); others (a wrong token, a refused scene) end the worker.
bool Retryable(const absl::Status& status);

// The waits between failed tries: the n-th is uniform in [b/2, b] with
// b = min(kFirstBackoffSeconds * 2^(n-1), kMaxBackoffSeconds). Not thread-safe.
class Backoff {
public:
    explicit Backoff(uint64_t seed) : jitter_(seed) {}
    double NextWait();
    // After a success: the next failure waits the shortest again.
    void Reset() { ceiling_ = kFirstBackoffSeconds; }

private:
    double ceiling_ = kFirstBackoffSeconds;
    std::mt19937_64 jitter_;
};

}  // namespace pf
