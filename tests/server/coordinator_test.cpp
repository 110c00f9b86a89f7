// The coordinator's logic without a socket: leases and their expiry, refusals (duplicate,
// stale, job gone, unknown worker, forged), in-order merging whatever the arrival order,
// cancellation, priorities and fairness, settings errors that name the field, client limits
// (checkpoints: coordinator_checkpoint_test.cpp; metrics: coordinator_metrics_test.cpp).
#include "server/coordinator.h"

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
#include <thread>

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

TEST(CoordinatorTest, ResultsInAnyOrderFromAnyWorkerGiveTheEmbeddedImage) {
    const absl::StatusOr<RenderOutcome> reference = EmbeddedReference(3 * 4 * 4096);
    ASSERT_TRUE(reference.ok()) << reference.status();

    FakeClock clock;
    Coordinator coordinator(Options(&clock));
    const absl::StatusOr<JobProgress> job = coordinator.Submit(SmallJob(3 * 4 * 4096));
    ASSERT_TRUE(job.ok()) << job.status();
    const std::string a = *coordinator.RegisterWorker(Cpu()),
                      b = *coordinator.RegisterWorker(Cpu());
    BatchRunner runner;
    std::mt19937_64 shuffle(testing::TestSeed());  // printed: PF_TEST_SEED repeats the order
    for (int epoch = 0; epoch < 3; ++epoch) {
        // Two workers take two batches each; their results come back in a random order.
        std::vector<std::pair<std::string, BatchResult>> reports;
        for (const std::string& worker : {a, b}) {
            const absl::StatusOr<CoordinatorLease> lease = coordinator.Lease(worker, 2, 0);
            ASSERT_TRUE(lease.ok() && lease->grant.batches.size() == 2);
            for (BatchResult& result : runner.Run(*lease))
                reports.emplace_back(worker, std::move(result));
        }
        // Out of order every epoch, whatever the seed: an in-order shuffle is drawn again.
        const auto in_order = [&] {
            return std::is_sorted(reports.begin(), reports.end(), [](const auto& x, const auto& y) {
                return x.second.spec.index < y.second.spec.index;
            });
        };
        do {
            std::shuffle(reports.begin(), reports.end(), shuffle);
        } while (in_order());
        for (auto& [worker, result] : reports)
            EXPECT_EQ(*coordinator.Report(worker, job->job_id, std::move(result)),
                      TallyVerdict::kAccepted);
    }
    const std::shared_ptr<Job> done = *coordinator.FindJob(job->job_id);
    EXPECT_EQ(done->Progress(clock.now).state, JobState::kDone);
    EXPECT_TRUE(SamePixels(*done->CurrentImage(), reference->image))
        << "the merge must not depend on arrival order";
}

TEST(CoordinatorTest, ScenesOverTheConfiguredLimitsAreRefused) {
    FakeClock clock;
    CoordinatorOptions options = Options(&clock);
    options.scene_limits.max_triangles = 10;  // the Cornell box has 32
    Coordinator coordinator(options);
    const absl::StatusOr<JobProgress> refused = coordinator.Submit(SmallJob(1000));
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.status().code(), absl::StatusCode::kResourceExhausted);
    EXPECT_NE(refused.status().message().find("more than 10 triangles"), std::string::npos)
        << refused.status();
    options.scene_limits.max_triangles = 32;
    Coordinator roomy(options);
    EXPECT_TRUE(roomy.Submit(SmallJob(1000)).ok());
}

// Over a client limit: RESOURCE_EXHAUSTED naming the coordinator's flag.
void ExpectOverLimit(const absl::StatusOr<JobProgress>& refused, const std::string& flag) {
    ASSERT_FALSE(refused.ok()) << "over " << flag;
    EXPECT_EQ(refused.status().code(), absl::StatusCode::kResourceExhausted) << refused.status();
    EXPECT_NE(refused.status().message().find(flag), std::string::npos) << refused.status();
}

TEST(CoordinatorTest, RequestsOverTheClientLimitsAreRefused) {
    FakeClock clock;
    CoordinatorOptions options = Options(&clock);
    options.client_limits.max_jobs_per_client = 2;
    options.client_limits.max_render_pixels = 32 * 32 - 1;
    Coordinator small_images(options);
    ExpectOverLimit(small_images.Submit(SmallJob(1000)), "--max-render-pixels");

    options.client_limits.max_render_pixels = 32 * 32;
    options.client_limits.max_photons_per_batch = (1u << 12) - 1;
    Coordinator small_batches(options);
    ExpectOverLimit(small_batches.Submit(SmallJob(1000)), "--max-photons-per-batch");

    options.client_limits.max_photons_per_batch = 1u << 12;
    options.client_limits.max_bundle_bytes = 1000;  // the Cornell box's glTF and buffer hold more
    Coordinator small_scenes(options);
    ExpectOverLimit(small_scenes.Submit(SmallJob(1000)), "--max-bundle-bytes");

    options.client_limits.max_bundle_bytes = kMaxBundleBytes;
    Coordinator coordinator(options);
    const std::string first = coordinator.Submit(SmallJob(1'000'000, 0, "alice"))->job_id;
    ASSERT_TRUE(coordinator.Submit(SmallJob(1'000'000, 0, "alice")).ok());
    ExpectOverLimit(coordinator.Submit(SmallJob(1'000'000, 0, "alice")), "--max-jobs-per-client");
    EXPECT_TRUE(coordinator.Submit(SmallJob(1'000'000, 0, "bob")).ok())
        << "the limit is per client";
    ASSERT_TRUE(coordinator.Cancel(first).ok());
    EXPECT_TRUE(coordinator.Submit(SmallJob(1'000'000, 0, "alice")).ok())
        << "an ended job no longer counts";
}

// Submissions of one client at once: the limit counts those still being prepared (their
// camera passes run outside the coordinator's lock), so exactly the limit's worth get in.
TEST(CoordinatorTest, ConcurrentSubmissionsOfOneClientStayWithinItsLimit) {
    FakeClock clock;
    CoordinatorOptions options = Options(&clock);
    options.client_limits.max_jobs_per_client = 2;
    Coordinator coordinator(options);
    constexpr int kSubmissions = 6;
    std::vector<JobRequest> requests;
    for (int i = 0; i < kSubmissions; ++i) requests.push_back(SmallJob(1'000'000, 0, "alice"));
    std::vector<absl::StatusOr<JobProgress>> outcomes(kSubmissions, absl::UnknownError("unset"));
    std::vector<std::thread> submitters;
    for (int i = 0; i < kSubmissions; ++i)
        submitters.emplace_back(
            [&, i] { outcomes[i] = coordinator.Submit(std::move(requests[i])); });
    for (std::thread& submitter : submitters) submitter.join();
    int accepted = 0;
    for (const absl::StatusOr<JobProgress>& outcome : outcomes) {
        if (outcome.ok())
            ++accepted;
        else
            ExpectOverLimit(outcome, "--max-jobs-per-client");
    }
    EXPECT_EQ(accepted, 2);
    EXPECT_EQ(coordinator.ListJobs().size(), 2u);
    EXPECT_TRUE(coordinator.Submit(SmallJob(1'000'000, 0, "bob")).ok())
        << "another client's submissions are not held back by them";
}

TEST(CoordinatorTest, WatchersPerJobAreCounted) {
    FakeClock clock;
    Coordinator coordinator(Options(&clock));
    const std::shared_ptr<Job> job =
        *coordinator.FindJob(coordinator.Submit(SmallJob(1000))->job_id);
    EXPECT_TRUE(job->AddWatcher(2));
    EXPECT_TRUE(job->AddWatcher(2));
    EXPECT_FALSE(job->AddWatcher(2));
    job->RemoveWatcher();
    EXPECT_TRUE(job->AddWatcher(2));
}

TEST(CoordinatorTest, DuplicateStaleGoneAndUnknownTalliesAreRefusedAndCounted) {
    FakeClock clock;
    Coordinator coordinator(Options(&clock));
    const std::string job_id = coordinator.Submit(SmallJob(1'000'000))->job_id;
    const std::string worker = *coordinator.RegisterWorker(Cpu());
    BatchRunner runner;
    absl::StatusOr<CoordinatorLease> lease = coordinator.Lease(worker, 4, 0);
    ASSERT_TRUE(lease.ok());
    std::vector<BatchResult> epoch0 = runner.Run(*lease);
    const BatchResult first = epoch0[0];
    for (BatchResult& result : epoch0)
        EXPECT_EQ(*coordinator.Report(worker, job_id, std::move(result)), TallyVerdict::kAccepted);
    // Epoch 0 is merged: its batch again is stale, whoever sends it.
    EXPECT_EQ(*coordinator.Report(worker, job_id, first), TallyVerdict::kStale);
    lease = coordinator.Lease(worker, 1, 0);
    const BatchResult second = runner.Run(*lease)[0];
    EXPECT_EQ(*coordinator.Report(worker, job_id, second), TallyVerdict::kAccepted);
    EXPECT_EQ(*coordinator.Report(worker, job_id, second), TallyVerdict::kDuplicate);
    // A forged spec, and hit points the job does not have.
    BatchResult forged = second;
    forged.spec.index += 1;
    forged.spec.photons += 1;
    EXPECT_TRUE(absl::IsInvalidArgument(coordinator.Report(worker, job_id, forged).status()));
    BatchResult outside = second;
    outside.spec = MakeBatchSpec(SmallSpec(0).layout, 1, 2, 32 * 32 * 4);
    outside.tally.hit_point.assign(outside.tally.hit_point.size(), 1u << 30);
    EXPECT_TRUE(absl::IsInvalidArgument(coordinator.Report(worker, job_id, outside).status()));
    EXPECT_TRUE(absl::IsNotFound(coordinator.Report("worker-nobody", job_id, second).status()));
    ASSERT_TRUE(coordinator.Cancel(job_id).ok());
    EXPECT_EQ(*coordinator.Report(worker, job_id, second), TallyVerdict::kJobGone);
    EXPECT_EQ(*coordinator.Report(worker, "job-unknown", second), TallyVerdict::kJobGone);
    const RefusalCounts refused = coordinator.Refusals();
    EXPECT_EQ(refused.stale, 1u);
    EXPECT_EQ(refused.duplicate, 1u);
    EXPECT_EQ(refused.malformed, 2u);
    EXPECT_EQ(refused.unknown_worker, 1u);
    EXPECT_EQ(refused.job_gone, 2u);
}

TEST(CoordinatorTest, ExpiredLeasesAndSilentWorkersHandTheirBatchesOut) {
    FakeClock clock;
    Coordinator coordinator(Options(&clock));
    const std::string job_id = coordinator.Submit(SmallJob(1'000'000))->job_id;
    const std::string slow = *coordinator.RegisterWorker(Cpu());
    const std::string other = *coordinator.RegisterWorker(Cpu());
    ASSERT_EQ(coordinator.Lease(slow, 4, 0)->grant.batches.size(), 4u);
    EXPECT_TRUE(coordinator.Lease(other, 4, 0)->grant.batches.empty()) << "every batch is out";
    // Both keep heartbeating, but the slow worker's lease (30 s) runs out: its batches go out
    // again.
    for (int beat = 0; beat < 4; ++beat) {
        clock.Advance(beat < 3 ? 9 : 4);
        ASSERT_TRUE(coordinator.Heartbeat(slow).ok());
        ASSERT_TRUE(coordinator.Heartbeat(other).ok());
    }
    const absl::StatusOr<CoordinatorLease> again = coordinator.Lease(other, 4, 0);
    ASSERT_TRUE(again.ok()) << again.status();
    ASSERT_EQ(again->grant.batches.size(), 4u);
    EXPECT_EQ(again->grant.batches[0].index, 0u);
    // The other worker falls silent (10 s): it is gone, its leases free at once, its id unknown.
    clock.Advance(5);
    ASSERT_TRUE(coordinator.Heartbeat(slow).ok());
    clock.Advance(6);
    const absl::StatusOr<CoordinatorLease> back = coordinator.Lease(slow, 4, 0);
    ASSERT_TRUE(back.ok()) << back.status();
    EXPECT_EQ(back->grant.batches.size(), 4u);
    EXPECT_TRUE(absl::IsNotFound(coordinator.Heartbeat(other)));
    EXPECT_EQ(coordinator.ListWorkers().size(), 1u);
}

TEST(CoordinatorTest, CancelEndsLeasesKeepsTheImageAndFreesTheInputs) {
    FakeClock clock;
    Coordinator coordinator(Options(&clock));
    const std::string job_id = coordinator.Submit(SmallJob(1'000'000))->job_id;
    const std::string worker = *coordinator.RegisterWorker(Cpu());
    absl::StatusOr<CoordinatorLease> lease = coordinator.Lease(worker, 4, 0);
    std::weak_ptr<const JobPayload> payload = lease->grant.job;
    BatchRunner runner;
    for (BatchResult& result : runner.Run(*lease))
        (void)coordinator.Report(worker, job_id, std::move(result));
    lease = coordinator.Lease(worker, 4, 0);
    const std::shared_ptr<Job> job = *coordinator.FindJob(job_id);
    ASSERT_TRUE(coordinator.Cancel(job_id).ok());
    EXPECT_EQ(job->Progress(clock.now).state, JobState::kCancelled);
    EXPECT_EQ(job->Leased(clock.now), 0u);
    EXPECT_TRUE(coordinator.Lease(worker, 4, 0)->grant.batches.empty());
    EXPECT_EQ(job->Progress(clock.now).epochs, 1u);
    ASSERT_NE(job->CurrentImage(), nullptr) << "the image of the merged epoch stays";
    lease = absl::UnknownError("released");
    runner = BatchRunner();
    EXPECT_TRUE(payload.expired()) << "a cancelled job's scene and hit points are freed";
}

// Weights 1, 32, 1: the high-priority job's whole epoch goes out before the others' first
// batch, then the equal ones alternate.
TEST(CoordinatorTest, HigherPriorityFirstThenFewestBatchesOut) {
    FakeClock clock;
    Coordinator coordinator(Options(&clock));
    const std::string low = coordinator.Submit(SmallJob(1'000'000, 0))->job_id;
    const std::string high = coordinator.Submit(SmallJob(1'000'000, 5))->job_id;
    const std::string low2 = coordinator.Submit(SmallJob(1'000'000, 0))->job_id;
    const std::string worker = *coordinator.RegisterWorker(Cpu());
    std::vector<std::string> order;
    for (int i = 0; i < 8; ++i) order.push_back(coordinator.Lease(worker, 1, 0)->grant.job_id);
    EXPECT_EQ(std::count(order.begin(), order.begin() + 4, high), 4)
        << "the high-priority job's epoch goes first";
    // Then the two equal jobs alternate, the older first.
    EXPECT_EQ(std::vector<std::string>(order.begin() + 4, order.end()),
              (std::vector<std::string>{low, low2, low, low2}));
}

// Jobs share the workers by weight (2^priority): one batch at a time, a job of priority 1 is
// leased twice the photons of one of priority 0 while both have batches to hand out, and a
// job of low priority still gets its share while a much higher one has work.
TEST(CoordinatorTest, WorkersAreSharedByPriorityWeightWithoutStarvation) {
    FakeClock clock;
    Coordinator coordinator(Options(&clock));
    auto many_batches = [](int priority) {
        JobRequest request = SmallJob(1'000'000, priority);
        request.spec.layout = {1u << 12, 64};
        return request;
    };
    const std::string low = coordinator.Submit(many_batches(0))->job_id;
    const std::string high = coordinator.Submit(many_batches(1))->job_id;
    const std::string worker = *coordinator.RegisterWorker(Cpu());
    std::map<std::string, int> leases;
    for (int i = 0; i < 30; ++i) ++leases[coordinator.Lease(worker, 1, 0)->grant.job_id];
    EXPECT_EQ(leases[high], 20);
    EXPECT_EQ(leases[low], 10);

    // A new job joins at the others' level: no credit for the time before it came. Weights
    // 1, 2, 16: the urgent job first catches up half a batch on the high one, then 16:2:1.
    const std::string urgent = coordinator.Submit(many_batches(4))->job_id;
    leases.clear();
    for (int i = 0; i < 34; ++i) ++leases[coordinator.Lease(worker, 1, 0)->grant.job_id];
    EXPECT_EQ(leases[urgent], 30);
    EXPECT_EQ(leases[high], 3);
    EXPECT_EQ(leases[low], 1) << "the low-priority job is not starved";
}

TEST(CoordinatorTest, BadRequestsNameTheFieldOrFile) {
    Coordinator coordinator;
    JobRequest request = SmallJob(1000);
    request.spec.alpha = 2;
    absl::Status status = coordinator.Submit(request).status();
    EXPECT_TRUE(absl::IsInvalidArgument(status));
    EXPECT_NE(status.message().find("settings.alpha"), std::string::npos) << status;
    request = SmallJob(1000);
    request.bundle.files.erase(request.bundle.main_file);
    status = coordinator.Submit(request).status();
    EXPECT_TRUE(absl::IsInvalidArgument(status)) << status;
    EXPECT_NE(status.message().find("cornell-box.gltf"), std::string::npos) << status;
    EXPECT_TRUE(absl::IsNotFound(coordinator.FindJob("job-0").status()));
    WorkerRegistration old = Cpu();
    old.version = "0.0.1";
    EXPECT_TRUE(absl::IsFailedPrecondition(coordinator.RegisterWorker(old).status()));
}

// What a hand-made SubmitJob may carry (the CLI refuses the same as flags): each bad number is
// refused naming its field and range, and a job with no budget only when it says so.
TEST(CoordinatorTest, SubmittedSettingsOutOfRangeAreRefusedNamingTheField) {
    Coordinator coordinator;
    struct Case {
        const char* field;
        std::function<void(JobRequest&)> edit;
    };
    const std::vector<Case> cases = {
        // A negative count read as unsigned: 2^64 - 5 photons is no budget at all.
        {"settings.photon_budget", [](JobRequest& r) { r.spec.photon_budget = ~uint64_t{0} - 4; }},
        {"settings.epoch_budget", [](JobRequest& r) { r.spec.epoch_budget = uint64_t{1} << 41; }},
        {"settings.seconds_budget",
         [](JobRequest& r) { r.spec.seconds_budget = std::numeric_limits<double>::quiet_NaN(); }},
        {"settings.seconds_budget", [](JobRequest& r) { r.spec.seconds_budget = -1; }},
        {"settings.seconds_budget", [](JobRequest& r) { r.spec.seconds_budget = 1e300; }},
        {"settings.target_error",
         [](JobRequest& r) { r.spec.target_error = std::numeric_limits<double>::infinity(); }},
        {"settings.alpha", [](JobRequest& r) { r.spec.alpha = -0.5; }},
        {"settings.initial_radius", [](JobRequest& r) { r.spec.initial_radius = -1; }},
        // (0 leaves a count to the coordinator: ResolvedLayout.)
        {"settings.photons_per_batch",
         [](JobRequest& r) { r.spec.layout.photons_per_batch = kMaxPhotonsPerBatch + 1; }},
        {"settings.batches_per_epoch",
         [](JobRequest& r) { r.spec.layout.batches_per_epoch = kMaxBatchesPerEpoch + 1; }},
        {"settings.samples_per_pixel", [](JobRequest& r) { r.spec.samples_per_pixel = 0; }},
        {"settings.width", [](JobRequest& r) { r.spec.width = -3; }},
        {"settings.priority", [](JobRequest& r) { r.priority = 1 << 30; }},
        {"budget", [](JobRequest& r) { r.spec.photon_budget = 0; }},
        {"settings.until_cancelled", [](JobRequest& r) { r.spec.until_cancelled = true; }},
    };
    for (const Case& c : cases) {
        JobRequest request = SmallJob(1000);
        c.edit(request);
        const absl::Status status = coordinator.Submit(request).status();
        EXPECT_TRUE(absl::IsInvalidArgument(status)) << c.field << ": " << status;
        EXPECT_NE(status.message().find(c.field), std::string::npos) << status;
    }
    EXPECT_TRUE(coordinator.ListJobs().empty()) << "a refused job must leave nothing behind";
    // No budget, said explicitly: accepted, and it runs until cancelled.
    JobRequest open_ended = SmallJob(1000);
    open_ended.spec.photon_budget = 0;
    open_ended.spec.until_cancelled = true;
    const absl::StatusOr<JobProgress> submitted = coordinator.Submit(open_ended);
    ASSERT_TRUE(submitted.ok()) << submitted.status();
    EXPECT_TRUE(coordinator.Cancel(submitted->job_id).ok());
}

TEST(CoordinatorTest, AJobWhoseEpochsCannotKeepTheWorkersBusyIsSubmittedWithAWarning) {
    FakeClock clock;
    Coordinator coordinator(Options(&clock));
    const absl::StatusOr<JobProgress> alone = coordinator.Submit(SmallJob(4 * 4096));
    ASSERT_TRUE(alone.ok()) << alone.status();
    EXPECT_TRUE(alone->warnings.empty()) << "no workers yet: nothing to warn about";
    WorkerRegistration big = Cpu();
    big.threads = 64;
    ASSERT_TRUE(coordinator.RegisterWorker(big).ok());
    const absl::StatusOr<JobProgress> starved =
        coordinator.Submit(SmallJob(4 * 4096));  // 4 one-chunk batches
    ASSERT_TRUE(starved.ok()) << starved.status();
    ASSERT_EQ(starved->warnings.size(), 1u);
    EXPECT_NE(starved->warnings[0].find("4 chunks"), std::string::npos) << starved->warnings[0];
    EXPECT_NE(starved->warnings[0].find("64 threads"), std::string::npos) << starved->warnings[0];
}

}  // namespace
}  // namespace pf
