// The dashboard over HTTP, or HTTPS with the coordinator's certificate (cpp-httplib): the
// DashboardApi's routes, plus the event streams the pages follow (server-sent events), which
// need a connection held open. Runs its own threads until destroyed.
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <thread>

#include "absl/status/statusor.h"
#include "server/dashboard_api.h"
#include "wire/server_security.h"

namespace httplib {
class Server;
}

namespace pf {

class DashboardServer {
public:
    // Event streams open at once; past this one gets 429 (each holds a thread).
    static constexpr int kMaxStreams = 48;

    // Listens on `address` ("host:port"; port 0 picks a free one): HTTPS with the
    // certificate and key of `security` unless it is plain text. UNAVAILABLE naming the
    // address when it cannot listen. `coordinator` and `access` must outlive the server.
    static absl::StatusOr<std::unique_ptr<DashboardServer>> Start(const std::string& address,
                                                                  const ServerSecurity& security,
                                                                  Coordinator& coordinator,
                                                                  const AccessControl& access);
    ~DashboardServer();  // closes the event streams and stops listening

    int Port() const { return port_; }
    // "https://HOST:PORT/", for the log and for scripts.
    const std::string& Url() const { return url_; }

private:
    DashboardServer(Coordinator& coordinator, const AccessControl& access);
    void Route();

    DashboardApi api_;
    std::unique_ptr<httplib::Server> http_;
    std::thread thread_;
    std::atomic<bool> stopping_{false};
    std::atomic<int> streams_{0};
    int port_ = 0;
    std::string url_;
};

}  // namespace pf
