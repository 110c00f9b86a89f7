// The fault-injecting TCP proxy (fault_proxy.h).
#include "tests/support/fault_proxy.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstring>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"

namespace pf::testing {
namespace {

using SteadyClock = std::chrono::steady_clock;

// How often a blocked pump looks whether the proxy is stopping.
constexpr int kPollMilliseconds = 50;

sockaddr_in Loopback(const std::string& host, int port) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<uint16_t>(port));
    inet_pton(AF_INET, host.c_str(), &address.sin_addr);
    return address;
}

bool WriteAll(int fd, const char* data, size_t size) {
    while (size > 0) {
        const ssize_t written = send(fd, data, size, MSG_NOSIGNAL);
        if (written <= 0) return false;
        data += written;
        size -= static_cast<size_t>(written);
    }
    return true;
}

}  // namespace

struct FaultProxy::Connection {
    int client_fd = -1, server_fd = -1;
    std::atomic<bool> closed{false};
    // Closes both ends once (with RST when `reset`), waking both pumps.
    void Close(bool reset) {
        if (closed.exchange(true)) return;
        for (int fd : {client_fd, server_fd}) {
            if (reset) {
                const linger hard{1, 0};
                setsockopt(fd, SOL_SOCKET, SO_LINGER, &hard, sizeof(hard));
            }
            shutdown(fd, SHUT_RDWR);
        }
    }
    ~Connection() {
        close(client_fd);
        close(server_fd);
    }
};

absl::StatusOr<std::unique_ptr<FaultProxy>> FaultProxy::Start(const std::string& target) {
    const size_t colon = target.rfind(':');
    int target_port = 0;
    if (colon == std::string::npos || !absl::SimpleAtoi(target.substr(colon + 1), &target_port))
        return absl::InvalidArgumentError(absl::StrCat("fault proxy: bad target '", target, "'"));
    const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in address = Loopback("127.0.0.1", 0);
    socklen_t length = sizeof(address);
    if (fd < 0 || bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0 ||
        listen(fd, 64) != 0 ||
        getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length) != 0) {
        if (fd >= 0) close(fd);
        return absl::UnavailableError(
            absl::StrCat("fault proxy: cannot listen: ", strerror(errno)));
    }
    std::unique_ptr<FaultProxy> proxy(new FaultProxy(
        fd, ntohs(address.sin_port), target.substr(0, colon), target_port, std::random_device()()));
    proxy->acceptor_ = std::thread([raw = proxy.get()] { raw->AcceptLoop(); });
    return proxy;
}

FaultProxy::FaultProxy(int listen_fd, int port, std::string target_host, int target_port,
                       uint64_t seed)
    : listen_fd_(listen_fd),
      port_(port),
      target_host_(std::move(target_host)),
      target_port_(target_port),
      rng_(seed) {}

FaultProxy::~FaultProxy() {
    stopping_ = true;
    {
        std::lock_guard lock(mutex_);
        changed_.notify_all();
        for (const std::shared_ptr<Connection>& connection : connections_) connection->Close(false);
    }
    acceptor_.join();
    for (std::thread& thread : threads_) thread.join();
    close(listen_fd_);
}

std::string FaultProxy::Address() const { return absl::StrCat("127.0.0.1:", port_); }

void FaultProxy::SetDelay(double seconds, double jitter_seconds) {
    std::lock_guard lock(mutex_);
    delay_seconds_ = seconds;
    jitter_seconds_ = jitter_seconds;
}

void FaultProxy::DropConnections() {
    std::lock_guard lock(mutex_);
    for (const std::shared_ptr<Connection>& connection : connections_) connection->Close(true);
}

void FaultProxy::Partition(bool partitioned) {
    std::lock_guard lock(mutex_);
    partitioned_ = partitioned;
    changed_.notify_all();
}

void FaultProxy::AcceptLoop() {
    while (!stopping_) {
        pollfd listening{listen_fd_, POLLIN, 0};
        if (poll(&listening, 1, kPollMilliseconds) <= 0) continue;
        const int client = accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
        if (client < 0) continue;
        ++accepted_;
        auto connection = std::make_shared<Connection>();
        connection->client_fd = client;
        connection->server_fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
        const sockaddr_in target = Loopback(target_host_, target_port_);
        if (connect(connection->server_fd, reinterpret_cast<const sockaddr*>(&target),
                    sizeof(target)) != 0) {
            connection->Close(true);
            continue;
        }
        std::lock_guard lock(mutex_);
        connections_.push_back(connection);
        threads_.emplace_back([this, connection] { Pump(connection, true); });
        threads_.emplace_back([this, connection] { Pump(connection, false); });
    }
}

bool FaultProxy::WaitToForward(SteadyClock::time_point& release) {
    std::unique_lock lock(mutex_);
    const auto delay = std::chrono::duration<double>(
        delay_seconds_ + std::uniform_real_distribution<double>(0, jitter_seconds_)(rng_));
    release = std::max(
        release, SteadyClock::now() + std::chrono::duration_cast<SteadyClock::duration>(delay));
    while (!stopping_ && (partitioned_ || SteadyClock::now() < release))
        changed_.wait_until(
            lock, partitioned_ ? SteadyClock::now() + std::chrono::milliseconds(kPollMilliseconds)
                               : release);
    return !stopping_;
}

void FaultProxy::Pump(std::shared_ptr<Connection> connection, bool upstream) {
    const int from = upstream ? connection->client_fd : connection->server_fd;
    const int to = upstream ? connection->server_fd : connection->client_fd;
    std::vector<char> buffer(1 << 16);
    SteadyClock::time_point release{};
    while (!connection->closed) {
        pollfd readable{from, POLLIN, 0};
        if (poll(&readable, 1, kPollMilliseconds) <= 0) continue;
        const ssize_t got = recv(from, buffer.data(), buffer.size(), 0);
        if (got <= 0 || !WaitToForward(release) ||
            !WriteAll(to, buffer.data(), static_cast<size_t>(got)))
            break;
    }
    connection->Close(false);
}

}  // namespace pf::testing
