// The farm under faults and bad input: cancelled and stalled jobs, forged and malformed
// requests, a coordinator killed at random moments, workers told to stop (the fixture in
// farm_fixture.h).
#include <algorithm>
#include <string>
#include <vector>

#include "tests/integration/farm_fixture.h"
#include "wire/blob_codec.h"

namespace pf {
namespace {

using namespace farm;  // NOLINT: the fixture and its helpers

TEST_F(FarmTest, CancelledJobStopsItsLeasesAndKeepsItsImage) {
    StartWorker();
    const v1::JobStatus job = Submit(1000);
    ASSERT_EQ(
        WatchUntil(job.job_id(), [&](const v1::JobStatus& status) { return status.epochs() >= 1; })
            .state(),
        v1::JOB_STATE_RUNNING);
    ASSERT_EQ(RunClient(Concat({"cancel", job.job_id(), "--server", address_},
                               Credentials().ClientFlags())),
              0);
    EXPECT_EQ(WatchUntil(job.job_id()).state(), v1::JOB_STATE_CANCELLED);
    const absl::StatusOr<v1::ListWorkersResponse> workers = client_->ListWorkers();
    ASSERT_TRUE(workers.ok());
    for (const v1::WorkerStatus& worker : workers->workers())
        EXPECT_EQ(worker.batches_leased(), 0u);
    const absl::StatusOr<v1::GetResultResponse> result = client_->GetResult(job.job_id());
    ASSERT_TRUE(result.ok() && result->has_image());
    EXPECT_GE(result->status().epochs(), 1u);
}

// A hand-driven worker: forged but well-formed results (no photons found) for leased batches.
class FakeWorker {
public:
    explicit FakeWorker(const std::string& address)
        : stub_(v1::Work::NewStub(OpenChannel(address, Credentials().Worker()))) {
        v1::RegisterWorkerRequest request;
        request.set_backend("cpu");
        request.set_version(std::string(kPhotonfarmVersion));
        v1::RegisterWorkerResponse response;
        grpc::ClientContext context;
        EXPECT_TRUE(stub_->RegisterWorker(&context, request, &response).ok());
        id_ = response.worker_id();
    }
    grpc::Status Lease(uint32_t chunks, v1::LeaseBatchesResponse* response) {
        v1::LeaseBatchesRequest request;
        request.set_worker_id(id_);
        request.set_chunks(chunks);
        grpc::ClientContext context;
        return stub_->LeaseBatches(&context, request, response);
    }
    v1::TallyVerdict Report(const v1::JobInputs& job, const v1::BatchSpec& spec,
                            const std::string& worker = "") {
        BatchResult result;
        result.spec = FromProto(spec);
        result.samples.assign(spec.sample_end() - spec.sample_begin(), Rgb(0.0f));
        result.photons_emitted = spec.photons();
        AddEmission(job, result);
        v1::ReportTallyRequest request;
        request.set_worker_id(worker.empty() ? id_ : worker);
        request.set_job_id(job.job_id());
        *request.mutable_result() = ToProto(result);
        v1::ReportTallyResponse response;
        grpc::ClientContext context;
        last_status_ = stub_->ReportTally(&context, request, &response);
        return response.verdict();
    }
    grpc::Status last_status_;

private:
    // ppm's share of the epoch's emission pass, black but of the size the coordinator takes:
    // the slice's pixels (SlicePixels) and the job's hit points in them. None where the job's
    // hit points cannot be fetched (a job that ended): such a report is refused before its
    // emission is read.
    void AddEmission(const v1::JobInputs& job, BatchResult& result) {
        const absl::StatusOr<JobSpec> spec = FromProto(job.settings());
        if (!spec.ok() || spec->integrator != Integrator::kPpm) return;
        if (hit_points_.empty()) {
            v1::FetchBlobRequest request;
            request.set_digest(job.hit_points_digest());
            grpc::ClientContext context;
            std::unique_ptr<grpc::ClientReader<v1::BlobChunk>> reader =
                stub_->FetchBlob(&context, request);
            std::string bytes;
            for (v1::BlobChunk chunk; reader->Read(&chunk);) bytes += chunk.data();
            if (!reader->Finish().ok()) return;
            absl::StatusOr<std::vector<HitPoint>> points =
                DecodeHitPoints(bytes, job.hit_point_count());
            if (!points.ok()) return;
            hit_points_ = std::move(*points);
        }
        const auto [first, end] =
            SlicePixels(result.spec, EpochCameraSamples(*spec, result.spec.epoch).per_pixel);
        result.emission.assign(end - first, Rgb(0.0f));
        result.coverage.assign(std::ranges::count_if(hit_points_,
                                                     [first, end](const HitPoint& point) {
                                                         return point.pixel >= first &&
                                                                point.pixel < end;
                                                     }),
                               Rgb(0.0f));
    }

    std::unique_ptr<v1::Work::Stub> stub_;
    std::string id_;
    std::vector<HitPoint> hit_points_;  // the job's, fetched for the first report
};

// A job that stalls (here: no worker at all) fails its watch at the deadline with the job's
// status and the farm's state, instead of hanging the suite until CTest's limit.
TEST_F(FarmTest, AStalledJobFailsItsWatchWithTheJobsStatus) {
    const v1::JobStatus job = Submit(kEpochs);
    const absl::StatusOr<v1::Snapshot> watched = client_->Watch(
        job.job_id(), 0, false, [](const v1::Snapshot&) { return true; }, 0.5);
    ASSERT_TRUE(absl::IsDeadlineExceeded(watched.status())) << watched.status();
    EXPECT_NE(watched.status().message().find("job " + job.job_id() +
                                              " did not end within 0.5 s; last seen: running, 0 "
                                              "epochs, 0 photons, 0 workers active"),
              std::string::npos)
        << watched.status();
    EXPECT_NONFATAL_FAILURE(WatchUntil(job.job_id(), {}, 0.5),
                            "job " + job.job_id() + ": running, 0 epochs");
    EXPECT_NONFATAL_FAILURE(WatchUntil(job.job_id(), {}, 0.5), "; 0 workers");
}

TEST_F(FarmTest, DuplicateStaleAndUnknownTalliesAreRefused) {
    const v1::JobStatus job = Submit(kEpochs);
    FakeWorker worker(address_);
    v1::LeaseBatchesResponse epoch0;
    ASSERT_TRUE(worker.Lease(8, &epoch0).ok());
    ASSERT_EQ(epoch0.batches_size(), 8);
    EXPECT_EQ(worker.Report(epoch0.job(), epoch0.batches(0)), v1::TALLY_VERDICT_ACCEPTED);
    EXPECT_EQ(worker.Report(epoch0.job(), epoch0.batches(0)), v1::TALLY_VERDICT_DUPLICATE);
    for (int i = 1; i < 8; ++i)
        EXPECT_EQ(worker.Report(epoch0.job(), epoch0.batches(i)), v1::TALLY_VERDICT_ACCEPTED);
    EXPECT_EQ(worker.Report(epoch0.job(), epoch0.batches(3)), v1::TALLY_VERDICT_STALE)
        << "epoch 0 is merged";
    worker.Report(epoch0.job(), epoch0.batches(3), "worker-forged");
    EXPECT_EQ(worker.last_status_.error_code(), grpc::StatusCode::NOT_FOUND) << "an unknown worker";
    ASSERT_TRUE(client_->Cancel(job.job_id()).ok());
    v1::LeaseBatchesResponse none;
    ASSERT_TRUE(worker.Lease(8, &none).ok());
    EXPECT_EQ(none.batches_size(), 0) << "a cancelled job hands out nothing";
    EXPECT_EQ(worker.Report(epoch0.job(), epoch0.batches(0)), v1::TALLY_VERDICT_JOB_GONE);
}

// The farm over a bad network (testing::FaultProxy between workers and the coordinator): one
// worker's every packet delayed 5-25 ms, another's connections reset again and again, and a
// hand-driven worker partitioned for longer than its lease while it holds a batch. The
// partitioned batch is leased again when its lease expires (the epochs go on without it), its
// late result is refused as stale once the partition heals, and the image is bit-identical
// to an uninterrupted render.
TEST_F(FarmTest, ABadNetworkLosesNothingAndCountsNothingTwice) {
    StopCoordinator();
    // Leases of a second; workers never declared gone here, so that the late result meets its
    // verdict rather than an unknown worker.
    StartCoordinator("127.0.0.1:0", {"--lease-seconds", "1"}, /*worker_timeout_seconds=*/600);
    ASSERT_FALSE(HasFatalFailure());
    auto slow = testing::FaultProxy::Start(address_);
    auto flaky = testing::FaultProxy::Start(address_);
    auto partitioned = testing::FaultProxy::Start(address_);
    ASSERT_TRUE(slow.ok() && flaky.ok() && partitioned.ok());
    (*slow)->SetDelay(0.005, 0.02);
    StartWorker("cpu", 1, (*slow)->Address());
    StartWorker("cpu", 1, (*flaky)->Address());
    FakeWorker straggler((*partitioned)->Address());
    const v1::JobStatus job = Submit(kLongEpochs);
    v1::LeaseBatchesResponse held;
    ASSERT_TRUE(straggler.Lease(1, &held).ok());
    ASSERT_EQ(held.batches_size(), 1) << FarmState();
    const uint64_t held_epoch = held.batches(0).epoch();

    (*partitioned)->Partition(true);
    v1::TallyVerdict late = v1::TALLY_VERDICT_UNSPECIFIED;
    std::thread report([&] { late = straggler.Report(held.job(), held.batches(0)); });
    // The epochs go on past the held batch's only once its lease expired and another worker
    // ran it; meanwhile the flaky worker's connections are reset every 100 ms.
    const v1::JobStatus moved_on = WatchUntil(job.job_id(), [&](const v1::JobStatus& status) {
        (*flaky)->DropConnections();
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
        return status.epochs() >= held_epoch + 2;
    });
    EXPECT_GE(moved_on.epochs(), held_epoch + 2) << "the held batch was leased again";
    (*partitioned)->Partition(false);
    report.join();
    EXPECT_TRUE(straggler.last_status_.ok()) << straggler.last_status_.error_message();
    EXPECT_EQ(late, v1::TALLY_VERDICT_STALE) << "the epoch of the late result has merged";
    EXPECT_GE((*flaky)->ConnectionsAccepted(), 2u) << "the flaky worker reconnected";

    ASSERT_EQ(WatchUntil(job.job_id()).state(), v1::JOB_STATE_DONE);
    const absl::StatusOr<v1::GetResultResponse> result = client_->GetResult(job.job_id());
    ASSERT_TRUE(result.ok()) << result.status();
    const absl::StatusOr<Image> image = FromProto(result->image());
    ASSERT_TRUE(image.ok());
    EXPECT_TRUE(Identical(image->pixels, Reference(kLongEpochs)))
        << "the job's image differs from an uninterrupted render";
}

TEST_F(FarmTest, MalformedRequestsNameTheField) {
    v1::SubmitJobRequest request;
    absl::Status status = client_->Submit(request).status();
    EXPECT_TRUE(absl::IsInvalidArgument(status)) << status;
    EXPECT_NE(status.message().find("scene"), std::string::npos) << status;
    *request.mutable_scene() = ToProto(*PackSceneBundle(kScene));
    request.mutable_settings()->set_photon_budget(1000);
    request.mutable_settings()->set_alpha(5);
    status = client_->Submit(request).status();
    EXPECT_TRUE(absl::IsInvalidArgument(status)) << status;
    EXPECT_NE(status.message().find("settings.alpha"), std::string::npos) << status;
    request.mutable_settings()->set_alpha(0.5);
    request.mutable_scene()->mutable_files(0)->set_path("../escape.gltf");
    status = client_->Submit(request).status();
    EXPECT_TRUE(absl::IsInvalidArgument(status)) << status;
    EXPECT_NE(status.message().find("scene.files"), std::string::npos) << status;
    FakeWorker worker(address_);
    v1::LeaseBatchesResponse response;
    const grpc::Status lease = worker.Lease(0, &response);
    EXPECT_EQ(lease.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_NE(lease.error_message().find("chunks"), std::string::npos) << lease.error_message();
    EXPECT_TRUE(absl::IsNotFound(client_->Cancel("job-none").status()));
}

TEST_F(FarmTest, HealthServiceAnswersServing) {
    // Probes carry no token: the health service is open to anyone who can complete TLS.
    ChannelSecurity security = Credentials().Client();
    security.token.clear();
    auto health = grpc::health::v1::Health::NewStub(OpenChannel(address_, security));
    grpc::ClientContext context;
    grpc::health::v1::HealthCheckResponse response;
    ASSERT_TRUE(health->Check(&context, {}, &response).ok());
    EXPECT_EQ(response.status(), grpc::health::v1::HealthCheckResponse::SERVING);
}

// The coordinator killed (SIGKILL) at random moments and restarted on its checkpoints: every
// unfinished job resumes, with at least the epochs of the last checkpoint before the kill, the
// workers find it again on their own, and the images come out bit-identical to uninterrupted
// renders. The moments come from a seed that is printed (PF_TEST_SEED repeats them; the
// processes' own timing still varies from run to run).
TEST_F(FarmTest, CoordinatorKilledAtRandomMomentsResumesEveryJobBitIdentical) {
    // A coordinator with checkpoints, on a port the kernel chose, which its restarts reuse so
    // that the workers find them.
    StopCoordinator();
    const std::filesystem::path checkpoints = testing::FreshTempDir("checkpoints");
    const std::vector<std::string> durable = {"--checkpoint-dir", checkpoints.string(),
                                              "--checkpoint-seconds", "0.05"};
    StartCoordinator("127.0.0.1:0", durable);
    ASSERT_FALSE(HasFatalFailure());
    const std::string listen = "127.0.0.1:" + address_.substr(address_.rfind(':') + 1);
    StartWorker();
    StartWorker();
    const v1::JobStatus first = Submit(2 * kLongEpochs);
    const v1::JobStatus second = Submit(kLongEpochs, 0, 0, /*stream=*/2);
    std::mt19937_64 rng(testing::TestSeed());
    constexpr int kKills = 3;
    int kills = 0;
    for (int kill = 0; kill < kKills; ++kill) {
        // A moment in the first half of the first job, which therefore is still running: every
        // kill happens (between the moment and the kill pass two checkpoints and at most 60
        // ms, a few epochs, not the 40 left).
        const uint64_t epochs = std::uniform_int_distribution<uint64_t>(2, kLongEpochs)(rng);
        SCOPED_TRACE(::testing::Message() << "kill " << kill << " after epoch " << epochs);
        const v1::JobStatus before = WatchUntil(
            first.job_id(), [&](const v1::JobStatus& status) { return status.epochs() >= epochs; });
        ASSERT_EQ(before.state(), v1::JOB_STATE_RUNNING);
        // Two checkpoints written after that moment: the second was begun after the first
        // ended, so after the moment, and holds at least `epochs` (a checkpoint being written
        // as the moment passed may hold fewer).
        const std::filesystem::path job_dir = checkpoints / first.job_id();
        const uint64_t then = NewestCheckpoint(job_dir);
        const auto deadline = std::chrono::steady_clock::now() +
                              std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                  std::chrono::duration<double>(DeadlineSeconds()));
        while (NewestCheckpoint(job_dir) < then + 2) {
            ASSERT_LT(std::chrono::steady_clock::now(), deadline)
                << "no checkpoint of " << job_dir << " past " << then << "; " << FarmState();
            std::this_thread::sleep_for(std::chrono::milliseconds(5));  // polling the folder
        }
        // Then the kill, up to 60 ms later, so that it falls anywhere in an epoch: mid-fold,
        // mid-checkpoint, with leases out. The wait draws the moment; nothing waits on it.
        std::this_thread::sleep_for(
            std::chrono::milliseconds(std::uniform_int_distribution<int>(0, 60)(rng)));
        coordinator_->Signal(SIGKILL);
        ASSERT_EQ(coordinator_->Wait(DeadlineSeconds()), 128 + SIGKILL);
        coordinator_.reset();
        ++kills;
        StartCoordinator(listen, durable);
        ASSERT_FALSE(HasFatalFailure());
        const absl::StatusOr<v1::ListJobsResponse> jobs = client_->ListJobs();
        ASSERT_TRUE(jobs.ok()) << jobs.status();
        ASSERT_EQ(jobs->jobs_size(), 2) << "both jobs resume";
        EXPECT_EQ(jobs->jobs(0).job_id(), first.job_id());
        EXPECT_GE(jobs->jobs(0).epochs(), epochs) << "the checkpointed work was kept";
    }
    EXPECT_EQ(kills, kKills);
    ASSERT_EQ(WatchUntil(first.job_id()).state(), v1::JOB_STATE_DONE);
    ASSERT_EQ(WatchUntil(second.job_id()).state(), v1::JOB_STATE_DONE);
    for (const auto& [job, expected] : {std::pair{first.job_id(), Reference(2 * kLongEpochs)},
                                        std::pair{second.job_id(), Reference(kLongEpochs, 2)}}) {
        const absl::StatusOr<v1::GetResultResponse> result = client_->GetResult(job);
        ASSERT_TRUE(result.ok()) << result.status();
        const absl::StatusOr<Image> image = FromProto(result->image());
        ASSERT_TRUE(image.ok());
        EXPECT_TRUE(Identical(image->pixels, expected))
            << job << " differs from an uninterrupted render";
    }
}

TEST_F(FarmTest, WorkerLeavesCleanlyOnSigterm) {
    ChildProcess& worker = StartWorker();
    const v1::JobStatus job = Submit(1000);
    ASSERT_EQ(
        WatchUntil(job.job_id(), [&](const v1::JobStatus& status) { return status.epochs() >= 1; })
            .state(),
        v1::JOB_STATE_RUNNING);
    worker.Signal(SIGTERM);
    EXPECT_EQ(worker.Wait(DeadlineSeconds()), 0);
    const absl::StatusOr<v1::ListWorkersResponse> workers = client_->ListWorkers();
    ASSERT_TRUE(workers.ok());
    EXPECT_EQ(workers->workers_size(), 0) << "the worker unregisters as it leaves";
    ASSERT_TRUE(client_->Cancel(job.job_id()).ok());
}

}  // namespace
}  // namespace pf
