// Session ids and CSRF tokens.
#include "server/dashboard_sessions.h"

#include <openssl/rand.h>

#include <algorithm>
#include <array>

#include "core/util/check.h"

namespace pf {

std::string RandomToken() {
    std::array<unsigned char, 32> bytes;
    PF_CHECK(RAND_bytes(bytes.data(), static_cast<int>(bytes.size())) == 1);
    static constexpr char kHex[] = "0123456789abcdef";
    std::string token;
    for (unsigned char byte : bytes) {
        token += kHex[byte >> 4];
        token += kHex[byte & 15];
    }
    return token;
}

std::pair<std::string, DashboardSession> DashboardSessions::Open(const std::string& name) {
    const Clock::time_point now = now_();
    DashboardSession session{name, RandomToken(), now + kLifetime};
    std::string id = RandomToken();
    std::lock_guard lock(mutex_);
    std::erase_if(sessions_, [&](const auto& entry) { return entry.second.expires <= now; });
    if (sessions_.size() >= kCapacity) {
        auto oldest = std::min_element(sessions_.begin(), sessions_.end(), [](auto& a, auto& b) {
            return a.second.expires < b.second.expires;
        });
        sessions_.erase(oldest);
    }
    sessions_[id] = session;
    return {std::move(id), std::move(session)};
}

std::optional<DashboardSession> DashboardSessions::Find(const std::string& id) const {
    std::lock_guard lock(mutex_);
    const auto it = sessions_.find(id);
    if (it == sessions_.end() || it->second.expires <= now_()) return std::nullopt;
    return it->second;
}

void DashboardSessions::Close(const std::string& id) {
    std::lock_guard lock(mutex_);
    sessions_.erase(id);
}

}  // namespace pf
