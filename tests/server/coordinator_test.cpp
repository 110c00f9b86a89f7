// The coordinator's logic without a socket: leases and their expiry, refusals (duplicate,
// stale, job gone, unknown worker, forged), in-order merging whatever the arrival order,
// cancellation, priorities and fairness, settings errors that name the field, client limits,
// checkpoints and their restoring, and the Prometheus metrics.
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

#include "absl/strings/str_split.h"
#include "core/scene/scene_loader.h"
#include "core/util/file_io.h"
#include "embedded/local_render.h"
#include "server/checkpoint_store.h"
#include "server/in_process_source.h"
#include "server/metrics.h"
#include "tests/support/test_env.h"
#include "worker/backend_factory.h"
#include "worker/worker_loop.h"

namespace pf {
namespace {

std::string ScenePath(const std::string& name) {
    return std::string(PF_SOURCE_DIR) + "/scenes/" + name;
}

JobSpec SmallSpec(uint64_t photons) {
    JobSpec spec;
    spec.width = 32;
    spec.height = 32;
    spec.photon_budget = photons;
    spec.layout = {1u << 12, 4};
    return spec;
}

JobRequest SmallJob(uint64_t photons, int priority = 0, std::string owner = "tester") {
    absl::StatusOr<SceneBundle> bundle = PackSceneBundle(ScenePath("cornell-box.gltf"));
    EXPECT_TRUE(bundle.ok()) << bundle.status();
    return {"test", std::move(owner), std::move(*bundle), SmallSpec(photons), priority};
}

// A clock the test moves by hand.
struct FakeClock {
    Clock::time_point now = Clock::time_point() + std::chrono::hours(1);
    void Advance(double seconds) {
        now += std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
    }
};

CoordinatorOptions Options(FakeClock* clock) {
    CoordinatorOptions options;
    options.lease_seconds = 30;
    options.worker_timeout_seconds = 10;
    options.now = [clock] { return clock->now; };
    return options;
}

WorkerRegistration Cpu() { return {"cpu", 1, std::string(kPhotonfarmVersion), ""}; }

// Runs batches the way a worker would, for reports made by hand.
class BatchRunner {
public:
    std::vector<BatchResult> Run(const CoordinatorLease& lease) {
        if (!backend_ || job_ != lease.grant.job) {
            backend_ = *CreateBackend("cpu", lease.grant.job->scene);
            job_ = lease.grant.job;
            EXPECT_TRUE(
                backend_->BeginJob({&job_->scene, &job_->emitters, *job_->hit_points, job_->seed})
                    .ok());
            epoch_ = UINT64_MAX;
        }
        if (epoch_ != lease.grant.epoch) {
            EXPECT_TRUE(backend_->BeginEpoch(lease.grant.epoch, *lease.grant.radius_sq).ok());
        }
        epoch_ = lease.grant.epoch;
        return *backend_->RunBatches(lease.grant.batches);
    }

private:
    std::unique_ptr<Backend> backend_;
    std::shared_ptr<const JobPayload> job_;
    uint64_t epoch_ = UINT64_MAX;
};

bool SamePixels(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Rgb)) == 0;
}

TEST(CoordinatorTest, ResultsInAnyOrderFromAnyWorkerGiveTheEmbeddedImage) {
    RenderSettings settings;
    settings.scene_path = ScenePath("cornell-box.gltf");
    settings.job = SmallSpec(3 * 4 * 4096);
    settings.threads = 1;
    const absl::StatusOr<RenderOutcome> reference = RenderLocally(settings);
    ASSERT_TRUE(reference.ok()) << reference.status();

    FakeClock clock;
    Coordinator coordinator(Options(&clock));
    const absl::StatusOr<JobProgress> job =
        coordinator.Submit(SmallJob(settings.job.photon_budget));
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
        {"settings.alpha", [](JobRequest& r) { r.spec.alpha = 0; }},
        {"settings.initial_radius", [](JobRequest& r) { r.spec.initial_radius = -1; }},
        {"settings.photons_per_batch", [](JobRequest& r) { r.spec.layout.photons_per_batch = 0; }},
        {"settings.batches_per_epoch", [](JobRequest& r) { r.spec.layout.batches_per_epoch = 0; }},
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

TEST(CoordinatorTest, AJobNoConnectedWorkerRunsIsSubmittedWithAWarningAndWaits) {
    FakeClock clock;
    Coordinator coordinator(Options(&clock));
    const std::string gpu =
        *coordinator.RegisterWorker({"vulkan", 1, std::string(kPhotonfarmVersion), ""});
    JobRequest request = SmallJob(4 * 4096);
    request.spec.integrator = Integrator::kPath;
    request.spec.photon_budget = 0;
    request.spec.epoch_budget = 2;
    const absl::StatusOr<JobProgress> waiting = coordinator.Submit(std::move(request));
    ASSERT_TRUE(waiting.ok()) << waiting.status();
    ASSERT_EQ(waiting->warnings.size(), 1u);
    EXPECT_NE(waiting->warnings[0].find(
                  "no connected worker runs the path integrator (connected: vulkan)"),
              std::string::npos)
        << waiting->warnings[0];
    const absl::StatusOr<CoordinatorLease> lease = coordinator.Lease(gpu, 4, 0);
    ASSERT_TRUE(lease.ok()) << lease.status();
    EXPECT_TRUE(lease->grant.batches.empty())
        << "a vulkan worker is never leased a path tracing job";
    // A ppm job, which the vulkan worker runs, comes without the warning.
    const absl::StatusOr<JobProgress> ppm = coordinator.Submit(SmallJob(64 * 4096));
    ASSERT_TRUE(ppm.ok()) << ppm.status();
    EXPECT_TRUE(ppm->warnings.empty()) << ppm->warnings[0];
}

}  // namespace
}  // namespace pf

namespace pf {
namespace {

// A checkpoint folder of its own, in this process's own temporary folder, removed at the end.
struct TempDir {
    std::string path = testing::FreshTempDir("checkpoints").string();
    ~TempDir() { std::filesystem::remove_all(path); }
};

CoordinatorOptions Durable(FakeClock* clock, const std::string& dir) {
    CoordinatorOptions options = Options(clock);
    options.checkpoint_dir = dir;
    options.checkpoint_seconds = 3600;  // only when the test asks, a job ends, and at the end
    return options;
}

// Leases and reports `batches` batches of the job, one at a time.
void RunBatches(Coordinator& coordinator, const std::string& worker, const std::string& job_id,
                int batches, BatchRunner& runner) {
    for (int i = 0; i < batches; ++i) {
        const absl::StatusOr<CoordinatorLease> lease = coordinator.Lease(worker, 1, 0);
        ASSERT_TRUE(lease.ok() && lease->grant.batches.size() == 1);
        for (BatchResult& result : runner.Run(*lease))
            ASSERT_EQ(*coordinator.Report(worker, job_id, std::move(result)),
                      TallyVerdict::kAccepted);
    }
}

// A job's checkpoint files (checkpoint-SEQUENCE.pfc), oldest first; not its fixed parts.
std::vector<std::filesystem::path> CheckpointFiles(const std::string& dir,
                                                   const std::string& job_id) {
    std::vector<std::filesystem::path> files;
    for (const auto& entry :
         std::filesystem::directory_iterator(std::filesystem::path(dir) / job_id))
        if (entry.path().filename().string().starts_with("checkpoint-"))
            files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    return files;
}

TEST(CoordinatorCheckpointTest, JobsResumeInANewCoordinatorBitIdentical) {
    RenderSettings settings;
    settings.scene_path = ScenePath("cornell-box.gltf");
    settings.job = SmallSpec(3 * 4 * 4096);
    settings.threads = 1;
    const absl::StatusOr<RenderOutcome> reference = RenderLocally(settings);
    ASSERT_TRUE(reference.ok()) << reference.status();

    TempDir dir;
    FakeClock clock;
    std::string running, cancelled;
    std::shared_ptr<const Image> cancelled_image;
    {
        Coordinator first(Durable(&clock, dir.path));
        running = first.Submit(SmallJob(settings.job.photon_budget))->job_id;
        cancelled = first.Submit(SmallJob(settings.job.photon_budget))->job_id;
        ASSERT_TRUE(first.Cancel(cancelled).ok());
        cancelled_image = (*first.FindJob(cancelled))->CurrentImage();
        const std::string worker = *first.RegisterWorker(Cpu());
        BatchRunner runner;
        RunBatches(first, worker, running, 4, runner);  // epoch 0
        RunBatches(first, worker, running, 2,
                   runner);  // half of epoch 1: a checkpoint between folds
        first.WriteCheckpoints();
    }  // and at the end, as a stopping coordinator does

    Coordinator second(Durable(&clock, dir.path));
    ASSERT_EQ(second.RestoreCheckpoints(), 2u);
    const std::vector<JobProgress> jobs = second.ListJobs();
    ASSERT_EQ(jobs.size(), 2u);
    EXPECT_EQ(jobs[0].job_id, running) << "in submission order";
    EXPECT_EQ(jobs[0].state, JobState::kRunning);
    EXPECT_EQ(jobs[0].epochs, 1u);
    EXPECT_EQ(jobs[1].state, JobState::kCancelled);
    EXPECT_TRUE(SamePixels(*(*second.FindJob(cancelled))->CurrentImage(), *cancelled_image))
        << "an ended job keeps its final image";
    // Epoch 1's first two batches were folded before the checkpoint: only the last two are out.
    const std::string worker = *second.RegisterWorker(Cpu());
    const absl::StatusOr<CoordinatorLease> lease = second.Lease(worker, 8, 0);
    ASSERT_TRUE(lease.ok());
    ASSERT_EQ(lease->grant.batches.size(), 2u);
    EXPECT_EQ(lease->grant.batches[0].index, 4u + 2u);
    BatchRunner runner;
    for (BatchResult& result : runner.Run(*lease))
        ASSERT_EQ(*second.Report(worker, running, std::move(result)), TallyVerdict::kAccepted);
    RunBatches(second, worker, running, 4, runner);  // epoch 2
    const std::shared_ptr<Job> done = *second.FindJob(running);
    EXPECT_EQ(done->Progress(clock.now).state, JobState::kDone);
    EXPECT_TRUE(SamePixels(*done->CurrentImage(), reference->image))
        << "resumed, it ends as an uninterrupted render";
    const std::string next = second.Submit(SmallJob(1000))->job_id;
    EXPECT_NE(next, running);
    EXPECT_NE(next, cancelled);
}

TEST(CoordinatorCheckpointTest, CorruptOrTruncatedCheckpointsFallBackToThePreviousOne) {
    TempDir dir;
    FakeClock clock;
    std::string job_id;
    {
        Coordinator coordinator(Durable(&clock, dir.path));
        job_id = coordinator.Submit(SmallJob(1'000'000))->job_id;
        const std::string worker = *coordinator.RegisterWorker(Cpu());
        BatchRunner runner;
        RunBatches(coordinator, worker, job_id, 4, runner);
        coordinator.WriteCheckpoints();  // at epoch 1
        RunBatches(coordinator, worker, job_id, 4, runner);
    }  // at epoch 2, written as it stops
    const std::vector<std::filesystem::path> files = CheckpointFiles(dir.path, job_id);
    ASSERT_EQ(files.size(), 2u) << "the latest two are kept";
    const auto epochs_resumed = [&] {
        Coordinator coordinator(Durable(&clock, dir.path));
        if (coordinator.RestoreCheckpoints() != 1) return uint64_t{0};
        return coordinator.ListJobs().at(0).epochs;
    };
    // One bit flipped in the middle of the newest (epoch 2): its checksum fails, and the one
    // before (epoch 1) is used.
    std::string bytes;
    {
        std::ifstream file(files.back(), std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(file), {});
    }
    bytes[bytes.size() / 2] ^= 1;
    std::ofstream(files.back(), std::ios::binary | std::ios::trunc) << bytes;
    EXPECT_EQ(epochs_resumed(), 1u);
    // Both cut short: nothing is resumed, and nothing crashes.
    for (const std::filesystem::path& file : CheckpointFiles(dir.path, job_id))
        std::filesystem::resize_file(file, 100);
    EXPECT_EQ(epochs_resumed(), 0u);
}

// A job's fixed parts (KIND-SHA256.fixed), sorted.
std::vector<std::filesystem::path> FixedParts(const std::string& dir, const std::string& job_id) {
    std::vector<std::filesystem::path> files;
    for (const auto& entry :
         std::filesystem::directory_iterator(std::filesystem::path(dir) / job_id))
        if (entry.path().extension() == ".fixed") files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    return files;
}

// Each file's inode and modification time: a file written again (a new file renamed over it)
// changes both.
std::map<std::string, std::pair<ino_t, int64_t>> Identities(
    const std::vector<std::filesystem::path>& files) {
    std::map<std::string, std::pair<ino_t, int64_t>> identities;
    for (const std::filesystem::path& file : files) {
        struct stat status {};
        EXPECT_EQ(stat(file.c_str(), &status), 0) << file;
        identities[file.string()] = {
            status.st_ino, int64_t(status.st_mtim.tv_sec) * 1'000'000'000 + status.st_mtim.tv_nsec};
    }
    return identities;
}

std::string ReadWholeFile(const std::filesystem::path& path) {
    std::ifstream file(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(file), {});
}

TEST(CoordinatorCheckpointTest, FixedPartsAreWrittenOncePerJob) {
    TempDir dir;
    FakeClock clock;
    std::string job_id;
    std::map<std::string, std::pair<ino_t, int64_t>> written;
    {
        Coordinator first(Durable(&clock, dir.path));
        job_id = first.Submit(SmallJob(1'000'000))->job_id;
        const std::string worker = *first.RegisterWorker(Cpu());
        BatchRunner runner;
        RunBatches(first, worker, job_id, 4, runner);
        first.WriteCheckpoints();
        ASSERT_EQ(FixedParts(dir.path, job_id).size(), 2u) << "the scene and the hit points";
        written = Identities(FixedParts(dir.path, job_id));
        RunBatches(first, worker, job_id, 2, runner);
        first.WriteCheckpoints();
        ASSERT_EQ(CheckpointFiles(dir.path, job_id).size(), 2u);
        EXPECT_EQ(Identities(FixedParts(dir.path, job_id)), written) << "not written again";

        const absl::StatusOr<JobCheckpointData> latest =
            CheckpointStore(dir.path).Read(CheckpointFiles(dir.path, job_id).back().string());
        ASSERT_TRUE(latest.ok()) << latest.status();
        ASSERT_EQ(latest->record.fixed_parts_size(), 2);
        ASSERT_TRUE(latest->fixed.contains("scene") && latest->fixed.contains("estimate"));
        EXPECT_LT(latest->record.ByteSizeLong(), latest->fixed.at("scene")->bytes.size())
            << "the record names the scene, not carries it";
        ByteReader state(latest->estimate);
        const absl::Status without = LoadEstimate(state).status();
        EXPECT_TRUE(absl::IsDataLoss(without) &&
                    without.message().find("kept apart") != std::string_view::npos)
            << "nor does the state hold the hit points: " << without;
    }  // and once more as it stops
    Coordinator second(Durable(&clock, dir.path));
    ASSERT_EQ(second.RestoreCheckpoints(), 1u);
    const std::string worker = *second.RegisterWorker(Cpu());
    BatchRunner runner;
    RunBatches(second, worker, job_id, 2, runner);
    second.WriteCheckpoints();
    EXPECT_EQ(CheckpointFiles(dir.path, job_id).size(), 2u);
    EXPECT_EQ(Identities(FixedParts(dir.path, job_id)), written)
        << "a resumed job's checkpoints name the same files";
}

TEST(CoordinatorCheckpointTest, MissingOrAlteredFixedPartsAreRefusedNamingThem) {
    TempDir dir;
    FakeClock clock;
    std::string job_id;
    {
        Coordinator coordinator(Durable(&clock, dir.path));
        job_id = coordinator.Submit(SmallJob(1'000'000))->job_id;
        const std::string worker = *coordinator.RegisterWorker(Cpu());
        BatchRunner runner;
        RunBatches(coordinator, worker, job_id, 4, runner);
    }  // its checkpoint written as it stops
    const std::vector<std::filesystem::path> parts = FixedParts(dir.path, job_id);
    ASSERT_EQ(parts.size(), 2u);
    const std::string checkpoint = CheckpointFiles(dir.path, job_id).back().string();
    const CheckpointStore store(dir.path);
    ASSERT_TRUE(store.Read(checkpoint).ok());
    const auto resumed = [&] {
        Coordinator coordinator(Durable(&clock, dir.path));
        return coordinator.RestoreCheckpoints();
    };
    // DATA_LOSS, naming the part's file and saying what is wrong with it.
    const auto refused = [&](const std::filesystem::path& part, const std::string& what) {
        const absl::Status status = store.Read(checkpoint).status();
        EXPECT_TRUE(absl::IsDataLoss(status)) << status;
        EXPECT_NE(status.message().find(part.string()), std::string_view::npos) << status;
        EXPECT_NE(status.message().find(what), std::string_view::npos) << status;
        EXPECT_EQ(resumed(), 0u) << "not resumed without its " << part;
    };
    for (const std::filesystem::path& part : parts) {
        const std::string saved = ReadWholeFile(part);
        // Another file, whole (its own checksum holds), in its place.
        ASSERT_TRUE(WriteChecksummedFile(part.string(), {"other contents"}).ok());
        refused(part, "altered");
        std::string flipped = saved;
        flipped[flipped.size() / 2] ^= 1;
        std::ofstream(part, std::ios::binary | std::ios::trunc) << flipped;
        refused(part, "corrupt");
        std::filesystem::remove(part);
        refused(part, "missing");
        std::ofstream(part, std::ios::binary | std::ios::trunc) << saved;
        EXPECT_EQ(resumed(), 1u) << "resumed once " << part << " is back";
    }
}

TEST(CoordinatorCheckpointTest, IdleJobsAreNotRewrittenAndForgottenOnesLoseTheirCheckpoints) {
    TempDir dir;
    FakeClock clock;
    CoordinatorOptions options = Durable(&clock, dir.path);
    options.finished_jobs_kept = 0;
    Coordinator coordinator(options);
    const std::string first = coordinator.Submit(SmallJob(1'000'000))->job_id;
    coordinator.WriteCheckpoints();
    ASSERT_TRUE(std::filesystem::exists(std::filesystem::path(dir.path) / first));
    coordinator.WriteCheckpoints();
    EXPECT_EQ(CheckpointFiles(dir.path, first).size(), 1u) << "an idle job is not written again";
    ASSERT_TRUE(coordinator.Cancel(first).ok());
    ASSERT_TRUE(coordinator.Submit(SmallJob(1'000'000)).ok());  // forgets the ended job
    coordinator.WriteCheckpoints();
    EXPECT_FALSE(std::filesystem::exists(std::filesystem::path(dir.path) / first));
}

}  // namespace
}  // namespace pf

namespace pf {
namespace {

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
