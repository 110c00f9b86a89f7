// A coordinator exposed to hostile peers, served in this process over TLS on 127.0.0.1: wrong
// and missing tokens, one role's token on the other's service, a worker without its
// certificate, forged batches, tallies that name hit points the job lacks or carry NaN,
// oversized messages and scenes, and paths that climb out of the bundle. None may be merged
// or read; the server stays up; the job's image (past its first epoch, so that it is not the
// black one every job starts with) stays as it was, and the job then renders bit-identical to
// `photonfarm render`.
#include <grpcpp/client_context.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <thread>

#include "client/farm_client.h"
#include "core/scene_io/scene_loader.h"
#include "embedded/local_render.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "photonfarm/v1/jobs.grpc.pb.h"
#include "photonfarm/v1/work.grpc.pb.h"
#include "server/coordinator_server.h"
#include "tests/support/farm_credentials.h"
#include "wire/proto_convert.h"
#include "worker/grpc_work_source.h"
#include "worker/worker_loop.h"

namespace pf {
namespace {

namespace v1 = photonfarm::v1;

const std::string kScene = std::string(PF_SOURCE_DIR) + "/scenes/cornell-box.gltf";
constexpr int kMaxMessageBytes = 4 << 20;
constexpr uint64_t kMaxBundleBytes = 1 << 20;

const testing::FarmCredentials& Credentials() { return testing::TestCredentials(PF_SOURCE_DIR); }

ServerSecurity Security() {
    const testing::FarmCredentials& files = Credentials();
    ServerSecurity security;
    security.cert_pem = files.Read("coordinator.pem");
    security.key_pem = files.Read("coordinator.key");
    security.worker_ca_pem = files.Read("ca.pem");
    security.client_tokens = {{"alice", files.ClientToken()}};
    security.worker_tokens = {{"workers", files.WorkerToken()}};
    return security;
}

JobSpec Spec() {
    JobSpec spec;
    spec.width = 32;
    spec.height = 32;
    spec.seed = 5;
    spec.layout = {1u << 12, 4};
    spec.photon_budget = 3 * 4 * (1u << 12);
    return spec;
}

v1::SubmitJobRequest SubmitRequest() {
    v1::SubmitJobRequest request;
    *request.mutable_scene() = ToProto(*PackSceneBundle(kScene));
    *request.mutable_settings() = ToProto(Spec());
    return request;
}

class HostilePeersTest : public ::testing::Test {
protected:
    void SetUp() override {
        CoordinatorOptions options;
        options.lease_seconds = 60;
        // The in-process worker sends no heartbeats: it must not be timed out mid-test.
        options.worker_timeout_seconds = 3600;
        options.client_limits.max_bundle_bytes = kMaxBundleBytes;
        options.client_limits.max_jobs_per_client = 2;
        options.client_limits.max_watchers_per_job = 2;
        coordinator_ = std::make_unique<Coordinator>(options);
        absl::StatusOr<std::unique_ptr<CoordinatorServer>> server =
            CoordinatorServer::Start(*coordinator_, {"127.0.0.1:0", Security(), kMaxMessageBytes});
        ASSERT_TRUE(server.ok()) << server.status();
        server_ = std::move(*server);
        address_ = "127.0.0.1:" + std::to_string(server_->Port());
    }
    void TearDown() override {
        worker_loop_.reset();
        worker_source_.reset();
        if (server_) server_->Shutdown();
    }

    std::unique_ptr<v1::Jobs::Stub> Jobs(const ChannelSecurity& security) {
        return v1::Jobs::NewStub(OpenChannel(address_, security));
    }
    std::unique_ptr<v1::Work::Stub> Work(const ChannelSecurity& security) {
        return v1::Work::NewStub(OpenChannel(address_, security));
    }
    // The job's image and status as a client sees them.
    v1::GetResultResponse Result(const std::string& job_id) {
        grpc::ClientContext context;
        v1::GetResultRequest request;
        request.set_job_id(job_id);
        v1::GetResultResponse response;
        EXPECT_TRUE(Jobs(Credentials().Client())->GetResult(&context, request, &response).ok());
        return response;
    }
    std::string SubmitJob() {
        grpc::ClientContext context;
        v1::SubmitJobResponse response;
        const grpc::Status status =
            Jobs(Credentials().Client())->SubmitJob(&context, SubmitRequest(), &response);
        EXPECT_TRUE(status.ok()) << status.error_message();
        return response.status().job_id();
    }
    // A real worker, in this process over TLS, stepped by the test.
    WorkerLoop& Worker() {
        if (!worker_loop_) {
            worker_source_ = std::make_unique<GrpcWorkSource>(
                OpenChannel(address_, Credentials().Worker()), address_,
                WorkerRegistration{"cpu", 1, std::string(kPhotonfarmVersion), ""}, "");
            worker_loop_ = std::make_unique<WorkerLoop>(*worker_source_, "cpu", 1);
        }
        return *worker_loop_;
    }
    // Runs the job with the real worker until `epochs` are merged (or it ends); returns the
    // image then. Step reports before it returns, so the epoch that completes is merged by then.
    v1::GetResultResponse RunUntil(const std::string& job_id, uint64_t epochs) {
        v1::GetResultResponse result = Result(job_id);
        while (result.status().state() == v1::JOB_STATE_RUNNING &&
               result.status().epochs() < epochs) {
            const absl::StatusOr<size_t> ran = Worker().Step();
            EXPECT_TRUE(ran.ok()) << ran.status();
            if (!ran.ok()) break;
            result = Result(job_id);
        }
        return result;
    }

    std::unique_ptr<Coordinator> coordinator_;
    std::unique_ptr<CoordinatorServer> server_;
    std::string address_;
    std::unique_ptr<GrpcWorkSource> worker_source_;
    std::unique_ptr<WorkerLoop> worker_loop_;
};

// Calls one RPC of each service and returns the statuses.
grpc::Status CallJobs(v1::Jobs::Stub& jobs) {
    grpc::ClientContext context;
    v1::ListJobsResponse response;
    return jobs.ListJobs(&context, {}, &response);
}
grpc::Status CallWork(v1::Work::Stub& work) {
    grpc::ClientContext context;
    v1::RegisterWorkerRequest request;
    request.set_backend("cpu");
    request.set_version(std::string(kPhotonfarmVersion));
    v1::RegisterWorkerResponse response;
    return work.RegisterWorker(&context, request, &response);
}

TEST_F(HostilePeersTest, TokensOpenOnlyTheirOwnService) {
    const testing::FarmCredentials& files = Credentials();
    ChannelSecurity none = files.Client(), wrong = files.Client(),
                    worker_as_client = files.Client();
    none.token.clear();
    wrong.token = std::string(64, 'x');
    worker_as_client.token = files.WorkerToken();
    ChannelSecurity worker_none = files.Worker(), worker_wrong = files.Worker(),
                    client_as_worker = files.Worker();
    worker_none.token.clear();
    worker_wrong.token = std::string(64, 'y');
    client_as_worker.token = files.ClientToken();
    ChannelSecurity no_certificate = files.Worker();
    no_certificate.cert_pem.clear();
    no_certificate.key_pem.clear();

    EXPECT_TRUE(CallJobs(*Jobs(files.Client())).ok());
    EXPECT_TRUE(CallWork(*Work(files.Worker())).ok());
    EXPECT_EQ(CallJobs(*Jobs(none)).error_code(), grpc::StatusCode::UNAUTHENTICATED);
    EXPECT_EQ(CallJobs(*Jobs(wrong)).error_code(), grpc::StatusCode::UNAUTHENTICATED);
    EXPECT_EQ(CallJobs(*Jobs(worker_as_client)).error_code(), grpc::StatusCode::PERMISSION_DENIED);
    EXPECT_EQ(CallWork(*Work(worker_none)).error_code(), grpc::StatusCode::UNAUTHENTICATED);
    EXPECT_EQ(CallWork(*Work(worker_wrong)).error_code(), grpc::StatusCode::UNAUTHENTICATED);
    EXPECT_EQ(CallWork(*Work(client_as_worker)).error_code(), grpc::StatusCode::PERMISSION_DENIED);
    const grpc::Status uncertified = CallWork(*Work(no_certificate));
    EXPECT_EQ(uncertified.error_code(), grpc::StatusCode::UNAUTHENTICATED);
    EXPECT_NE(uncertified.error_message().find("certificate"), std::string::npos)
        << uncertified.error_message();

    // A worker's token cannot submit; a client's cannot report.
    {
        grpc::ClientContext context;
        v1::SubmitJobResponse response;
        EXPECT_EQ(
            Jobs(worker_as_client)->SubmitJob(&context, SubmitRequest(), &response).error_code(),
            grpc::StatusCode::PERMISSION_DENIED);
    }
    {
        grpc::ClientContext context;
        v1::ReportTallyResponse response;
        EXPECT_EQ(Work(client_as_worker)->ReportTally(&context, {}, &response).error_code(),
                  grpc::StatusCode::PERMISSION_DENIED);
    }
    EXPECT_TRUE(coordinator_->ListJobs().empty()) << "nothing was submitted";
    EXPECT_EQ(coordinator_->ListWorkers().size(), 1u)
        << "only the worker with its token registered";

    // Probes need no token.
    grpc::ClientContext context;
    grpc::health::v1::HealthCheckResponse health;
    ASSERT_TRUE(grpc::health::v1::Health::NewStub(OpenChannel(address_, none))
                    ->Check(&context, {}, &health)
                    .ok());
    EXPECT_EQ(health.status(), grpc::health::v1::HealthCheckResponse::SERVING);
}

// A worker with valid credentials that sends everything a worker should not.
class HostileWorker {
public:
    explicit HostileWorker(std::unique_ptr<v1::Work::Stub> stub) : stub_(std::move(stub)) {
        grpc::ClientContext context;
        v1::RegisterWorkerRequest request;
        request.set_backend("cpu");
        request.set_version(std::string(kPhotonfarmVersion));
        v1::RegisterWorkerResponse response;
        EXPECT_TRUE(stub_->RegisterWorker(&context, request, &response).ok());
        id = response.worker_id();
    }
    v1::LeaseBatchesResponse Lease(uint32_t chunks) {
        grpc::ClientContext context;
        v1::LeaseBatchesRequest request;
        request.set_worker_id(id);
        request.set_chunks(chunks);
        v1::LeaseBatchesResponse response;
        EXPECT_TRUE(stub_->LeaseBatches(&context, request, &response).ok());
        return response;
    }
    // A plausible result for `spec`: every hit point in range gets one photon of flux 1.
    static v1::BatchResult Plausible(const v1::BatchSpec& spec) {
        v1::BatchResult result;
        *result.mutable_spec() = spec;
        for (int i = 0; i < 3; ++i) {
            result.mutable_tally()->add_hit_point_delta(i == 0 ? 0 : 1);
            result.mutable_tally()->add_photons(1);
            result.mutable_tally()->add_inner_photons(0);
            for (int c = 0; c < 3; ++c) result.mutable_tally()->add_flux(1.0f);
        }
        for (uint32_t i = spec.sample_begin(); i < spec.sample_end(); ++i)
            for (int c = 0; c < 3; ++c) result.add_samples(0.5f);
        result.set_photons_emitted(spec.photons());
        return result;
    }
    grpc::Status Report(const std::string& job_id, const v1::BatchResult& result,
                        v1::TallyVerdict* verdict, const std::string& as = "") {
        grpc::ClientContext context;
        v1::ReportTallyRequest request;
        request.set_worker_id(as.empty() ? id : as);
        request.set_job_id(job_id);
        *request.mutable_result() = result;
        v1::ReportTallyResponse response;
        const grpc::Status status = stub_->ReportTally(&context, request, &response);
        *verdict = response.verdict();
        return status;
    }
    void Leave() {
        grpc::ClientContext context;
        v1::UnregisterWorkerRequest request;
        request.set_worker_id(id);
        v1::UnregisterWorkerResponse response;
        EXPECT_TRUE(stub_->UnregisterWorker(&context, request, &response).ok());
    }

    std::string id;

private:
    std::unique_ptr<v1::Work::Stub> stub_;
};

bool SameImage(const v1::Image& a, const v1::Image& b) {
    absl::StatusOr<Image> left = FromProto(a), right = FromProto(b);
    return left.ok() && right.ok() && left->pixels.size() == right->pixels.size() &&
           std::memcmp(left->pixels.data(), right->pixels.data(),
                       left->pixels.size() * sizeof(Rgb)) == 0;
}

TEST_F(HostilePeersTest, HostileWorkerMergesNothingAndTheJobStillRendersExactly) {
    const std::string job_id = SubmitJob();
    // A real worker merges epoch 0 first: the image to guard is then a real one, which the
    // comparison below can tell from the black image the job began with.
    const v1::GetResultResponse black = Result(job_id);
    const v1::GetResultResponse before = RunUntil(job_id, 1);
    ASSERT_EQ(before.status().epochs(), 1u);
    ASSERT_FALSE(SameImage(black.image(), before.image()))
        << "the comparison must see an epoch's difference, or it proves nothing";

    // The hostile worker holds the whole of epoch 1: had any forged result below been taken,
    // the epoch would fold and the image change (or a slot be filled: see the end).
    HostileWorker hostile(Work(Credentials().Worker()));
    const v1::LeaseBatchesResponse lease = hostile.Lease(4);
    ASSERT_EQ(lease.batches_size(), 4);
    ASSERT_EQ(lease.batches(0).epoch(), 1u);
    const v1::BatchSpec held = lease.batches(0);
    const uint32_t hit_points = static_cast<uint32_t>(lease.job().hit_point_count());
    v1::TallyVerdict verdict;

    // Forged batch ids: a batch leased to another worker, one of a later epoch, one the epoch
    // lacks.
    HostileWorker accomplice(Work(Credentials().Worker()));
    ASSERT_TRUE(accomplice.Report(job_id, HostileWorker::Plausible(held), &verdict).ok());
    EXPECT_EQ(verdict, v1::TALLY_VERDICT_NOT_LEASED) << "the batch is the hostile worker's";
    accomplice.Leave();
    v1::BatchSpec later = held;
    later.set_epoch(held.epoch() + 3);
    ASSERT_TRUE(hostile.Report(job_id, HostileWorker::Plausible(later), &verdict).ok());
    EXPECT_EQ(verdict, v1::TALLY_VERDICT_STALE);
    v1::BatchSpec missing = held;
    missing.set_index(held.index() + 1000);
    EXPECT_EQ(hostile.Report(job_id, HostileWorker::Plausible(missing), &verdict).error_code(),
              grpc::StatusCode::INVALID_ARGUMENT);
    v1::BatchSpec bigger = held;
    bigger.set_photons(held.photons() * 2);
    EXPECT_EQ(hostile.Report(job_id, HostileWorker::Plausible(bigger), &verdict).error_code(),
              grpc::StatusCode::INVALID_ARGUMENT)
        << "a spec that does not match the slot's";
    // Another worker's identity.
    EXPECT_EQ(
        hostile
            .Report(job_id, HostileWorker::Plausible(held), &verdict, "worker-1-0000000000000000")
            .error_code(),
        grpc::StatusCode::NOT_FOUND);
    // For every batch of the epoch: tallies naming hit points the job lacks, with NaN, Inf or
    // negative flux or direct light, out of order.
    constexpr int kMalformedPerBatch = 8;
    for (const v1::BatchSpec& batch : lease.batches()) {
        SCOPED_TRACE(::testing::Message() << "batch " << batch.index());
        v1::BatchResult out_of_range = HostileWorker::Plausible(batch);
        out_of_range.mutable_tally()->set_hit_point_delta(2, hit_points);
        EXPECT_EQ(hostile.Report(job_id, out_of_range, &verdict).error_code(),
                  grpc::StatusCode::INVALID_ARGUMENT);
        for (float bad : {std::numeric_limits<float>::quiet_NaN(),
                          std::numeric_limits<float>::infinity(), -1.0f}) {
            v1::BatchResult poisoned = HostileWorker::Plausible(batch);
            poisoned.mutable_tally()->set_flux(4, bad);
            EXPECT_EQ(hostile.Report(job_id, poisoned, &verdict).error_code(),
                      grpc::StatusCode::INVALID_ARGUMENT)
                << bad;
            v1::BatchResult poisoned_direct = HostileWorker::Plausible(batch);
            poisoned_direct.set_samples(0, bad);
            EXPECT_EQ(hostile.Report(job_id, poisoned_direct, &verdict).error_code(),
                      grpc::StatusCode::INVALID_ARGUMENT)
                << bad;
        }
        v1::BatchResult repeated = HostileWorker::Plausible(batch);
        repeated.mutable_tally()->set_hit_point_delta(1, 0);
        EXPECT_EQ(hostile.Report(job_id, repeated, &verdict).error_code(),
                  grpc::StatusCode::INVALID_ARGUMENT);
    }
    // ppm's share of the epoch's emission pass missing, of another size, or poisoned.
    const auto refused_naming = [&](const v1::BatchResult& result, const std::string& field) {
        const grpc::Status status = hostile.Report(job_id, result, &verdict);
        EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << field;
        EXPECT_NE(status.error_message().find(field), std::string::npos) << status.error_message();
    };
    refused_naming(HostileWorker::Plausible(held), "result.emission");
    v1::BatchResult one_pixel = HostileWorker::Plausible(held);
    for (int c = 0; c < 3; ++c) one_pixel.add_emission(0.5f), one_pixel.add_coverage(0.1f);
    refused_naming(one_pixel, "result.emission");
    v1::BatchResult poisoned_emission = one_pixel;
    poisoned_emission.set_emission(1, std::numeric_limits<float>::quiet_NaN());
    refused_naming(poisoned_emission, "emission 0 is negative, NaN or Inf");
    // A message over the coordinator's limit.
    v1::BatchResult oversized = HostileWorker::Plausible(held);
    for (int i = 0; i < kMaxMessageBytes / 4; ++i) oversized.mutable_tally()->add_flux(1.0f);
    EXPECT_EQ(hostile.Report(job_id, oversized, &verdict).error_code(),
              grpc::StatusCode::RESOURCE_EXHAUSTED);

    const RefusalCounts refused = coordinator_->Refusals();
    EXPECT_EQ(refused.not_leased, 1u);
    EXPECT_EQ(refused.stale, 1u);
    EXPECT_EQ(refused.unknown_worker, 1u);
    EXPECT_EQ(refused.malformed, 5u + 4u * kMalformedPerBatch);
    const v1::GetResultResponse after = Result(job_id);
    EXPECT_EQ(after.status().epochs(), 1u);
    EXPECT_EQ(after.status().photons(), before.status().photons());
    EXPECT_TRUE(SameImage(before.image(), after.image())) << "nothing hostile may reach the image";
    hostile.Leave();  // its leases go back

    // The real worker finishes the job: every one of its results is taken (none finds its slot
    // filled by a forged one), and the image is the one `photonfarm render` makes.
    const v1::GetResultResponse done = RunUntil(job_id, UINT64_MAX);
    EXPECT_EQ(done.status().state(), v1::JOB_STATE_DONE);
    EXPECT_EQ(coordinator_->Refusals().duplicate, 0u);
    EXPECT_EQ(coordinator_->Refusals().stale, 1u);
    RenderSettings local;
    local.scene_path = kScene;
    local.job = Spec();
    local.threads = 1;
    absl::StatusOr<RenderOutcome> rendered = RenderLocally(local);
    ASSERT_TRUE(rendered.ok()) << rendered.status();
    EXPECT_TRUE(SameImage(done.image(), ToProto(rendered->image)));
}

TEST_F(HostilePeersTest, HostileClientIsRefusedAndChangesNothing) {
    const std::string job_id = SubmitJob();
    const v1::GetResultResponse black = Result(job_id);
    const v1::GetResultResponse before = RunUntil(job_id, 1);  // a real image, not the black one
    ASSERT_EQ(before.status().epochs(), 1u);
    ASSERT_FALSE(SameImage(black.image(), before.image()));
    std::unique_ptr<v1::Jobs::Stub> jobs = Jobs(Credentials().Client());
    const auto submit = [&](const v1::SubmitJobRequest& request) {
        grpc::ClientContext context;
        v1::SubmitJobResponse response;
        return jobs->SubmitJob(&context, request, &response);
    };
    const auto expect = [](const grpc::Status& status, grpc::StatusCode code,
                           const std::string& words) {
        EXPECT_EQ(status.error_code(), code) << status.error_message();
        EXPECT_NE(status.error_message().find(words), std::string::npos) << status.error_message();
    };

    v1::SubmitJobRequest escape = SubmitRequest();
    escape.mutable_scene()->mutable_files(0)->set_path("../../etc/passwd");
    expect(submit(escape), grpc::StatusCode::INVALID_ARGUMENT, "scene.files");
    v1::SubmitJobRequest absolute = SubmitRequest();
    absolute.mutable_scene()->set_main_file("/etc/passwd");
    expect(submit(absolute), grpc::StatusCode::INVALID_ARGUMENT, "scene");
    v1::SubmitJobRequest big_scene = SubmitRequest();
    big_scene.mutable_scene()->add_files()->set_path("padding.bin");
    big_scene.mutable_scene()
        ->mutable_files(big_scene.scene().files_size() - 1)
        ->set_content(std::string(kMaxBundleBytes, 'x'));
    expect(submit(big_scene), grpc::StatusCode::RESOURCE_EXHAUSTED, "--max-bundle-bytes");
    v1::SubmitJobRequest oversized = big_scene;
    oversized.mutable_scene()
        ->mutable_files(oversized.scene().files_size() - 1)
        ->set_content(std::string(kMaxMessageBytes, 'x'));
    EXPECT_EQ(submit(oversized).error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
    v1::SubmitJobRequest huge_image = SubmitRequest();
    huge_image.mutable_settings()->set_width(
        4097);  // 2^24 + 8193 pixels, over the default limit of 2^24
    huge_image.mutable_settings()->set_height(4097);
    huge_image.mutable_settings()->set_samples_per_pixel(1);
    expect(submit(huge_image), grpc::StatusCode::RESOURCE_EXHAUSTED, "--max-render-pixels");
    v1::SubmitJobRequest huge_batches = SubmitRequest();
    huge_batches.mutable_settings()->set_photons_per_batch(1u << 30);
    expect(submit(huge_batches), grpc::StatusCode::INVALID_ARGUMENT, "settings.photons_per_batch");
    v1::SubmitJobRequest nan_alpha = SubmitRequest();
    nan_alpha.mutable_settings()->set_alpha(std::nan(""));
    expect(submit(nan_alpha), grpc::StatusCode::INVALID_ARGUMENT, "settings.alpha");

    // Jobs per client: alice runs one; a second is allowed, a third is over the limit of 2.
    ASSERT_TRUE(submit(SubmitRequest()).ok());
    expect(submit(SubmitRequest()), grpc::StatusCode::RESOURCE_EXHAUSTED, "--max-jobs-per-client");

    // Watchers per job: two streams held open, a third refused.
    std::vector<std::unique_ptr<grpc::ClientContext>> contexts;
    std::vector<std::unique_ptr<grpc::ClientReader<v1::Snapshot>>> readers;
    v1::WatchJobRequest watch;
    watch.set_job_id(job_id);
    for (int i = 0; i < 3; ++i) {
        contexts.push_back(std::make_unique<grpc::ClientContext>());
        readers.push_back(jobs->WatchJob(contexts.back().get(), watch));
        v1::Snapshot snapshot;
        if (i < 2) {
            ASSERT_TRUE(readers.back()->Read(&snapshot)) << "watcher " << i;
        }
    }
    v1::Snapshot snapshot;
    EXPECT_FALSE(readers.back()->Read(&snapshot));
    expect(readers.back()->Finish(), grpc::StatusCode::RESOURCE_EXHAUSTED,
           "--max-watchers-per-job");
    for (size_t i = 0; i < 2; ++i) contexts[i]->TryCancel();
    for (size_t i = 0; i < 2; ++i) readers[i]->Finish();

    const v1::GetResultResponse after = Result(job_id);
    EXPECT_EQ(after.status().state(), v1::JOB_STATE_RUNNING);
    EXPECT_EQ(after.status().epochs(), 1u);
    EXPECT_TRUE(SameImage(before.image(), after.image()));
    EXPECT_TRUE(CallJobs(*jobs).ok()) << "the server is still up";
}

}  // namespace
}  // namespace pf
