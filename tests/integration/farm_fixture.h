// The farm tests' fixture: a real photonfarm-coordinator and photonfarm-worker processes on
// 127.0.0.1 with ephemeral ports, jobs submitted through the client, and the helpers both
// farm test files share (farm_test.cpp: renders; farm_faults_test.cpp: faults and refusals).
#pragma once

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
#include "core/scene_io/scene_loader.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "photonfarm/v1/work.grpc.pb.h"
#include "tests/support/child_process.h"
#include "tests/support/farm_credentials.h"
#include "tests/support/fault_proxy.h"
#include "tests/support/image_agreement.h"
#include "tests/support/test_env.h"
#include "tests/support/vulkan_validation.h"
#include "wire/proto_convert.h"
#include "wire/secure_channel.h"

namespace pf::farm {

namespace v1 = photonfarm::v1;
using testing::ChildProcess;
using testing::TempPath;

inline const std::string kBin = PF_BINARY_DIR;
inline const std::string kScene = std::string(PF_SOURCE_DIR) + "/scenes/cornell-box.gltf";
// 48x48, 4 spp, epochs of 8 batches of 2^13 photons.
inline const std::vector<std::string> kJobFlags = {
    "--width", "48",     "--height", "48", "--photons-per-batch", "8192", "--batches-per-epoch",
    "8",       "--seed", "11"};
constexpr int kEpochs = 6;
// Long enough (~1 s on two cores) for something to happen while the job runs.
constexpr int kLongEpochs = 40;

// Workers heartbeat every 0.2 s on an idle machine and are declared gone after ten missed
// heartbeats: 2 s, twice that on 2 cores, where `ctest -j 2` runs two farms of several
// processes each and a heartbeat thread may wait its turn for a while. The test that kills a
// worker waits out this timeout once.
inline double HeartbeatSeconds() { return testing::ScaledSeconds(0.2); }
inline double WorkerTimeoutSeconds() { return 10 * HeartbeatSeconds(); }
// How long one job, render or client command may take before the test fails, printing the
// farm's state: far over what any here needs (seconds), and under CTest's TIMEOUT of 300 s
// for this binary, so that a stalled job fails with its status rather than being killed.
inline double DeadlineSeconds() { return std::min(testing::ScaledSeconds(90), 240.0); }

// The farm runs as it would on a network: TLS, workers with certificates, tokens.
inline const testing::FarmCredentials& Credentials() {
    return testing::TestCredentials(PF_SOURCE_DIR);
}

inline std::vector<std::string> Concat(std::vector<std::string> a,
                                       const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

// Pixels of an EXR, compared byte for byte.
inline std::vector<Rgb> Pixels(const std::string& path) {
    absl::StatusOr<Image> image = ReadExr(path);
    EXPECT_TRUE(image.ok()) << image.status();
    return image.ok() ? image->pixels : std::vector<Rgb>{};
}

inline bool Identical(const std::vector<Rgb>& a, const std::vector<Rgb>& b) {
    return !a.empty() && a.size() == b.size() &&
           std::memcmp(a.data(), b.data(), a.size() * sizeof(Rgb)) == 0;
}

// The newest checkpoint's sequence number in a job's checkpoint folder (checkpoint_store.h:
// checkpoint-SEQUENCE.pfc, written whole by a rename), 0 if none.
inline uint64_t NewestCheckpoint(const std::filesystem::path& job_dir) {
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
    void StartCoordinator(const std::string& listen, const std::vector<std::string>& flags = {},
                          double worker_timeout_seconds = WorkerTimeoutSeconds()) {
        ASSERT_FALSE(coordinator_) << "one coordinator at a time";
        coordinator_ = std::make_unique<ChildProcess>(Concat(
            Concat(
                {kBin + "/server/photonfarm-coordinator", "--listen", listen, "--heartbeat-seconds",
                 std::to_string(HeartbeatSeconds()), "--worker-timeout-seconds",
                 std::to_string(worker_timeout_seconds), "--log-level", "warn"},
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

    // A worker of the coordinator, reached at `through` where given (a FaultProxy's address).
    ChildProcess& StartWorker(const std::string& backend = "cpu", int threads = 1,
                              const std::string& through = "") {
        workers_.push_back(std::make_unique<ChildProcess>(
            Concat({kBin + "/worker/photonfarm-worker", "--coordinator",
                    through.empty() ? address_ : through, "--threads", std::to_string(threads),
                    "--backend", backend, "--log-level", "warn"},
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

}  // namespace pf::farm
