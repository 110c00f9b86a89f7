// The browser dashboard's handlers, with no transport: a request in, a response out, so they
// are tested without a socket (server/dashboard_server.h serves them over HTTP(S)). The page
// and its script, JSON endpoints (the Jobs service's messages, as `photonfarm ... --json`
// prints them), the image as PNG and EXR, login and cancel. docs/operations.md lists the
// endpoints.
//
// Who may call: where client tokens are configured, a login (POST /api/login with a client
// token) opens a session whose id travels in an HttpOnly, SameSite=Strict cookie (Secure under
// TLS); scripts may send "Authorization: Bearer TOKEN" instead. A worker's token opens nothing.
// Actions (cancel, logout) from a session must carry its CSRF token in X-CSRF-Token, and a
// request whose Origin is not this server's is refused. Thread-safe.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"
#include "server/access_control.h"
#include "server/coordinator.h"
#include "server/dashboard_sessions.h"

namespace pf {

struct HttpRequest {
    std::string method;  // "GET", "POST"
    std::string path;    // without the query
    std::map<std::string, std::string> query;
    std::map<std::string, std::string> headers;  // names in lower case
    std::string body;
    std::string peer;  // the caller's address, its name where no tokens are configured
};

struct HttpResponse {
    int status = 200;
    std::string content_type;
    std::string body;
    std::vector<std::pair<std::string, std::string>> headers;  // besides Content-Type
};

class DashboardApi {
public:
    static constexpr char kSessionCookie[] = "pf_session";
    static constexpr char kCsrfHeader[] = "x-csrf-token";

    // Both must outlive this object.
    DashboardApi(Coordinator& coordinator, const AccessControl& access);

    HttpResponse Handle(const HttpRequest& request);

    // The caller's name, if it may read: UNAUTHENTICATED or PERMISSION_DENIED otherwise.
    // For the event streams, which the server writes itself.
    absl::StatusOr<std::string> Authenticate(const HttpRequest& request) const;
    // A refusal as the dashboard answers it: the HTTP code of its status, a JSON body
    // {"code": "NOT_FOUND", "error": "..."}.
    static HttpResponse Error(const absl::Status& status);
    // The job's event stream's next message: its status and the convergence points after the
    // first `points_sent` (updated), as JSON.
    std::string JobEvent(const Job& job, size_t* points_sent) const;

    Coordinator& coordinator() const { return coordinator_; }

private:
    HttpResponse Login(const HttpRequest& request);
    HttpResponse Session(const HttpRequest& request);
    HttpResponse Logout(const HttpRequest& request);
    // {"name", "csrf_token", "tokens_required"}: what the page learns of its session.
    HttpResponse SessionJson(const DashboardSession& session) const;
    HttpResponse JobRequest(const HttpRequest& request, const std::string& job_id,
                            const std::string& what);
    // The session the request's cookie names, if live.
    std::optional<std::pair<std::string, DashboardSession>> CookieSession(
        const HttpRequest& request) const;
    // OK when an action may go ahead: a bearer token, or a session's cookie with its CSRF token.
    absl::Status CheckAction(const HttpRequest& request) const;
    std::string SessionCookie(const std::string& id, bool expire) const;

    Coordinator& coordinator_;
    const AccessControl& access_;
    DashboardSessions sessions_;
};

}  // namespace pf
