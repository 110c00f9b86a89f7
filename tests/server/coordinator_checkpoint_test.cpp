// The coordinator's checkpoints: jobs resume bit-identical in a new coordinator, corrupt or
// truncated checkpoints fall back, fixed parts are written once and checked.
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
    const absl::StatusOr<RenderOutcome> reference = EmbeddedReference(3 * 4 * 4096);
    ASSERT_TRUE(reference.ok()) << reference.status();

    TempDir dir;
    FakeClock clock;
    std::string running, cancelled;
    std::shared_ptr<const Image> cancelled_image;
    {
        Coordinator first(Durable(&clock, dir.path));
        running = first.Submit(SmallJob(3 * 4 * 4096))->job_id;
        cancelled = first.Submit(SmallJob(3 * 4 * 4096))->job_id;
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
