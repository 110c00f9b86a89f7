// The farm as users run it: a real photonfarm-coordinator and photonfarm-worker processes on
// 127.0.0.1 with ephemeral ports, jobs submitted through the client. Images must come out
// bit-identical to `photonfarm render` however many workers ran them and whichever died.
#include <grpcpp/client_context.h>
#include <grpcpp/create_channel.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <memory>
#include <random>
#include <thread>

#include "client/farm_client.h"
#include "core/film/exr_io.h"
#include "core/film/image_metrics.h"
#include "core/scene/scene_bundle.h"
#include "core/scene/scene_loader.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "photonfarm/v1/work.grpc.pb.h"
#include "tests/support/child_process.h"
#include "tests/support/farm_credentials.h"
#include "tests/support/image_agreement.h"
#include "tests/support/vulkan_validation.h"
#include "worker/proto_convert.h"
#include "worker/secure_channel.h"
#include "worker/work_source.h"

namespace pf {
namespace {

namespace v1 = photonfarm::v1;
using testing::ChildProcess;

const std::string kBin = PF_BINARY_DIR;
const std::string kScene = std::string(PF_SOURCE_DIR) + "/scenes/cornell-box.gltf";
// 48x48, 4 spp, epochs of 8 batches of 2^13 photons.
const std::vector<std::string> kJobFlags = {
    "--width", "48",     "--height", "48", "--photons-per-batch", "8192", "--batches-per-epoch",
    "8",       "--seed", "11"};
constexpr int kEpochs = 6;
// Long enough (~1 s on two cores) for something to happen while the job runs.
constexpr int kLongEpochs = 40;

// The farm runs as it would on a network: TLS, workers with certificates, tokens.
const testing::FarmCredentials& Credentials() { return testing::TestCredentials(PF_SOURCE_DIR); }

std::string TempPath(const std::string& name) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("pf-farm-test-" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);
    return (dir / name).string();
}

std::vector<std::string> Concat(std::vector<std::string> a, const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

// Pixels of an EXR, compared byte for byte.
std::vector<Rgb> Pixels(const std::string& path) {
    absl::StatusOr<Image> image = ReadExr(path);
    EXPECT_TRUE(image.ok()) << image.status();
    return image.ok() ? image->pixels : std::vector<Rgb>{};
}

bool Identical(const std::vector<Rgb>& a, const std::vector<Rgb>& b) {
    return !a.empty() && a.size() == b.size() &&
           std::memcmp(a.data(), b.data(), a.size() * sizeof(Rgb)) == 0;
}

class FarmTest : public ::testing::Test {
protected:
    void SetUp() override { StartCoordinator("127.0.0.1:0"); }

    // Starts the coordinator on `listen` with the fixture's flags and connects the client.
    void StartCoordinator(const std::string& listen, const std::vector<std::string>& flags = {}) {
        coordinator_ = std::make_unique<ChildProcess>(Concat(
            Concat(
                {kBin + "/server/photonfarm-coordinator", "--listen", listen, "--heartbeat-seconds",
                 "0.2", "--worker-timeout-seconds", "1.5", "--log-level", "warn"},
                Credentials().CoordinatorFlags()),
            flags));
        const std::optional<std::string> line = coordinator_->ReadLine(30);
        ASSERT_TRUE(line && line->starts_with("listening on ")) << "the coordinator did not start";
        address_ = line->substr(std::strlen("listening on "));
        absl::StatusOr<FarmClient> client = FarmClient::Connect(address_, Credentials().Client());
        ASSERT_TRUE(client.ok()) << client.status();
        client_ = std::make_unique<FarmClient>(std::move(*client));
    }

    void TearDown() override {
        workers_.clear();  // killed and reaped
        if (coordinator_) {
            coordinator_->Signal(SIGTERM);
            EXPECT_EQ(coordinator_->Wait(30), 0) << "the coordinator must stop cleanly on SIGTERM";
        }
    }

    ChildProcess& StartWorker(const std::string& backend = "cpu") {
        workers_.push_back(std::make_unique<ChildProcess>(
            Concat({kBin + "/worker/photonfarm-worker", "--coordinator", address_, "--threads", "1",
                    "--backend", backend, "--log-level", "warn"},
                   Credentials().WorkerFlags())));
        return *workers_.back();
    }

    // `photonfarm submit --watch` to the end; returns its exit code.
    int SubmitAndWatch(const std::string& out, int epochs = kEpochs,
                       const std::vector<std::string>& flags = {}) {
        ChildProcess submit(
            Concat({kBin + "/client/photonfarm", "submit", kScene, "--server", address_, "--watch",
                    "--interval", "0", "--out", out, "--photons", std::to_string(epochs * 8 * 8192),
                    "--log-level", "warn"},
                   Concat(Concat(kJobFlags, flags), Credentials().ClientFlags())));
        return submit.Wait(300).value_or(-1);
    }

    v1::JobStatus Submit(int epochs, int priority = 0, double target_error = 0, int stream = 0) {
        absl::StatusOr<SceneBundle> bundle = PackSceneBundle(kScene);
        v1::SubmitJobRequest request;
        *request.mutable_scene() = ToProto(*bundle);
        v1::JobSettings* settings = request.mutable_settings();
        settings->set_width(48);
        settings->set_height(48);
        settings->set_photons_per_batch(8192);
        settings->set_batches_per_epoch(8);
        settings->set_seed(11);
        settings->set_photon_budget(uint64_t(epochs) * 8 * 8192);
        settings->set_priority(priority);
        settings->set_target_error(target_error);
        settings->set_photon_stream(stream);
        absl::StatusOr<v1::JobStatus> status = client_->Submit(request);
        EXPECT_TRUE(status.ok()) << status.status();
        return status.ok() ? *status : v1::JobStatus{};
    }

    // Watches the job until `predicate` holds for a snapshot, or to its end without one.
    v1::JobStatus WatchUntil(const std::string& job_id,
                             const std::function<bool(const v1::JobStatus&)>& predicate = {}) {
        absl::StatusOr<v1::Snapshot> last =
            client_->Watch(job_id, 0, false, [&](const v1::Snapshot& snapshot) {
                return !(predicate && predicate(snapshot.status()));
            });
        EXPECT_TRUE(last.ok()) << last.status();
        return last.ok() ? last->status() : v1::JobStatus{};
    }

    // `photonfarm render` of the job (another photon stream of its seed where `stream` > 0).
    std::vector<Rgb> Reference(int epochs = kEpochs, int stream = 0,
                               const std::vector<std::string>& flags = {}) {
        const std::string out = TempPath("render-" + std::to_string(stream) + ".exr");
        ChildProcess render(
            Concat({kBin + "/client/photonfarm", "render", kScene, "--threads", "2", "--out", out,
                    "--photons", std::to_string(epochs * 8 * 8192), "--photon-stream",
                    std::to_string(stream), "--log-level", "warn"},
                   Concat(kJobFlags, flags)));
        EXPECT_EQ(render.Wait(300), 0);
        return Pixels(out);
    }

    std::unique_ptr<ChildProcess> coordinator_;
    std::vector<std::unique_ptr<ChildProcess>> workers_;
    std::string address_;
    std::unique_ptr<FarmClient> client_;
};

TEST_F(FarmTest, OneWorkerThreeWorkersAndRenderGiveTheSameImage) {
    StartWorker();
    ASSERT_EQ(SubmitAndWatch(TempPath("one.exr")), 0);
    StartWorker();
    StartWorker();
    ASSERT_EQ(SubmitAndWatch(TempPath("three.exr")), 0);
    const std::vector<Rgb> reference = Reference();
    EXPECT_TRUE(Identical(Pixels(TempPath("one.exr")), reference))
        << "one worker differs from photonfarm render";
    EXPECT_TRUE(Identical(Pixels(TempPath("three.exr")), reference))
        << "three workers differ from photonfarm render";
}

TEST_F(FarmTest, EveryIntegratorGivesRendersImageOnTwoWorkers) {
    // Stochastic ppm's workers trace each epoch's hit points themselves, classic pm's build
    // the photon maps themselves, and the path tracer's render pixels: every one must still
    // give the image `photonfarm render` gives, byte for byte.
    StartWorker();
    StartWorker();
    // Rough metal and rough glass: caustics for the caustic map, glossy paths for all.
    const std::string scene = std::string(PF_SOURCE_DIR) + "/scenes/cornell-glossy.gltf";
    for (const std::string integrator : {"sppm", "pm", "path"}) {
        const std::vector<std::string> flags =
            Concat(kJobFlags, {"--integrator", integrator, "--epochs", "3", "--pm-photons", "20k",
                               "--pm-caustic-photons", "20k", "--log-level", "warn"});
        const std::string farm = TempPath("farm-" + integrator + ".exr");
        ChildProcess submit(Concat({kBin + "/client/photonfarm", "submit", scene, "--server",
                                    address_, "--watch", "--interval", "0", "--out", farm},
                                   Concat(flags, Credentials().ClientFlags())));
        ASSERT_EQ(submit.Wait(300), 0) << integrator;
        const std::string local = TempPath("render-" + integrator + ".exr");
        ChildProcess render(
            Concat({kBin + "/client/photonfarm", "render", scene, "--threads", "2", "--out", local},
                   flags));
        ASSERT_EQ(render.Wait(300), 0) << integrator;
        EXPECT_TRUE(Identical(Pixels(farm), Pixels(local)))
            << integrator << ": the farm's image differs from render's";
    }
}

TEST_F(FarmTest, CpuAndVulkanWorkersShareAJob) {
    testing::SkipWithoutVulkan();
    if (IsSkipped() || HasFatalFailure()) return;
    ChildProcess& vulkan = StartWorker("vulkan");
    ChildProcess& cpu = StartWorker("cpu");
    // Both registered before the job, so both lease from its first epoch.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (client_->ListWorkers().value_or(v1::ListWorkersResponse{}).workers_size() < 2 &&
           std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    // The Vulkan worker's batches follow nearly the CPU's paths (the same streams): the
    // image must be a draw of the CPU-only estimator, by the checks of image_agreement.cpp,
    // against CPU renders of photon streams 1 and 2 (the job's is 0: a reference of stream 0
    // would be nearly the same image, not an independent draw, and fails the spread check).
    // ppm, then sppm, whose Vulkan worker traces each epoch's hit points on its CPU.
    const auto image = [](std::vector<Rgb> pixels) {
        Image result(48, 48);
        result.pixels = std::move(pixels);
        return result;
    };
    uint64_t vulkan_batches = 0;
    for (const std::vector<std::string>& flags :
         {std::vector<std::string>{}, {"--integrator", "sppm"}}) {
        SCOPED_TRACE(flags.empty() ? "ppm" : "sppm");
        ASSERT_EQ(SubmitAndWatch(TempPath("mixed.exr"), kEpochs, flags), 0);
        const absl::StatusOr<v1::ListWorkersResponse> workers = client_->ListWorkers();
        ASSERT_TRUE(workers.ok()) << workers.status();
        ASSERT_EQ(workers->workers_size(), 2);
        for (const v1::WorkerStatus& worker : workers->workers()) {
            EXPECT_GT(worker.batches_done(), 0u) << worker.backend() << " worker ran no batch";
            if (!worker.backend().starts_with("vulkan: ")) continue;
            EXPECT_GT(worker.batches_done(), vulkan_batches)
                << "the Vulkan worker ran none of this job's batches";
            vulkan_batches = worker.batches_done();
        }
        EXPECT_GT(vulkan_batches, 0u) << "a Vulkan worker registers with its device's name";
        testing::ExpectSameEstimator(image(Pixels(TempPath("mixed.exr"))),
                                     image(Reference(kEpochs, 1, flags)),
                                     image(Reference(kEpochs, 2, flags)));
    }
    // The Vulkan worker exits 1 should the validation layer have reported an error.
    for (ChildProcess* worker : {&vulkan, &cpu}) {
        worker->Signal(SIGTERM);
        EXPECT_EQ(worker->Wait(30), 0);
    }
}

TEST_F(FarmTest, WorkerKilledMidJobChangesNothing) {
    ChildProcess& doomed = StartWorker();
    StartWorker();
    const v1::JobStatus job = Submit(kLongEpochs);
    const v1::JobStatus at =
        WatchUntil(job.job_id(), [&](const v1::JobStatus& status) { return status.epochs() >= 2; });
    ASSERT_EQ(at.state(), v1::JOB_STATE_RUNNING) << "the job must still run when the worker dies";
    doomed.Signal(SIGKILL);  // its leases die with it
    ASSERT_EQ(WatchUntil(job.job_id()).state(), v1::JOB_STATE_DONE);
    const absl::StatusOr<v1::GetResultResponse> result = client_->GetResult(job.job_id());
    ASSERT_TRUE(result.ok()) << result.status();
    const absl::StatusOr<Image> image = FromProto(result->image());
    ASSERT_TRUE(image.ok());
    EXPECT_TRUE(Identical(image->pixels, Reference(kLongEpochs)));
}

TEST_F(FarmTest, LateWorkerGetsWorkAndTwoJobsBothFinish) {
    StartWorker();
    const v1::JobStatus first = Submit(kLongEpochs);
    const v1::JobStatus second = Submit(kLongEpochs);
    ASSERT_EQ(
        WatchUntil(first.job_id(), [](const v1::JobStatus& status) { return status.epochs() >= 1; })
            .state(),
        v1::JOB_STATE_RUNNING);
    StartWorker();
    EXPECT_EQ(WatchUntil(first.job_id()).state(), v1::JOB_STATE_DONE);
    EXPECT_EQ(WatchUntil(second.job_id()).state(), v1::JOB_STATE_DONE);
    const absl::StatusOr<v1::ListWorkersResponse> workers = client_->ListWorkers();
    ASSERT_TRUE(workers.ok());
    ASSERT_EQ(workers->workers_size(), 2);
    for (const v1::WorkerStatus& worker : workers->workers())
        EXPECT_GT(worker.batches_done(), 0u) << worker.worker_id() << " got no work";
}

TEST_F(FarmTest, TargetErrorEndsTheJobAndSnapshotsCarryTheEstimate) {
    StartWorker();
    constexpr int kCapEpochs = 200;
    const v1::JobStatus job = Submit(kCapEpochs, 0, 0.03);
    bool unknown_at_first = false, estimated = false;
    const v1::JobStatus last = WatchUntil(job.job_id(), [&](const v1::JobStatus& status) {
        if (status.epochs() < 2 && !status.has_estimated_error()) unknown_at_first = true;
        if (status.epochs() >= 2 && status.has_estimated_error()) estimated = true;
        return false;
    });
    EXPECT_TRUE(unknown_at_first) << "no estimate can exist before two epochs";
    EXPECT_TRUE(estimated) << "snapshots from the second epoch on carry the estimated error";
    ASSERT_EQ(last.state(), v1::JOB_STATE_DONE);
    ASSERT_TRUE(last.has_estimated_error());
    EXPECT_LE(last.estimated_error(), 0.03);
    EXPECT_LT(last.photons(), uint64_t(kCapEpochs) * 8 * 8192)
        << "the target, not the photon cap, ended the job";
}

TEST_F(FarmTest, JobWithAReferenceLogsItsErrorAndWritesTheReport) {
    StartWorker();
    // The reference: the same hit points (seed), independent photons (another stream), 4x longer.
    const std::string reference = TempPath("reference.exr");
    ChildProcess render(
        Concat({kBin + "/client/photonfarm", "render", kScene, "--threads", "2", "--out", reference,
                "--photons", std::to_string(4 * kEpochs * 8 * 8192), "--photon-stream", "1",
                "--log-level", "warn"},
               kJobFlags));
    ASSERT_EQ(render.Wait(300), 0);
    const std::string out = TempPath("measured.exr"), report = TempPath("report");
    ChildProcess submit(
        Concat({kBin + "/client/photonfarm", "submit", kScene, "--server", address_, "--watch",
                "--interval", "0", "--out", out, "--photons", std::to_string(kEpochs * 8 * 8192),
                "--reference", reference, "--report", report, "--log-level", "warn"},
               Concat(kJobFlags, Credentials().ClientFlags())));
    ASSERT_EQ(submit.Wait(300), 0);

    // One CSV row per epoch; the last one's measurement is what `compare` finds between the
    // final image and the reference.
    absl::StatusOr<JobConvergence> log;
    const absl::StatusOr<v1::ListJobsResponse> jobs = client_->ListJobs();
    ASSERT_TRUE(jobs.ok() && jobs->jobs_size() == 1);
    log = client_->Convergence(jobs->jobs(0).job_id());
    ASSERT_TRUE(log.ok()) << log.status();
    ASSERT_EQ(log->points.size(), static_cast<size_t>(kEpochs));
    for (const ConvergencePoint& point : log->points) {
        ASSERT_TRUE(point.measured.has_value()) << "epoch " << point.epochs;
        EXPECT_EQ(point.measured->nonfinite_pixels, 0u);
        EXPECT_EQ(point.estimated.has_value(), point.epochs >= 2);
    }
    const absl::StatusOr<ImageDifference> final = CompareImages(*ReadExr(out), *ReadExr(reference));
    ASSERT_TRUE(final.ok());
    EXPECT_DOUBLE_EQ(log->points.back().measured->rmse, final->rmse);
    EXPECT_DOUBLE_EQ(log->points.back().measured->rel_mse, final->rel_mse);
    EXPECT_LT(log->points.back().measured->rmse, log->points.front().measured->rmse)
        << "the error must fall";
    for (const char* file :
         {"convergence.csv", "convergence.gp", "convergence.png", "convergence.svg"})
        EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(report) / file)) << file;

    // A reference of another size is refused before any work, naming it.
    v1::SubmitJobRequest request;
    *request.mutable_scene() = ToProto(*PackSceneBundle(kScene));
    request.mutable_settings()->set_width(32);
    request.mutable_settings()->set_photon_budget(8192);
    *request.mutable_reference() = ToProto(*ReadExr(reference));
    const absl::Status status = client_->Submit(request).status();
    EXPECT_TRUE(absl::IsInvalidArgument(status)) << status;
    EXPECT_NE(status.message().find("reference: the image is 48x48 but the job renders 32x32"),
              std::string::npos)
        << status;
}

TEST_F(FarmTest, CancelledJobStopsItsLeasesAndKeepsItsImage) {
    StartWorker();
    const v1::JobStatus job = Submit(1000);
    WatchUntil(job.job_id(), [&](const v1::JobStatus& status) { return status.epochs() >= 1; });
    ChildProcess cancel(
        Concat({kBin + "/client/photonfarm", "cancel", job.job_id(), "--server", address_},
               Credentials().ClientFlags()));
    ASSERT_EQ(cancel.Wait(60), 0);
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
    std::unique_ptr<v1::Work::Stub> stub_;
    std::string id_;
};

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
// unfinished job resumes, the workers find it again on their own, and the images come out
// bit-identical to uninterrupted renders.
TEST_F(FarmTest, CoordinatorKilledAtRandomMomentsResumesEveryJobBitIdentical) {
    const std::string port = address_.substr(address_.rfind(':') + 1);
    const std::vector<std::string> durable = {"--checkpoint-dir", TempPath("checkpoints"),
                                              "--checkpoint-seconds", "0.05"};
    StartCoordinator("127.0.0.1:" + port, durable);  // the same port, with checkpoints
    ASSERT_FALSE(HasFatalFailure());
    StartWorker();
    StartWorker();
    const v1::JobStatus first = Submit(2 * kLongEpochs);
    const v1::JobStatus second = Submit(kLongEpochs, 0, 0, /*stream=*/2);
    const unsigned seed = std::random_device{}();
    SCOPED_TRACE(::testing::Message() << "random seed " << seed);
    std::mt19937 rng(seed);
    for (int kill = 0; kill < 3; ++kill) {
        const int epochs = std::uniform_int_distribution<int>(2, 2 * kLongEpochs / 3)(rng);
        const v1::JobStatus before = WatchUntil(first.job_id(), [&](const v1::JobStatus& status) {
            return status.epochs() >= static_cast<uint64_t>(epochs);
        });
        if (before.state() != v1::JOB_STATE_RUNNING) break;  // ran to its end first
        std::this_thread::sleep_for(
            std::chrono::milliseconds(std::uniform_int_distribution<int>(0, 60)(rng)));
        coordinator_->Signal(SIGKILL);
        ASSERT_EQ(coordinator_->Wait(30), 128 + SIGKILL);
        StartCoordinator("127.0.0.1:" + port, durable);
        ASSERT_FALSE(HasFatalFailure());
        const absl::StatusOr<v1::ListJobsResponse> jobs = client_->ListJobs();
        ASSERT_TRUE(jobs.ok()) << jobs.status();
        ASSERT_EQ(jobs->jobs_size(), 2) << "both jobs resume";
        EXPECT_EQ(jobs->jobs(0).job_id(), first.job_id());
        EXPECT_GT(jobs->jobs(0).epochs(), 0u)
            << "the work before the kill was kept (checkpoints every 0.05 s)";
    }
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
    WatchUntil(job.job_id(), [&](const v1::JobStatus& status) { return status.epochs() >= 1; });
    worker.Signal(SIGTERM);
    EXPECT_EQ(worker.Wait(60), 0);
    const absl::StatusOr<v1::ListWorkersResponse> workers = client_->ListWorkers();
    ASSERT_TRUE(workers.ok());
    EXPECT_EQ(workers->workers_size(), 0) << "the worker unregisters as it leaves";
    ASSERT_TRUE(client_->Cancel(job.job_id()).ok());
}

}  // namespace
}  // namespace pf
