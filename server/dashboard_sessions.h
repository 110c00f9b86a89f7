// The dashboard's logins: a session per login, named by a random id (the browser's cookie),
// holding the client name its token opened and a CSRF token the page sends back with every
// action. Sessions expire `lifetime` after their login; past `capacity` the oldest goes.
// Thread-safe.
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>

namespace pf {

struct DashboardSession {
    std::string name;        // the client token's name, or the address where no tokens are set
    std::string csrf_token;  // sent back in X-CSRF-Token with each action
    std::chrono::steady_clock::time_point expires;
};

class DashboardSessions {
public:
    using Clock = std::chrono::steady_clock;
    static constexpr std::chrono::hours kLifetime{12};
    static constexpr size_t kCapacity = 4096;

    explicit DashboardSessions(std::function<Clock::time_point()> now = Clock::now)
        : now_(std::move(now)) {}

    // A new session for `name`: its id (the cookie's value) and the session.
    std::pair<std::string, DashboardSession> Open(const std::string& name);
    // The live session with this id; none for an unknown or expired one.
    std::optional<DashboardSession> Find(const std::string& id) const;
    void Close(const std::string& id);

private:
    std::function<Clock::time_point()> now_;
    mutable std::mutex mutex_;
    std::map<std::string, DashboardSession> sessions_;  // by id
};

// 32 random bytes from OpenSSL's generator, in hex: a session id or a CSRF token.
std::string RandomToken();

}  // namespace pf
