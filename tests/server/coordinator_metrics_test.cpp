// The coordinator's Prometheus metrics, scraped over HTTP.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <random>

#include "absl/strings/str_split.h"
#include "core/scene_io/scene_loader.h"
#include "core/util/file_io.h"
#include "embedded/local_render.h"
#include "server/checkpoint_store.h"
#include "server/in_process_source.h"
#include "server/metrics.h"
#include "tests/server/coordinator_test_support.h"
#include "tests/support/test_env.h"
#include "worker/backend_factory.h"
#include "worker/worker_loop.h"

namespace pf {
namespace {

using namespace coordinator_test;

// GET http://127.0.0.1:PORT/metrics, the body.
std::string Scrape(int port) {
    const int fd = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<uint16_t>(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) != 0) {
        close(fd);
        return "";
    }
    const std::string request = "GET /metrics HTTP/1.0\r\nHost: 127.0.0.1\r\n\r\n";
    EXPECT_EQ(write(fd, request.data(), request.size()), static_cast<ssize_t>(request.size()));
    std::string response;
    char buffer[4096];
    for (ssize_t n; (n = read(fd, buffer, sizeof(buffer))) > 0;)
        response.append(buffer, static_cast<size_t>(n));
    close(fd);
    const size_t body = response.find("\r\n\r\n");
    return body == std::string::npos ? "" : response.substr(body + 4);
}

// The value of the sample `name{labels}` in a scrape, or NaN.
double Sample(const std::string& scrape, const std::string& sample) {
    for (const std::string& line : std::vector<std::string>(absl::StrSplit(scrape, '\n')))
        if (line.starts_with(sample + " ")) return std::stod(line.substr(sample.size() + 1));
    return std::nan("");
}

TEST(CoordinatorMetricsTest, ScrapesShowPhotonsBatchesWorkersMergesAndRefusals) {
    FakeClock clock;
    Coordinator coordinator(Options(&clock));
    absl::StatusOr<std::unique_ptr<MetricsServer>> server =
        MetricsServer::Start("127.0.0.1:0", std::make_shared<CoordinatorMetrics>(coordinator));
    ASSERT_TRUE(server.ok()) << server.status();
    const std::string job_id = coordinator.Submit(SmallJob(3 * 4 * 4096))->job_id;
    const std::string worker = *coordinator.RegisterWorker(Cpu());
    std::string scrape = Scrape((*server)->Port());
    EXPECT_EQ(Sample(scrape, "photonfarm_batches_pending"), 4) << scrape;
    EXPECT_EQ(Sample(scrape, "photonfarm_batches_leased"), 0);
    EXPECT_EQ(Sample(scrape, "photonfarm_workers{backend=\"cpu\"}"), 1);
    EXPECT_EQ(Sample(scrape, "photonfarm_jobs{state=\"running\"}"), 1);

    BatchRunner runner;
    const absl::StatusOr<CoordinatorLease> lease = coordinator.Lease(worker, 4, 0);
    ASSERT_TRUE(lease.ok() && lease->grant.batches.size() == 4);
    scrape = Scrape((*server)->Port());
    EXPECT_EQ(Sample(scrape, "photonfarm_batches_pending"), 0);
    EXPECT_EQ(Sample(scrape, "photonfarm_batches_leased"), 4);
    std::vector<BatchResult> results = runner.Run(*lease);
    BatchResult copy = results[0];
    for (BatchResult& result : results)
        ASSERT_EQ(*coordinator.Report(worker, job_id, std::move(result)), TallyVerdict::kAccepted);
    EXPECT_EQ(*coordinator.Report(worker, job_id, std::move(copy)),
              TallyVerdict::kStale);  // epoch 0 is merged

    scrape = Scrape((*server)->Port());
    EXPECT_EQ(Sample(scrape, "photonfarm_photons_total"), 4 * 4096);
    EXPECT_EQ(Sample(scrape, "photonfarm_merge_seconds_count"), 4)
        << "one merge per accepted tally";
    EXPECT_EQ(Sample(scrape, "photonfarm_tallies_refused_total{reason=\"stale\"}"), 1);
    EXPECT_EQ(Sample(scrape, "photonfarm_tallies_refused_total{reason=\"duplicate\"}"), 0);
    EXPECT_EQ(Sample(scrape, "photonfarm_batches_pending"), 4) << "the next epoch's";
    EXPECT_TRUE(
        std::isnan(Sample(scrape, "photonfarm_job_estimated_error{job=\"" + job_id + "\"}")))
        << "no estimate after one epoch";
    const absl::StatusOr<CoordinatorLease> second = coordinator.Lease(worker, 4, 0);
    for (BatchResult& result : runner.Run(*second))
        ASSERT_EQ(*coordinator.Report(worker, job_id, std::move(result)), TallyVerdict::kAccepted);
    scrape = Scrape((*server)->Port());
    const double error = Sample(scrape, "photonfarm_job_estimated_error{job=\"" + job_id + "\"}");
    EXPECT_NEAR(error, *(*coordinator.FindJob(job_id))->Progress(clock.now).estimated_error, 1e-12);
}

}  // namespace
}  // namespace pf
