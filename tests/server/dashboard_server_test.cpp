// The dashboard over HTTPS on 127.0.0.1: the page, a login whose cookie reads the API, and a
// job's event stream that speaks once per merged epoch.
#include "server/dashboard_server.h"

#include <gtest/gtest.h>
#include <httplib.h>

#include <nlohmann/json.hpp>

#include "tests/server/coordinator_test_support.h"
#include "tests/support/farm_credentials.h"

namespace pf {
namespace {

using namespace coordinator_test;

const testing::FarmCredentials& Credentials() { return testing::TestCredentials(PF_SOURCE_DIR); }

ServerSecurity Tls() {
    ServerSecurity security;
    security.cert_pem = Credentials().Read("coordinator.pem");
    security.key_pem = Credentials().Read("coordinator.key");
    security.client_tokens = {{"alice", Credentials().ClientToken()}};
    security.worker_tokens = {{"pool", Credentials().WorkerToken()}};
    return security;
}

// A coordinator and its dashboard over HTTPS with tokens, on a free port of 127.0.0.1.
struct TlsDashboard {
    FakeClock clock;
    Coordinator coordinator{Options(&clock)};
    ServerSecurity security = Tls();
    AccessControl access{security};
    absl::StatusOr<std::unique_ptr<DashboardServer>> server =
        DashboardServer::Start("127.0.0.1:0", security, coordinator, access);
};

std::unique_ptr<httplib::SSLClient> Client(int port) {
    auto client = std::make_unique<httplib::SSLClient>("127.0.0.1", port);
    client->set_ca_cert_path(Credentials().Path("ca.pem").c_str());
    client->enable_server_certificate_verification(true);
    client->set_read_timeout(30, 0);
    return client;
}

TEST(DashboardServerTest, ServesThePageAndTheApiOverTlsWithTheCoordinatorsCertificate) {
    TlsDashboard dashboard;
    ASSERT_TRUE(dashboard.server.ok()) << dashboard.server.status();
    DashboardServer& server = **dashboard.server;
    EXPECT_EQ(server.Url(), "https://127.0.0.1:" + std::to_string(server.Port()) + "/");
    const auto client = Client(server.Port());
    const httplib::Result page = client->Get("/");
    ASSERT_TRUE(page) << httplib::to_string(page.error());
    EXPECT_EQ(page->status, 200);
    EXPECT_NE(page->body.find("photonfarm"), std::string::npos);
    EXPECT_EQ(client->Get("/api/jobs")->status, 401);

    const httplib::Result login = client->Post(
        "/api/login", "{\"token\": \"" + Credentials().ClientToken() + "\"}", "application/json");
    ASSERT_TRUE(login);
    ASSERT_EQ(login->status, 200) << login->body;
    const std::string cookie = login->get_header_value("Set-Cookie");
    const httplib::Headers session = {{"Cookie", cookie.substr(0, cookie.find(';'))}};
    const httplib::Result jobs = client->Get("/api/jobs", session);
    ASSERT_TRUE(jobs);
    EXPECT_EQ(jobs->status, 200);
    EXPECT_EQ(jobs->body, "{\"jobs\":[]}");
    EXPECT_EQ(jobs->get_header_value("X-Content-Type-Options"), "nosniff");
}

TEST(DashboardServerTest, APlainTextClientGetsNoAnswerFromATlsDashboard) {
    TlsDashboard dashboard;
    ASSERT_TRUE(dashboard.server.ok()) << dashboard.server.status();
    DashboardServer& server = **dashboard.server;
    httplib::Client plain("127.0.0.1", server.Port());
    plain.set_read_timeout(5, 0);
    const httplib::Result page = plain.Get("/");
    EXPECT_TRUE(!page || page->status != 200);
}

TEST(DashboardServerTest, AJobsEventStreamSpeaksOncePerMergedEpochAndEndsWithTheJob) {
    TlsDashboard dashboard;
    ASSERT_TRUE(dashboard.server.ok()) << dashboard.server.status();
    Coordinator& coordinator = dashboard.coordinator;
    DashboardServer& server = **dashboard.server;
    const std::string job_id = coordinator.Submit(SmallJob(2 * 4 * 4096))->job_id;
    const std::string worker = *coordinator.RegisterWorker(Cpu());
    BatchRunner runner;
    const auto run_epoch = [&] {
        const absl::StatusOr<CoordinatorLease> lease = coordinator.Lease(worker, 4, 0);
        ASSERT_TRUE(lease.ok() && lease->job != nullptr);
        for (BatchResult& result : runner.Run(*lease))
            ASSERT_EQ(*coordinator.Report(worker, job_id, std::move(result)),
                      TallyVerdict::kAccepted);
    };

    const auto client = Client(server.Port());
    std::string received;
    std::vector<nlohmann::json> events;
    const httplib::Result stream =
        client->Get("/api/jobs/" + job_id + "/events",
                    {{"Authorization", "Bearer " + Credentials().ClientToken()}},
                    [&](const char* data, size_t length) {
                        received.append(data, length);
                        for (size_t end; (end = received.find("\n\n")) != std::string::npos;) {
                            const std::string message = received.substr(0, end);
                            received.erase(0, end + 2);
                            if (!message.starts_with("event: job\ndata: ")) continue;
                            events.push_back(nlohmann::json::parse(message.substr(17)));
                            // The next epoch merges only after this event arrived.
                            if (events.back()["status"]["state"] == "JOB_STATE_RUNNING")
                                run_epoch();
                        }
                        return true;
                    });
    ASSERT_TRUE(stream) << httplib::to_string(stream.error());
    EXPECT_EQ(stream->status, 200);
    EXPECT_EQ(stream->get_header_value("Content-Type"), "text/event-stream");
    // The job's budget is two epochs: an event at the start and one after each epoch, the last
    // saying it is done; then the server closed the stream. Each point came once.
    ASSERT_GE(events.size(), 3u);
    EXPECT_TRUE(events[0]["points"].empty()) << events[0].dump();
    std::vector<std::string> epochs;
    for (const nlohmann::json& event : events)
        for (const nlohmann::json& point : event["points"]) epochs.push_back(point["epochs"]);
    EXPECT_EQ(epochs, (std::vector<std::string>{"1", "2"}));
    EXPECT_EQ(events.back()["status"]["state"], "JOB_STATE_DONE");

    const httplib::Result refused = client->Get("/api/jobs/" + job_id + "/events");
    ASSERT_TRUE(refused);
    EXPECT_EQ(refused->status, 401) << "no token, no stream";
}

TEST(DashboardServerTest, AnAddressInUseIsRefusedNamingIt) {
    FakeClock clock;
    Coordinator coordinator(Options(&clock));
    ServerSecurity open;
    open.plaintext = true;
    const AccessControl access(open);
    absl::StatusOr<std::unique_ptr<DashboardServer>> first =
        DashboardServer::Start("127.0.0.1:0", open, coordinator, access);
    ASSERT_TRUE(first.ok());
    const std::string taken = "127.0.0.1:" + std::to_string((*first)->Port());
    const absl::StatusOr<std::unique_ptr<DashboardServer>> second =
        DashboardServer::Start(taken, open, coordinator, access);
    EXPECT_EQ(second.status().code(), absl::StatusCode::kUnavailable);
    EXPECT_NE(second.status().message().find(taken), std::string::npos) << second.status();
}

}  // namespace
}  // namespace pf
