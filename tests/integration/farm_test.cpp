// The farm as users run it: a real photonfarm-coordinator and photonfarm-worker processes on
// 127.0.0.1 with ephemeral ports, jobs submitted through the client. Images must come out
// bit-identical to `photonfarm render` however many workers ran them and whichever died.
// Heartbeats and timeouts are scaled to the machine (PF_TEST_TIME_SCALE, test_env.h), every
// wait on the farm has a deadline after which the test fails printing the farm's state, and
// the randomised test prints its seed (PF_TEST_SEED).
#include <grpcpp/client_context.h>
#include <grpcpp/create_channel.h>
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <random>
#include <thread>

#include "absl/strings/str_cat.h"
#include "client/farm_client.h"
#include "core/film/exr_io.h"
#include "core/film/image_metrics.h"
#include "core/job/work_source.h"
#include "core/scene/scene_bundle.h"
#include "core/scene/scene_loader.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "photonfarm/v1/work.grpc.pb.h"
#include "tests/support/child_process.h"
#include "tests/support/farm_credentials.h"
#include "tests/support/image_agreement.h"
#include "tests/support/test_env.h"
#include "tests/support/vulkan_validation.h"
#include "wire/proto_convert.h"
#include "wire/secure_channel.h"

namespace pf {
namespace {

namespace v1 = photonfarm::v1;
using testing::ChildProcess;
using testing::TempPath;

const std::string kBin = PF_BINARY_DIR;
const std::string kScene = std::string(PF_SOURCE_DIR) + "/scenes/cornell-box.gltf";
// 48x48, 4 spp, epochs of 8 batches of 2^13 photons.
const std::vector<std::string> kJobFlags = {
    "--width", "48",     "--height", "48", "--photons-per-batch", "8192", "--batches-per-epoch",
    "8",       "--seed", "11"};
constexpr int kEpochs = 6;
// Long enough (~1 s on two cores) for something to happen while the job runs.
constexpr int kLongEpochs = 40;

// Workers heartbeat every 0.2 s on an idle machine and are declared gone after ten missed
// heartbeats: 2 s, twice that on 2 cores, where `ctest -j 2` runs two farms of several
// processes each and a heartbeat thread may wait its turn for a while. The test that kills a
// worker waits out this timeout once.
double HeartbeatSeconds() { return testing::ScaledSeconds(0.2); }
double WorkerTimeoutSeconds() { return 10 * HeartbeatSeconds(); }
// How long one job, render or client command may take before the test fails, printing the
// farm's state: far over what any here needs (seconds), and under CTest's TIMEOUT of 300 s
// for this binary, so that a stalled job fails with its status rather than being killed.
double DeadlineSeconds() { return std::min(testing::ScaledSeconds(90), 240.0); }

// The farm runs as it would on a network: TLS, workers with certificates, tokens.
const testing::FarmCredentials& Credentials() { return testing::TestCredentials(PF_SOURCE_DIR); }

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

// The newest checkpoint's sequence number in a job's checkpoint folder (checkpoint_store.h:
// checkpoint-SEQUENCE.pfc, written whole by a rename), 0 if none.
uint64_t NewestCheckpoint(const std::filesystem::path& job_dir) {
    uint64_t newest = 0;
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(job_dir, error)) {
        const std::string name = entry.path().filename().string();
        if (name.starts_with("checkpoint-") && name.ends_with(".pfc"))
            newest = std::max<uint64_t>(newest, std::stoull(name.substr(11, name.size() - 15)));
    }
    return newest;
}

class FarmTest : public ::testing::Test {
protected:
    void SetUp() override { StartCoordinator("127.0.0.1:0"); }

    // Starts the coordinator on `listen` with the fixture's flags and connects the client.
    void StartCoordinator(const std::string& listen, const std::vector<std::string>& flags = {}) {
        ASSERT_FALSE(coordinator_) << "one coordinator at a time";
        coordinator_ = std::make_unique<ChildProcess>(Concat(
            Concat(
                {kBin + "/server/photonfarm-coordinator", "--listen", listen, "--heartbeat-seconds",
                 std::to_string(HeartbeatSeconds()), "--worker-timeout-seconds",
                 std::to_string(WorkerTimeoutSeconds()), "--log-level", "warn"},
                Credentials().CoordinatorFlags()),
            flags));
        const std::optional<std::string> line = coordinator_->ReadLine(DeadlineSeconds());
        ASSERT_TRUE(line && line->starts_with("listening on ")) << "the coordinator did not start";
        address_ = line->substr(std::strlen("listening on "));
        absl::StatusOr<FarmClient> client = FarmClient::Connect(address_, Credentials().Client());
        ASSERT_TRUE(client.ok()) << client.status();
        client_ = std::make_unique<FarmClient>(std::move(*client));
    }

    // Stops the coordinator as an operator would (SIGTERM), which must exit 0.
    void StopCoordinator() {
        if (!coordinator_) return;
        coordinator_->Signal(SIGTERM);
        EXPECT_EQ(coordinator_->Wait(DeadlineSeconds()), 0)
            << "the coordinator must stop cleanly on SIGTERM";
        coordinator_.reset();
        client_.reset();
    }

    void TearDown() override {
        workers_.clear();  // killed and reaped
        StopCoordinator();
    }

    ChildProcess& StartWorker(const std::string& backend = "cpu", int threads = 1) {
        workers_.push_back(std::make_unique<ChildProcess>(
            Concat({kBin + "/worker/photonfarm-worker", "--coordinator", address_, "--threads",
                    std::to_string(threads), "--backend", backend, "--log-level", "warn"},
                   Credentials().WorkerFlags())));
        return *workers_.back();
    }

    // The farm as the coordinator sees it, in one line, for failure messages: every job's
    // status and every worker's batches.
    std::string FarmState() {
        if (!client_) return "no coordinator";
        std::string state = "the farm: ";
        if (const absl::StatusOr<v1::ListJobsResponse> jobs = client_->ListJobs(); jobs.ok()) {
            for (const v1::JobStatus& job : jobs->jobs())
                absl::StrAppend(&state, "job ", job.job_id(), ": ", StatusLine(job), "; ");
        } else {
            absl::StrAppend(&state, "jobs: ", jobs.status().ToString(), "; ");
        }
        if (const absl::StatusOr<v1::ListWorkersResponse> workers = client_->ListWorkers();
            workers.ok()) {
            absl::StrAppend(&state, workers->workers_size(), " workers");
            for (const v1::WorkerStatus& worker : workers->workers())
                absl::StrAppend(&state, ", ", worker.worker_id(), " (", worker.backend(), ", ",
                                worker.threads(), " threads): ", worker.batches_done(),
                                " batches done, ", worker.batches_leased(), " leased, heartbeat ",
                                worker.seconds_since_heartbeat(), " s ago");
        } else {
            absl::StrAppend(&state, "workers: ", workers.status().ToString());
        }
        return state;
    }

    // Runs a photonfarm command to its end; its exit code, or -1 (the test failed, naming the
    // farm's state) if it has not ended within the deadline.
    int RunClient(const std::vector<std::string>& args) {
        ChildProcess client(Concat({kBin + "/client/photonfarm"}, args));
        const std::optional<int> code = client.Wait(DeadlineSeconds());
        if (!code)
            ADD_FAILURE() << "photonfarm " << args.at(0) << " did not end within "
                          << DeadlineSeconds() << " s; " << FarmState();
        return code.value_or(-1);
    }

    // `photonfarm submit --watch` to the end; returns its exit code.
    int SubmitAndWatch(const std::string& out, int epochs = kEpochs,
                       const std::vector<std::string>& flags = {}) {
        return RunClient(
            Concat({"submit", kScene, "--server", address_, "--watch", "--interval", "0", "--out",
                    out, "--photons", std::to_string(epochs * 8 * 8192), "--log-level", "warn"},
                   Concat(Concat(kJobFlags, flags), Credentials().ClientFlags())));
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

    // Watches the job until `predicate` holds for a snapshot, or to its end without one. A job
    // that does neither within the deadline fails the test with the farm's state, and gives
    // a status whose state is JOB_STATE_UNSPECIFIED (which no caller expects).
    v1::JobStatus WatchUntil(const std::string& job_id,
                             const std::function<bool(const v1::JobStatus&)>& predicate = {},
                             double deadline_seconds = DeadlineSeconds()) {
        absl::StatusOr<v1::Snapshot> last = client_->Watch(
            job_id, 0, false,
            [&](const v1::Snapshot& snapshot) {
                return !(predicate && predicate(snapshot.status()));
            },
            deadline_seconds);
        if (!last.ok()) {
            ADD_FAILURE() << last.status() << "; " << FarmState();
            return v1::JobStatus{};
        }
        return last->status();
    }

    // Waits until `count` workers are registered, polling the coordinator (it has no call that
    // waits for workers); false, having failed the test, if they are not within the deadline.
    bool WaitForWorkers(int count) {
        const auto deadline = std::chrono::steady_clock::now() +
                              std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                  std::chrono::duration<double>(DeadlineSeconds()));
        while (client_->ListWorkers().value_or(v1::ListWorkersResponse{}).workers_size() != count) {
            if (std::chrono::steady_clock::now() > deadline) {
                ADD_FAILURE() << count << " workers did not register within " << DeadlineSeconds()
                              << " s; " << FarmState();
                return false;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        return true;
    }

    // Batches each registered worker has run, by worker id.
    std::map<std::string, uint64_t> BatchesDone() {
        const absl::StatusOr<v1::ListWorkersResponse> workers = client_->ListWorkers();
        EXPECT_TRUE(workers.ok()) << workers.status();
        std::map<std::string, uint64_t> done;
        if (workers.ok())
            for (const v1::WorkerStatus& worker : workers->workers())
                done[worker.worker_id()] = worker.batches_done();
        return done;
    }

    // `photonfarm render` of the job (another photon stream of its seed where `stream` > 0).
    std::vector<Rgb> Reference(int epochs = kEpochs, int stream = 0,
                               const std::vector<std::string>& flags = {}) {
        const std::string out = TempPath("render-" + std::to_string(++renders_) + ".exr");
        EXPECT_EQ(RunClient(Concat({"render", kScene, "--threads", "2", "--out", out, "--photons",
                                    std::to_string(uint64_t(epochs) * 8 * 8192), "--photon-stream",
                                    std::to_string(stream), "--log-level", "warn"},
                                   Concat(kJobFlags, flags))),
                  0);
        return Pixels(out);
    }

    std::unique_ptr<ChildProcess> coordinator_;
    std::vector<std::unique_ptr<ChildProcess>> workers_;
    std::string address_;
    std::unique_ptr<FarmClient> client_;
    int renders_ = 0;
};

// However many workers of whatever thread counts share a job, every batch is the one
// `photonfarm render` runs and the merge folds them in batch order: the image is render's,
// byte for byte. Every worker must have run some of each job, or the test proves less than it
// says.
TEST_F(FarmTest, OneTwoAndFiveWorkersOfMixedThreadCountsGiveRendersImage) {
    const std::vector<Rgb> reference = Reference();
    const int threads[] = {1, 2, 3, 1, 2};  // a worker leases one batch per thread
    size_t started = 0;
    for (const size_t workers : {1u, 2u, 5u}) {
        SCOPED_TRACE(::testing::Message() << workers << " workers");
        while (started < workers) StartWorker("cpu", threads[started++]);
        // All registered before the job, so that all lease from its first epoch.
        ASSERT_TRUE(WaitForWorkers(static_cast<int>(workers)));
        std::map<std::string, uint64_t> before = BatchesDone();
        const std::string out = TempPath("workers-" + std::to_string(workers) + ".exr");
        ASSERT_EQ(SubmitAndWatch(out), 0);
        const std::map<std::string, uint64_t> after = BatchesDone();
        ASSERT_EQ(after.size(), workers) << FarmState();
        for (const auto& [worker, done] : after)
            EXPECT_GT(done, before[worker])
                << worker << " ran none of the job's batches; " << FarmState();
        EXPECT_TRUE(Identical(Pixels(out), reference))
            << workers << " workers differ from photonfarm render";
    }
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
        ASSERT_EQ(RunClient(Concat({"submit", scene, "--server", address_, "--watch", "--interval",
                                    "0", "--out", farm},
                                   Concat(flags, Credentials().ClientFlags()))),
                  0)
            << integrator;
        const std::string local = TempPath("render-" + integrator + ".exr");
        ASSERT_EQ(RunClient(Concat({"render", scene, "--threads", "2", "--out", local}, flags)), 0)
            << integrator;
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
    ASSERT_TRUE(WaitForWorkers(2));
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
        EXPECT_EQ(worker->Wait(DeadlineSeconds()), 0);
    }
}

TEST_F(FarmTest, WorkerKilledMidJobChangesNothing) {
    ChildProcess& doomed = StartWorker();
    StartWorker();
    const v1::JobStatus job = Submit(kLongEpochs);
    const v1::JobStatus at =
        WatchUntil(job.job_id(), [&](const v1::JobStatus& status) { return status.epochs() >= 2; });
    ASSERT_EQ(at.state(), v1::JOB_STATE_RUNNING) << "the job must still run when the worker dies";
    doomed.Signal(SIGKILL);  // its leases go back once it misses its heartbeats
    ASSERT_EQ(WatchUntil(job.job_id()).state(), v1::JOB_STATE_DONE);
    const absl::StatusOr<v1::GetResultResponse> result = client_->GetResult(job.job_id());
    ASSERT_TRUE(result.ok()) << result.status();
    const absl::StatusOr<Image> image = FromProto(result->image());
    ASSERT_TRUE(image.ok());
    EXPECT_TRUE(Identical(image->pixels, Reference(kLongEpochs)));
}

TEST_F(FarmTest, LateWorkerGetsWorkAndTwoJobsBothFinish) {
    ChildProcess& early = StartWorker();
    const v1::JobStatus first = Submit(kLongEpochs);
    const v1::JobStatus second = Submit(kLongEpochs);
    ASSERT_EQ(
        WatchUntil(first.job_id(), [](const v1::JobStatus& status) { return status.epochs() >= 1; })
            .state(),
        v1::JOB_STATE_RUNNING);
    const std::map<std::string, uint64_t> alone = BatchesDone();
    ASSERT_EQ(alone.size(), 1u);
    EXPECT_GT(alone.begin()->second, 0u) << "the early worker ran the first epoch";
    // The early worker is stopped while the late one joins, so the jobs cannot run out of work
    // before the late worker asks, however slowly it starts: it must get some.
    early.Signal(SIGSTOP);
    StartWorker();
    std::string late;
    const auto late_ran = [&] {
        for (const auto& [worker, done] : BatchesDone())
            if (!alone.contains(worker) && done > 0) late = worker;
        return !late.empty();
    };
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                              std::chrono::duration<double>(DeadlineSeconds()));
    while (!late_ran() && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));  // polling: no call waits
    early.Signal(SIGCONT);  // (declared gone meanwhile on a slow machine, it registers again)
    ASSERT_FALSE(late.empty()) << "the late worker ran no batch; " << FarmState();
    EXPECT_EQ(WatchUntil(first.job_id()).state(), v1::JOB_STATE_DONE);
    EXPECT_EQ(WatchUntil(second.job_id()).state(), v1::JOB_STATE_DONE);
}

// A job with a target error ends after the first epoch whose estimate is at most the target,
// before its photon budget, with render's image; and the estimate it stopped on is honest: it
// agrees, within the bound derived below, with the error measured against an independent
// render of many more photons.
TEST_F(FarmTest, TargetErrorEndsTheJobAtTheFirstEpochUnderItAndTheEstimateIsHonest) {
    StartWorker();
    constexpr int kCapEpochs = 200;
    constexpr double kTarget = 0.03;
    const v1::JobStatus job = Submit(kCapEpochs, 0, kTarget);
    const v1::JobStatus last = WatchUntil(job.job_id());
    ASSERT_EQ(last.state(), v1::JOB_STATE_DONE);
    EXPECT_LT(last.photons(), uint64_t(kCapEpochs) * 8 * 8192)
        << "the target, not the photon budget, ended the job";

    // Every epoch's estimate, from the job's convergence log: none before the second epoch,
    // above the target at every epoch but the last, at most the target there.
    const absl::StatusOr<JobConvergence> log = client_->Convergence(job.job_id());
    ASSERT_TRUE(log.ok()) << log.status();
    ASSERT_EQ(log->points.size(), last.epochs());
    ASSERT_GE(log->points.size(), 3u) << "a target this low takes several epochs";
    for (const ConvergencePoint& point : log->points) {
        SCOPED_TRACE(::testing::Message() << "epoch " << point.epochs);
        ASSERT_EQ(point.estimated.has_value(), point.epochs >= 2);
        if (!point.estimated) continue;
        if (point.epochs < last.epochs())
            EXPECT_GT(point.estimated->RelativeError(), kTarget) << "the job ran past the target";
        else
            EXPECT_LE(point.estimated->RelativeError(), kTarget);
    }
    // Snapshots carry the estimate the job stopped on.
    ASSERT_TRUE(last.has_estimated_error());
    EXPECT_EQ(last.estimated_error(), log->points.back().estimated->RelativeError());

    const absl::StatusOr<v1::GetResultResponse> result = client_->GetResult(job.job_id());
    ASSERT_TRUE(result.ok()) << result.status();
    const absl::StatusOr<Image> image = FromProto(result->image());
    ASSERT_TRUE(image.ok()) << image.status();
    EXPECT_TRUE(Identical(image->pixels, Reference(kCapEpochs, 0, {"--target-error", "0.03"})))
        << "render with the same target stops at the same epoch with the same image";

    // Honesty. R: the same hit points (seed), independent photons (stream 1), k = 16 times the
    // photons in the same layout. PPM's error with alpha = 2/3 falls as N^(-1/3) (Knaus and
    // Zwicker 2011: variance and bias both as N^(-1/3) in RMS terms; docs/convergence.md
    // measures -0.35 on this scene), so e_R <= c e_I with c = k^(-1/3) = 0.397, where e_I and
    // e_R are the relative RMS errors of the image and of R from their common limit. The
    // triangle inequality in the relative-MSE norm then bounds what is measured,
    // m = sqrt(rel_mse(I, R)), by (1 - c) e_I <= m <= (1 + c) e_I. The estimate E is required,
    // by tests/integration/convergence_test.cpp on every shipped scene, to lie within a factor
    // 2 of the measured error: e_I / 2 <= E <= 2 e_I. Together:
    //   1 / (2 (1 + c)) = 0.358 <= E / m <= 2 / (1 - c) = 3.32.
    constexpr double kReferenceFactor = 16;
    const double c = std::pow(kReferenceFactor, -1.0 / 3.0);
    Image reference(48, 48);
    reference.pixels = Reference(static_cast<int>(kReferenceFactor * last.epochs()), 1);
    const double estimated = last.estimated_error();
    const auto honest = [&](const Image& rendered) {
        const absl::StatusOr<ImageDifference> measured = CompareImages(rendered, reference);
        if (!measured.ok() || !measured->AllFinite()) return ::testing::AssertionFailure();
        const double ratio = estimated / std::sqrt(measured->rel_mse);
        if (ratio >= 1 / (2 * (1 + c)) && ratio <= 2 / (1 - c))
            return ::testing::AssertionSuccess() << "estimate / measured " << ratio;
        return ::testing::AssertionFailure()
               << "estimate " << estimated << " against measured " << std::sqrt(measured->rel_mse)
               << ": ratio " << ratio << " outside [" << 1 / (2 * (1 + c)) << ", " << 2 / (1 - c)
               << "]";
    };
    EXPECT_TRUE(honest(*image));
    // The check can fail: the same image 25% too bright is measured ~25% off, which an
    // estimate of 3% does not cover.
    Image brighter = *image;
    for (Rgb& pixel : brighter.pixels) pixel = pixel * 1.25f;
    EXPECT_FALSE(honest(brighter));
}

TEST_F(FarmTest, JobWithAReferenceLogsItsErrorAndWritesTheReport) {
    StartWorker();
    // The reference: the same hit points (seed), independent photons (another stream), 4x longer.
    const std::string reference = TempPath("reference.exr");
    ASSERT_EQ(RunClient(Concat({"render", kScene, "--threads", "2", "--out", reference, "--photons",
                                std::to_string(4 * kEpochs * 8 * 8192), "--photon-stream", "1",
                                "--log-level", "warn"},
                               kJobFlags)),
              0);
    const std::string out = TempPath("measured.exr"), report = TempPath("report");
    ASSERT_EQ(
        RunClient(Concat({"submit", kScene, "--server", address_, "--watch", "--interval", "0",
                          "--out", out, "--photons", std::to_string(kEpochs * 8 * 8192),
                          "--reference", reference, "--report", report, "--log-level", "warn"},
                         Concat(kJobFlags, Credentials().ClientFlags()))),
        0);

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
