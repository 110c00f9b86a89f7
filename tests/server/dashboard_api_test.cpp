// The dashboard's handlers without a socket: who may read and act (tokens, sessions, CSRF,
// origins), what the JSON endpoints say, and the images they serve.
#include "server/dashboard_api.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/film/exr_io.h"
#include "core/util/file_io.h"
#include "server/job_views.h"
#include "tests/server/coordinator_test_support.h"
#include "tests/support/test_env.h"
#include "wire/json.h"

namespace pf {
namespace {

using namespace coordinator_test;

constexpr char kClientSecret[] = "client-secret-0123456789";
constexpr char kWorkerSecret[] = "worker-secret-0123456789";

ServerSecurity Tokens() {
    ServerSecurity security;  // TLS (the certificate is the transport's business)
    security.client_tokens = {{"alice", kClientSecret}};
    security.worker_tokens = {{"worker-pool", kWorkerSecret}};
    return security;
}

HttpRequest Get(std::string path, std::map<std::string, std::string> headers = {}) {
    return {"GET", std::move(path), {}, std::move(headers), "", "127.0.0.1"};
}

HttpRequest Post(std::string path, std::map<std::string, std::string> headers = {},
                 std::string body = "") {
    return {"POST", std::move(path), {}, std::move(headers), std::move(body), "127.0.0.1"};
}

std::string Header(const HttpResponse& response, const std::string& name) {
    for (const auto& [key, value] : response.headers)
        if (key == name) return value;
    return "";
}

std::string ErrorCode(const HttpResponse& response) {
    return nlohmann::json::parse(response.body).value("code", "");
}

// A coordinator with one small job, and the dashboard over it.
struct Dashboard {
    explicit Dashboard(ServerSecurity security = Tokens())
        : coordinator(Options(&clock)), access(std::move(security)), api(coordinator, access) {
        job_id = coordinator.Submit(SmallJob(8 * 4 * 4096))->job_id;
    }
    // Logs in with the client token: the cookie header to send and the session's CSRF token.
    std::pair<std::string, std::string> LogIn() {
        const HttpResponse response = api.Handle(
            Post("/api/login", {}, std::string("{\"token\": \"") + kClientSecret + "\"}"));
        EXPECT_EQ(response.status, 200) << response.body;
        const std::string cookie = Header(response, "Set-Cookie");
        return {cookie.substr(0, cookie.find(';')),
                nlohmann::json::parse(response.body).value("csrf_token", "")};
    }
    // Leases and reports one epoch's batches.
    void RunEpoch() {
        const std::string worker = *coordinator.RegisterWorker(Cpu());
        const absl::StatusOr<CoordinatorLease> lease = coordinator.Lease(worker, 4, 0);
        ASSERT_TRUE(lease.ok() && lease->job != nullptr);
        for (BatchResult& result : runner.Run(*lease))
            ASSERT_EQ(*coordinator.Report(worker, job_id, std::move(result)),
                      TallyVerdict::kAccepted);
    }
    JobState State() { return (*coordinator.FindJob(job_id))->Progress(clock.now).state; }

    FakeClock clock;
    Coordinator coordinator;
    AccessControl access;
    DashboardApi api;
    BatchRunner runner;
    std::string job_id;
};

TEST(DashboardApiTest, NothingIsReadWithoutAClientToken) {
    Dashboard dashboard;
    for (const char* path : {"/api/jobs", "/api/workers", "/api/session"}) {
        const HttpResponse response = dashboard.api.Handle(Get(path));
        EXPECT_EQ(response.status, 401) << path;
        EXPECT_EQ(ErrorCode(response), "UNAUTHENTICATED") << response.body;
    }
    EXPECT_EQ(dashboard.api.Handle(Get("/api/jobs/" + dashboard.job_id + "/image.png")).status,
              401);
    EXPECT_EQ(dashboard.api.Handle(Post("/api/login", {}, "{\"token\": \"wrong\"}")).status, 401);
    for (const char* body : {"not json", "{\"token\": 7}", "[\"token\"]", ""})
        EXPECT_EQ(dashboard.api.Handle(Post("/api/login", {}, body)).status, 401) << body;
    EXPECT_EQ(dashboard.api.Handle(Get("/api/jobs", {{"authorization", "Bearer wrong"}})).status,
              401);
    EXPECT_EQ(dashboard.api.Handle(Get("/api/jobs", {{"cookie", "pf_session=forged"}})).status,
              401);
    // The page itself loads (it shows the login form).
    const HttpResponse page = dashboard.api.Handle(Get("/"));
    EXPECT_EQ(page.status, 200);
    EXPECT_NE(page.body.find("/assets/dashboard.js"), std::string::npos);
}

TEST(DashboardApiTest, AWorkersTokenOpensNothing) {
    Dashboard dashboard;
    const HttpResponse login = dashboard.api.Handle(
        Post("/api/login", {}, std::string("{\"token\": \"") + kWorkerSecret + "\"}"));
    EXPECT_EQ(login.status, 403);
    EXPECT_EQ(ErrorCode(login), "PERMISSION_DENIED");
    EXPECT_TRUE(Header(login, "Set-Cookie").empty());
    EXPECT_EQ(
        dashboard.api
            .Handle(Get("/api/jobs", {{"authorization", std::string("Bearer ") + kWorkerSecret}}))
            .status,
        403);
}

TEST(DashboardApiTest, ALoginSetsAnHttpOnlySecureCookieThatReadsTheJobList) {
    Dashboard dashboard;
    const HttpResponse login = dashboard.api.Handle(
        Post("/api/login", {}, std::string("{\"token\": \"") + kClientSecret + "\"}"));
    ASSERT_EQ(login.status, 200);
    const std::string cookie = Header(login, "Set-Cookie");
    EXPECT_TRUE(cookie.starts_with("pf_session=")) << cookie;
    for (const char* attribute : {"; HttpOnly", "; Secure", "; SameSite=Strict", "; Path=/"})
        EXPECT_NE(cookie.find(attribute), std::string::npos) << cookie;
    EXPECT_EQ(nlohmann::json::parse(login.body).value("name", ""), "alice");

    const std::string session = cookie.substr(0, cookie.find(';'));
    const HttpResponse jobs = dashboard.api.Handle(Get("/api/jobs", {{"cookie", session}}));
    ASSERT_EQ(jobs.status, 200) << jobs.body;
    EXPECT_EQ(jobs.content_type, "application/json");
    const nlohmann::json list = nlohmann::json::parse(jobs.body);
    ASSERT_EQ(list["jobs"].size(), 1u);
    EXPECT_EQ(list["jobs"][0]["job_id"], dashboard.job_id);
    EXPECT_EQ(list["jobs"][0]["owner"], "tester");
    EXPECT_EQ(list["jobs"][0]["state"], "JOB_STATE_RUNNING");
    EXPECT_EQ(list["jobs"][0]["integrator"], "INTEGRATOR_PPM");
    // A bearer token reads the same (scripts).
    EXPECT_EQ(
        dashboard.api
            .Handle(Get("/api/jobs", {{"authorization", std::string("Bearer ") + kClientSecret}}))
            .body,
        jobs.body);
    // The session's page learns its CSRF token again after a reload.
    const HttpResponse again = dashboard.api.Handle(Get("/api/session", {{"cookie", session}}));
    EXPECT_EQ(nlohmann::json::parse(again.body)["csrf_token"],
              nlohmann::json::parse(login.body)["csrf_token"]);
}

TEST(DashboardApiTest, SessionsExpireAndLoggingOutEndsThem) {
    Dashboard dashboard;
    auto [cookie, csrf] = dashboard.LogIn();
    EXPECT_EQ(dashboard.api.Handle(Get("/api/jobs", {{"cookie", cookie}})).status, 200);
    dashboard.clock.Advance(13 * 3600);
    EXPECT_EQ(dashboard.api.Handle(Get("/api/jobs", {{"cookie", cookie}})).status, 401);

    std::tie(cookie, csrf) = dashboard.LogIn();
    EXPECT_EQ(dashboard.api.Handle(Post("/api/logout", {{"cookie", cookie}})).status, 403)
        << "logout is an action: it needs the CSRF token";
    const HttpResponse logout =
        dashboard.api.Handle(Post("/api/logout", {{"cookie", cookie}, {"x-csrf-token", csrf}}));
    EXPECT_EQ(logout.status, 200);
    EXPECT_NE(Header(logout, "Set-Cookie").find("Max-Age=0"), std::string::npos);
    EXPECT_EQ(dashboard.api.Handle(Get("/api/jobs", {{"cookie", cookie}})).status, 401);
}

TEST(DashboardApiTest, CancelNeedsTheSessionsCsrfTokenAndThisOrigin) {
    Dashboard dashboard;
    const auto [cookie, csrf] = dashboard.LogIn();
    const std::string cancel = "/api/jobs/" + dashboard.job_id + "/cancel";
    const HttpResponse no_csrf = dashboard.api.Handle(Post(cancel, {{"cookie", cookie}}));
    EXPECT_EQ(no_csrf.status, 403);
    EXPECT_NE(no_csrf.body.find("CSRF"), std::string::npos) << no_csrf.body;
    EXPECT_EQ(dashboard.api.Handle(Post(cancel, {{"cookie", cookie}, {"x-csrf-token", csrf + "0"}}))
                  .status,
              403);
    EXPECT_EQ(dashboard.api
                  .Handle(Post(cancel, {{"cookie", cookie},
                                        {"x-csrf-token", csrf},
                                        {"host", "farm.example:8443"},
                                        {"origin", "https://evil.example"}}))
                  .status,
              403);
    EXPECT_EQ(
        dashboard.api.Handle(Get(cancel, {{"cookie", cookie}, {"x-csrf-token", csrf}})).status, 501)
        << "cancel is a POST";
    EXPECT_EQ(dashboard.State(), JobState::kRunning) << "no refused request cancelled the job";

    const HttpResponse cancelled =
        dashboard.api.Handle(Post(cancel, {{"cookie", cookie},
                                           {"x-csrf-token", csrf},
                                           {"host", "farm.example:8443"},
                                           {"origin", "https://farm.example:8443"}}));
    ASSERT_EQ(cancelled.status, 200) << cancelled.body;
    EXPECT_EQ(nlohmann::json::parse(cancelled.body)["status"]["state"], "JOB_STATE_CANCELLED");
    EXPECT_EQ(dashboard.State(), JobState::kCancelled);
}

TEST(DashboardApiTest, ABearerTokenActsWithoutCsrf) {
    Dashboard dashboard;
    const HttpResponse cancelled =
        dashboard.api.Handle(Post("/api/jobs/" + dashboard.job_id + "/cancel",
                                  {{"authorization", std::string("Bearer ") + kClientSecret}}));
    EXPECT_EQ(cancelled.status, 200) << cancelled.body;
    EXPECT_EQ(dashboard.State(), JobState::kCancelled);
    EXPECT_EQ(dashboard.api
                  .Handle(Post("/api/jobs/job-nope/cancel",
                               {{"authorization", std::string("Bearer ") + kClientSecret}}))
                  .status,
              404);
}

TEST(DashboardApiTest, WithoutTokensASessionOpensByItselfAndActionsStillNeedItsCsrfToken) {
    ServerSecurity open;
    open.plaintext = true;
    Dashboard dashboard(open);
    EXPECT_EQ(dashboard.api.Handle(Get("/api/jobs")).status, 200);
    const HttpResponse session = dashboard.api.Handle(Get("/api/session"));
    ASSERT_EQ(session.status, 200);
    const std::string cookie = Header(session, "Set-Cookie");
    EXPECT_EQ(cookie.find("Secure"), std::string::npos) << "plain HTTP: no Secure cookie";
    const std::string csrf = nlohmann::json::parse(session.body)["csrf_token"];
    const std::string cancel = "/api/jobs/" + dashboard.job_id + "/cancel";
    EXPECT_EQ(dashboard.api.Handle(Post(cancel)).status, 403) << "a cross-site form post";
    EXPECT_EQ(dashboard.api
                  .Handle(Post(cancel, {{"cookie", cookie.substr(0, cookie.find(';'))},
                                        {"x-csrf-token", csrf}}))
                  .status,
              200);
}

TEST(DashboardApiTest, TheJobsImageComesAsPngAndAsTheExactExr) {
    Dashboard dashboard;
    const auto [cookie, csrf] = dashboard.LogIn();
    const std::string base = "/api/jobs/" + dashboard.job_id;
    EXPECT_EQ(
        dashboard.api.Handle(Get("/api/jobs/job-nope/image.png", {{"cookie", cookie}})).status,
        404);
    dashboard.RunEpoch();
    const HttpResponse png = dashboard.api.Handle(Get(base + "/image.png", {{"cookie", cookie}}));
    ASSERT_EQ(png.status, 200) << png.body;
    EXPECT_EQ(png.content_type, "image/png");
    ASSERT_GT(png.body.size(), 24u);
    EXPECT_EQ(png.body.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
    const auto be32 = [&](size_t at) {
        const auto* bytes = reinterpret_cast<const unsigned char*>(png.body.data() + at);
        return (bytes[0] << 24) | (bytes[1] << 16) | (bytes[2] << 8) | bytes[3];
    };
    EXPECT_EQ(be32(16), 32);  // IHDR width, height: the job's film
    EXPECT_EQ(be32(20), 32);
    HttpRequest brighter = Get(base + "/image.png", {{"cookie", cookie}});
    brighter.query["exposure"] = "2";
    EXPECT_NE(dashboard.api.Handle(brighter).body, png.body);
    brighter.query["exposure"] = "bright";
    EXPECT_EQ(dashboard.api.Handle(brighter).status, 400);
    brighter.query["exposure"] = "nan";
    EXPECT_EQ(dashboard.api.Handle(brighter).status, 400);

    const HttpResponse exr = dashboard.api.Handle(Get(base + "/image.exr", {{"cookie", cookie}}));
    ASSERT_EQ(exr.status, 200);
    EXPECT_NE(Header(exr, "Content-Disposition").find(dashboard.job_id + ".exr"),
              std::string::npos);
    const std::string path = testing::TempPath("dashboard-download.exr");
    ASSERT_TRUE(WriteFileAtomically(path, exr.body).ok());
    const absl::StatusOr<Image> read = ReadExr(path);
    ASSERT_TRUE(read.ok()) << read.status();
    EXPECT_TRUE(
        SamePixels(*read, *(*dashboard.coordinator.FindJob(dashboard.job_id))->CurrentImage()));
}

TEST(DashboardApiTest, AJobsPageDataAndEventsCarryItsConvergencePointsOnce) {
    Dashboard dashboard;
    const auto [cookie, csrf] = dashboard.LogIn();
    dashboard.RunEpoch();
    dashboard.RunEpoch();
    const HttpResponse view =
        dashboard.api.Handle(Get("/api/jobs/" + dashboard.job_id, {{"cookie", cookie}}));
    ASSERT_EQ(view.status, 200);
    const nlohmann::json data = nlohmann::json::parse(view.body);
    EXPECT_EQ(data["points"].size(), 2u);
    EXPECT_EQ(data["status"]["epochs"], "2");  // uint64 as a string, protobuf's JSON mapping
    EXPECT_EQ(data["pixels"], "1024");

    const Job& job = **dashboard.coordinator.FindJob(dashboard.job_id);
    size_t sent = 0;
    EXPECT_EQ(nlohmann::json::parse(dashboard.api.JobEvent(job, &sent))["points"].size(), 2u);
    EXPECT_EQ(sent, 2u);
    EXPECT_TRUE(nlohmann::json::parse(dashboard.api.JobEvent(job, &sent))["points"].empty())
        << "nothing new";
    dashboard.RunEpoch();
    const nlohmann::json third = nlohmann::json::parse(dashboard.api.JobEvent(job, &sent));
    ASSERT_EQ(third["points"].size(), 1u);
    EXPECT_EQ(third["points"][0]["epochs"], "3");
}

TEST(DashboardApiTest, UnknownJobsPathsAndMethodsAreRefusedByName) {
    Dashboard dashboard;
    const auto [cookie, csrf] = dashboard.LogIn();
    const HttpResponse job = dashboard.api.Handle(Get("/api/jobs/job-nope", {{"cookie", cookie}}));
    EXPECT_EQ(job.status, 404);
    EXPECT_NE(job.body.find("job-nope"), std::string::npos) << job.body;
    EXPECT_EQ(dashboard.api.Handle(Get("/api/nothing", {{"cookie", cookie}})).status, 404);
    EXPECT_EQ(dashboard.api.Handle(Get("/secret.txt")).status, 404);
    HttpRequest put = Get("/api/jobs");
    put.method = "PUT";
    EXPECT_EQ(dashboard.api.Handle(put).status, 501);
    for (const char* page : {"/", "/workers", "/jobs/anything"})
        EXPECT_EQ(dashboard.api.Handle(Get(page)).content_type, "text/html; charset=utf-8");
    EXPECT_EQ(dashboard.api.Handle(Get("/assets/dashboard.js")).status, 200);
    EXPECT_EQ(dashboard.api.Handle(Get("/assets/dashboard.css")).status, 200);
}

TEST(DashboardApiTest, TheWorkersListShowsRatesAndHeartbeats) {
    Dashboard dashboard;
    const auto [cookie, csrf] = dashboard.LogIn();
    dashboard.clock.Advance(2);
    dashboard.RunEpoch();  // registers a worker that reports 4 batches of 4096 photons
    dashboard.clock.Advance(4);
    const nlohmann::json list =
        nlohmann::json::parse(dashboard.api.Handle(Get("/api/workers", {{"cookie", cookie}})).body);
    ASSERT_EQ(list["workers"].size(), 1u);
    const nlohmann::json& worker = list["workers"][0];
    EXPECT_EQ(worker["backend"], "cpu");
    EXPECT_EQ(worker["batches_done"], "4");
    EXPECT_EQ(worker["photons_reported"], "16384");
    EXPECT_DOUBLE_EQ(worker["seconds_since_heartbeat"].get<double>(), 4);
    EXPECT_DOUBLE_EQ(worker["photons_per_second"].get<double>(), 16384 / 4.0);
}

}  // namespace
}  // namespace pf
