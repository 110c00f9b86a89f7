// Dashboard routes: the page, the JSON endpoints, images, login and actions.
#include "server/dashboard_api.h"

#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "absl/strings/strip.h"
#include "core/film/exr_io.h"
#include "core/film/png_writer.h"
#include "server/job_views.h"
#include "server/web/dashboard.css.h"
#include "server/web/dashboard.html.h"
#include "server/web/dashboard.js.h"
#include "wire/json.h"
#include "wire/proto_convert.h"
#include "wire/rpc_status.h"

namespace pf {
namespace {

namespace v1 = photonfarm::v1;

constexpr char kJson[] = "application/json";

HttpResponse Json(std::string body) { return {200, kJson, std::move(body), {}}; }

HttpResponse Asset(std::string_view body, const char* type) {
    return {200, type, std::string(body), {{"Cache-Control", "no-cache"}}};
}

// The value of `name` in a Cookie header ("a=1; pf_session=...").
std::string CookieValue(const std::map<std::string, std::string>& headers, absl::string_view name) {
    const auto cookie = headers.find("cookie");
    if (cookie == headers.end()) return "";
    for (absl::string_view part : absl::StrSplit(cookie->second, ';')) {
        part = absl::StripAsciiWhitespace(part);
        if (absl::ConsumePrefix(&part, name) && absl::ConsumePrefix(&part, "="))
            return std::string(part);
    }
    return "";
}

// The "token" field of the login's JSON body ({"token": "..."}); empty when the body is not
// such an object.
std::string TokenField(const std::string& body) {
    const nlohmann::json parsed = nlohmann::json::parse(body, nullptr, /*allow_exceptions=*/false);
    if (!parsed.is_object()) return "";
    const auto token = parsed.find("token");
    return token != parsed.end() && token->is_string() ? token->get<std::string>() : "";
}

// The request's Origin, when it has one, names this server (its Host header).
absl::Status CheckOrigin(const HttpRequest& request) {
    const auto origin = request.headers.find("origin");
    if (origin == request.headers.end()) return absl::OkStatus();
    const auto host = request.headers.find("host");
    absl::string_view origin_host = origin->second;
    if (!absl::ConsumePrefix(&origin_host, "https://"))
        absl::ConsumePrefix(&origin_host, "http://");
    if (host == request.headers.end() || origin_host != host->second)
        return absl::PermissionDeniedError(
            absl::StrCat("Origin ", origin->second,
                         " is not this dashboard's: cross-site requests are refused"));
    return absl::OkStatus();
}

}  // namespace

DashboardApi::DashboardApi(Coordinator& coordinator, const AccessControl& access)
    : coordinator_(coordinator),
      access_(access),
      sessions_([&coordinator] { return coordinator.Options().now(); }) {}

HttpResponse DashboardApi::Error(const absl::Status& status) {
    const nlohmann::json body = {{"code", absl::StatusCodeToString(status.code())},
                                 {"error", std::string(status.message())}};
    return {HttpStatusCode(status.code()), kJson, body.dump(), {}};
}

std::string DashboardApi::SessionCookie(const std::string& id, bool expire) const {
    return absl::StrCat(
        kSessionCookie, "=", id, "; Path=/; HttpOnly; SameSite=Strict",
        access_.Encrypted() ? "; Secure" : "",
        expire ? "; Max-Age=0"
               : absl::StrCat("; Max-Age=",
                              std::chrono::seconds(DashboardSessions::kLifetime).count()));
}

std::optional<std::pair<std::string, DashboardSession>> DashboardApi::CookieSession(
    const HttpRequest& request) const {
    const std::string id = CookieValue(request.headers, kSessionCookie);
    if (id.empty()) return std::nullopt;
    std::optional<DashboardSession> session = sessions_.Find(id);
    if (!session) return std::nullopt;
    return std::pair{id, std::move(*session)};
}

absl::StatusOr<std::string> DashboardApi::Authenticate(const HttpRequest& request) const {
    if (const auto header = request.headers.find("authorization");
        header != request.headers.end()) {
        absl::string_view value = header->second;
        if (!absl::ConsumePrefix(&value, "Bearer "))
            return absl::UnauthenticatedError(
                "the Authorization header must read \"Bearer TOKEN\"");
        if (!access_.TokensRequired(Role::kClient)) return request.peer;
        const std::string secret(value);
        return access_.AuthorizeToken(&secret, Role::kClient);
    }
    if (const auto session = CookieSession(request)) return session->second.name;
    if (!access_.TokensRequired(Role::kClient)) return request.peer;
    return absl::UnauthenticatedError("log in with a client token (POST /api/login)");
}

absl::Status DashboardApi::CheckAction(const HttpRequest& request) const {
    if (absl::Status origin = CheckOrigin(request); !origin.ok()) return origin;
    if (request.headers.contains("authorization")) return Authenticate(request).status();
    const auto session = CookieSession(request);
    if (!session) {
        if (absl::Status allowed = Authenticate(request).status(); !allowed.ok()) return allowed;
        return absl::PermissionDeniedError(
            "no session: actions need the CSRF token of a session (GET /api/session)");
    }
    const auto csrf = request.headers.find(kCsrfHeader);
    if (csrf == request.headers.end() ||
        !ConstantTimeEqual(csrf->second, session->second.csrf_token))
        return absl::PermissionDeniedError(
            "the request's X-CSRF-Token does not match its session's: reload the page");
    return absl::OkStatus();
}

HttpResponse DashboardApi::SessionJson(const DashboardSession& session) const {
    const nlohmann::json body = {{"name", session.name},
                                 {"csrf_token", session.csrf_token},
                                 {"tokens_required", access_.TokensRequired(Role::kClient)}};
    return Json(body.dump());
}

HttpResponse DashboardApi::Login(const HttpRequest& request) {
    if (absl::Status origin = CheckOrigin(request); !origin.ok()) return Error(origin);
    std::string name = request.peer;
    if (access_.TokensRequired(Role::kClient)) {
        const std::string token = TokenField(request.body);
        absl::StatusOr<std::string> authorized =
            access_.AuthorizeToken(token.empty() ? nullptr : &token, Role::kClient);
        if (!authorized.ok()) return Error(authorized.status());
        name = std::move(*authorized);
    }
    auto [id, session] = sessions_.Open(name);
    HttpResponse response = SessionJson(session);
    response.headers.emplace_back("Set-Cookie", SessionCookie(id, false));
    return response;
}

// The page's first question: who am I, and my CSRF token. Where no tokens are configured a
// session opens without a login.
HttpResponse DashboardApi::Session(const HttpRequest& request) {
    if (const auto session = CookieSession(request)) return SessionJson(session->second);
    if (!access_.TokensRequired(Role::kClient)) return Login(request);
    return Error(absl::UnauthenticatedError("log in with a client token (POST /api/login)"));
}

HttpResponse DashboardApi::Logout(const HttpRequest& request) {
    if (absl::Status allowed = CheckAction(request); !allowed.ok()) return Error(allowed);
    if (const auto session = CookieSession(request)) sessions_.Close(session->first);
    HttpResponse response = Json("{}");
    response.headers.emplace_back("Set-Cookie", SessionCookie("", true));
    return response;
}

std::string DashboardApi::JobEvent(const Job& job, size_t* points_sent) const {
    v1::GetConvergenceResponse view = ConvergenceView(job, coordinator_.Options().now());
    const size_t total = static_cast<size_t>(view.points_size());
    const size_t skip = std::min(*points_sent, total);
    view.mutable_points()->DeleteSubrange(0, static_cast<int>(skip));
    *points_sent = total;
    return ToJson(view);
}

HttpResponse DashboardApi::JobRequest(const HttpRequest& request, const std::string& job_id,
                                      const std::string& what) {
    if (what == "cancel") {
        if (request.method != "POST") return Error(absl::UnimplementedError("cancel: use POST"));
        if (absl::Status allowed = CheckAction(request); !allowed.ok()) return Error(allowed);
        absl::StatusOr<JobProgress> progress =
            coordinator_.Cancel(job_id, "cancelled from the dashboard");
        if (!progress.ok()) return Error(progress.status());
        v1::CancelJobResponse response;
        *response.mutable_status() = ToProto(*progress);
        return Json(ToJson(response));
    }
    absl::StatusOr<std::shared_ptr<Job>> job = coordinator_.FindJob(job_id);
    if (!job.ok()) return Error(job.status());
    if (what.empty()) return Json(ToJson(ConvergenceView(**job, coordinator_.Options().now())));
    if (what != "image.png" && what != "image.exr")
        return Error(absl::NotFoundError(absl::StrCat("no such page: ", request.path)));
    const std::shared_ptr<const Image> image = (*job)->CurrentImage();
    if (!image)
        return Error(absl::NotFoundError(absl::StrCat("job ", job_id, " has no image yet")));
    if (what == "image.exr") {
        absl::StatusOr<std::string> exr = EncodeExr(*image, {{"photonfarm:job", job_id}});
        if (!exr.ok()) return Error(exr.status());
        return {200,
                "image/x-exr",
                std::move(*exr),
                {{"Content-Disposition", absl::StrCat("attachment; filename=\"", job_id, ".exr\"")},
                 {"Cache-Control", "no-store"}}};
    }
    float exposure = 0;
    if (const auto it = request.query.find("exposure"); it != request.query.end())
        if (!absl::SimpleAtof(it->second, &exposure) || !(std::abs(exposure) <= 32))
            return Error(absl::InvalidArgumentError(absl::StrCat(
                "exposure: '", it->second, "' is not a number of stops in [-32, 32]")));
    absl::StatusOr<std::string> png = EncodePng(*image, exposure);
    if (!png.ok()) return Error(png.status());
    return {200, "image/png", std::move(*png), {{"Cache-Control", "no-store"}}};
}

HttpResponse DashboardApi::Handle(const HttpRequest& request) {
    const std::string& path = request.path;
    if (request.method == "GET") {
        if (path == "/" || path == "/workers" || path.starts_with("/jobs/"))
            return Asset(kDashboardHtml, "text/html; charset=utf-8");
        if (path == "/assets/dashboard.js")
            return Asset(kDashboardJs, "text/javascript; charset=utf-8");
        if (path == "/assets/dashboard.css") return Asset(kDashboardCss, "text/css; charset=utf-8");
        if (path == "/api/session") return Session(request);
    } else if (request.method == "POST") {
        if (path == "/api/login") return Login(request);
        if (path == "/api/logout") return Logout(request);
    } else {
        return Error(absl::UnimplementedError(
            absl::StrCat(request.method, " ", path, ": the dashboard answers GET and POST")));
    }
    if (!path.starts_with("/api/"))
        return Error(absl::NotFoundError(absl::StrCat("no such page: ", path)));
    if (absl::StatusOr<std::string> caller = Authenticate(request); !caller.ok())
        return Error(caller.status());
    if (request.method == "GET" && path == "/api/jobs")
        return Json(ToJson(JobListView(coordinator_)));
    if (request.method == "GET" && path == "/api/workers")
        return Json(ToJson(WorkerListView(coordinator_)));
    absl::string_view rest = path;
    if (absl::ConsumePrefix(&rest, "/api/jobs/")) {
        const std::vector<std::string> parts = absl::StrSplit(rest, absl::MaxSplits('/', 1));
        const std::string what = parts.size() == 2 ? parts[1] : "";
        if (what == "cancel" || request.method == "GET") return JobRequest(request, parts[0], what);
    }
    return Error(
        absl::NotFoundError(absl::StrCat("no such endpoint: ", request.method, " ", path)));
}

}  // namespace pf
