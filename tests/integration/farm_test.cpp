// The farm as users run it: a real photonfarm-coordinator and photonfarm-worker processes on
// 127.0.0.1 with ephemeral ports, jobs submitted through the client. Images must come out
// bit-identical to `photonfarm render` however many workers ran them and whichever died.
// Heartbeats and timeouts are scaled to the machine (PF_TEST_TIME_SCALE, test_env.h), every
// wait on the farm has a deadline after which the test fails printing the farm's state, and
// the randomised test prints its seed (PF_TEST_SEED).
#include "tests/integration/farm_fixture.h"

namespace pf {
namespace {

using namespace farm;  // NOLINT: the fixture and its helpers

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
    // Stochastic ppm's workers trace each epoch's hit points themselves (rpm's with their
    // gather hits), classic pm's build the photon maps themselves, and the path tracer's
    // render pixels: every one must still
    // give the image `photonfarm render` gives, byte for byte.
    StartWorker();
    StartWorker();
    // Rough metal and rough glass: caustics for the caustic map, glossy paths for all.
    const std::string scene = std::string(PF_SOURCE_DIR) + "/scenes/cornell-glossy.gltf";
    for (const std::string integrator : {"sppm", "pm", "rpm", "path"}) {
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

TEST_F(FarmTest, AdaptivePhotonTracingChosenByTheCoordinatorGivesRendersImage) {
    // light-gap, lit through a slit: the coordinator's pilot chooses adaptive tracing (auto)
    // and its workers must trace it too, chain for chain, or the image would differ.
    StartWorker();
    StartWorker();
    const std::string scene = std::string(PF_SOURCE_DIR) + "/scenes/light-gap.gltf";
    const std::vector<std::string> flags =
        Concat(kJobFlags, {"--epochs", "3", "--log-level", "warn"});
    const std::string farm = TempPath("farm-adaptive.exr");
    ASSERT_EQ(RunClient(Concat({"submit", scene, "--server", address_, "--watch", "--interval", "0",
                                "--out", farm},
                               Concat(flags, Credentials().ClientFlags()))),
              0);
    const std::string local = TempPath("render-adaptive.exr");
    ASSERT_EQ(RunClient(Concat({"render", scene, "--threads", "2", "--out", local}, flags)), 0);
    const std::string uniform = TempPath("render-uniform.exr");
    ASSERT_EQ(RunClient(Concat({"render", scene, "--threads", "2", "--out", uniform,
                                "--photon-tracing", "uniform"},
                               flags)),
              0);
    EXPECT_TRUE(Identical(Pixels(farm), Pixels(local))) << "the farm's image differs from render's";
    EXPECT_FALSE(Identical(Pixels(local), Pixels(uniform))) << "auto did not trace adaptively";
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
    // ppm, then sppm and rpm, whose Vulkan worker traces each epoch's hit points (rpm's
    // gather hits with them) on its CPU.
    const auto image = [](std::vector<Rgb> pixels) {
        Image result(48, 48);
        result.pixels = std::move(pixels);
        return result;
    };
    uint64_t vulkan_batches = 0;
    for (const std::vector<std::string>& flags :
         {std::vector<std::string>{}, {"--integrator", "sppm"}, {"--integrator", "rpm"}}) {
        SCOPED_TRACE(flags.empty() ? "ppm" : flags[1]);
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

TEST_F(FarmTest, VulkanWorkersRunEveryIntegratorAsRenderDoes) {
    // Every integrator on the device: a farm of two Vulkan workers gives the image `photonfarm
    // render --backend vulkan` gives, byte for byte. path and pm (pixel_trace.comp): a Vulkan and
    // a CPU worker share a job, each running some of its batches, and since the device follows
    // the CPU's paths but for float rounding the image is the CPU render's to 1e-3 in nearly
    // every pixel (the photon integrators' mixed jobs: CpuAndVulkanWorkersShareAJob).
    testing::SkipWithoutVulkan();
    if (IsSkipped() || HasFatalFailure()) return;
    const std::string scene = std::string(PF_SOURCE_DIR) + "/scenes/cornell-glossy.gltf";
    // Small jobs: every check here is bit for bit or float rounding, which needs no statistic,
    // and lavapipe under the validation layer is slow. 24x24 pixels and batches of 2^11
    // photons, still 8 batches an epoch for two workers to share, over 3 epochs.
    const auto flags = [](const std::string& integrator) {
        const std::vector<std::string> small = {"--width", "24", "--height", "24", "--seed", "11"};
        return Concat(small, {"--photons-per-batch", "2048", "--batches-per-epoch", "8",
                              "--integrator", integrator, "--epochs", "3", "--pm-photons", "20k",
                              "--pm-caustic-photons", "20k", "--log-level", "warn"});
    };
    const auto submit = [&](const std::string& integrator, const std::string& out) {
        return RunClient(Concat(
            {"submit", scene, "--server", address_, "--watch", "--interval", "0", "--out", out},
            Concat(flags(integrator), Credentials().ClientFlags())));
    };
    const auto render = [&](const std::string& integrator, const std::string& backend) {
        const std::string out = TempPath("render-" + integrator + "-" + backend + ".exr");
        EXPECT_EQ(RunClient(Concat(
                      {"render", scene, "--threads", "2", "--backend", backend, "--out", out},
                      flags(integrator))),
                  0);
        return Pixels(out);
    };
    ChildProcess& first = StartWorker("vulkan");
    ChildProcess& second = StartWorker("vulkan");
    ASSERT_TRUE(WaitForWorkers(2));
    for (const std::string integrator : {"ppm", "sppm", "rpm", "pm", "path"}) {
        const std::string farm = TempPath("farm-vulkan-" + integrator + ".exr");
        ASSERT_EQ(submit(integrator, farm), 0) << integrator;
        EXPECT_TRUE(Identical(Pixels(farm), render(integrator, "vulkan")))
            << integrator << ": the Vulkan farm's image differs from render --backend vulkan's";
    }
    second.Signal(SIGTERM);
    EXPECT_EQ(second.Wait(DeadlineSeconds()), 0);
    ChildProcess& cpu = StartWorker("cpu");
    const auto batches = [&](const std::string& backend_prefix) {
        uint64_t done = 0;
        const absl::StatusOr<v1::ListWorkersResponse> workers = client_->ListWorkers();
        EXPECT_TRUE(workers.ok()) << workers.status();
        if (workers.ok())
            for (const v1::WorkerStatus& worker : workers->workers())
                if (worker.backend().starts_with(backend_prefix)) done += worker.batches_done();
        return done;
    };
    ASSERT_TRUE(WaitForWorkers(2));  // the stopped worker left the farm as it ended
    for (const std::string integrator : {"pm", "path"}) {
        SCOPED_TRACE(integrator);
        const uint64_t gpu_before = batches("vulkan: "), cpu_before = batches("cpu");
        const std::string mixed = TempPath("farm-mixed-" + integrator + ".exr");
        ASSERT_EQ(submit(integrator, mixed), 0);
        EXPECT_GT(batches("vulkan: "), gpu_before) << "the Vulkan worker ran none of the job";
        EXPECT_GT(batches("cpu"), cpu_before) << "the CPU worker ran none of the job";
        const std::vector<Rgb> image = Pixels(mixed), reference = render(integrator, "cpu");
        ASSERT_EQ(image.size(), reference.size());
        size_t agreeing = 0;
        for (size_t p = 0; p < image.size(); ++p)
            agreeing += MaxComponent(Abs(image[p] - reference[p])) <=
                        1e-3f * std::max(1.0f, MaxComponent(reference[p]));
        EXPECT_GE(double(agreeing), 0.97 * double(image.size()))
            << agreeing << " of " << image.size() << " pixels agree with the CPU render";
    }
    for (ChildProcess* worker : {&first, &cpu}) {
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

}  // namespace
}  // namespace pf
