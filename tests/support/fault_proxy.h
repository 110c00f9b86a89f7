// A TCP proxy for tests that puts a bad network between a worker and the coordinator: it
// listens on 127.0.0.1 (an ephemeral port), forwards every connection to a target, and on
// request delays each piece of data by a fixed time plus a random jitter (in order, as TCP
// delivers), resets every open connection, or partitions: forwards nothing either way (new
// connections wait) until healed. TLS passes through untouched. Stops and joins everything it
// started when destroyed.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "absl/status/statusor.h"

namespace pf::testing {

class FaultProxy {
public:
    // Forwards to `target` ("127.0.0.1:PORT").
    static absl::StatusOr<std::unique_ptr<FaultProxy>> Start(const std::string& target);
    ~FaultProxy();
    FaultProxy(const FaultProxy&) = delete;
    FaultProxy& operator=(const FaultProxy&) = delete;

    std::string Address() const;  // 127.0.0.1:PORT, for the workers
    // Every piece of data forwarded from now on waits `seconds` plus a uniform draw in
    // [0, jitter_seconds] (never overtaking the piece before it).
    void SetDelay(double seconds, double jitter_seconds);
    // Resets every open connection (RST): calls on them fail, and the peers reconnect.
    void DropConnections();
    // While partitioned nothing is forwarded either way and new connections wait.
    void Partition(bool partitioned);
    uint64_t ConnectionsAccepted() const { return accepted_.load(); }

private:
    struct Connection;
    FaultProxy(int listen_fd, int port, std::string target_host, int target_port, uint64_t seed);
    void AcceptLoop();
    void Pump(std::shared_ptr<Connection> connection, bool upstream);
    // Waits until not partitioned and the piece's release time; false when stopping.
    bool WaitToForward(std::chrono::steady_clock::time_point& release);

    const int listen_fd_, port_;
    const std::string target_host_;
    const int target_port_;
    std::atomic<bool> stopping_{false};
    std::atomic<uint64_t> accepted_{0};
    mutable std::mutex mutex_;  // guards what follows
    std::condition_variable changed_;
    double delay_seconds_ = 0, jitter_seconds_ = 0;
    bool partitioned_ = false;
    std::mt19937_64 rng_;
    std::vector<std::shared_ptr<Connection>> connections_;
    std::vector<std::thread> threads_;  // the pumps
    std::thread acceptor_;
};

}  // namespace pf::testing
