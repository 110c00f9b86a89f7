// The gRPC work source.
#include "worker/grpc_work_source.h"

#include <grpcpp/client_context.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "absl/strings/str_cat.h"
#include "core/job/job_spec.h"
#include "core/util/sha256.h"
#include "wire/blob_codec.h"
#include "wire/proto_convert.h"
#include "wire/rpc_status.h"

namespace pf {
namespace {

namespace v1 = photonfarm::v1;

constexpr size_t kPayloadsKept = 4;
constexpr size_t kRadiiKept = 4;

template <typename T>
std::shared_ptr<const T> Lookup(std::list<std::pair<std::string, std::shared_ptr<const T>>>& cache,
                                const std::string& key) {
    for (auto it = cache.begin(); it != cache.end(); ++it)
        if (it->first == key) {
            cache.splice(cache.begin(), cache, it);
            return cache.front().second;
        }
    return nullptr;
}

template <typename T>
void Remember(std::list<std::pair<std::string, std::shared_ptr<const T>>>& cache,
              const std::string& key, std::shared_ptr<const T> value, size_t kept) {
    cache.emplace_front(key, std::move(value));
    if (cache.size() > kept) cache.pop_back();
}

bool IsHexDigest(const std::string& digest) {
    return digest.size() == 64 && digest.find_first_not_of("0123456789abcdef") == std::string::npos;
}

}  // namespace

GrpcWorkSource::GrpcWorkSource(std::shared_ptr<grpc::Channel> channel, std::string address,
                               WorkerRegistration registration, std::string cache_dir)
    : channel_(channel),
      stub_(v1::Work::NewStub(channel)),
      address_(absl::StrCat("coordinator at ", address)),
      registration_(std::move(registration)),
      cache_dir_(std::move(cache_dir)) {}

bool GrpcWorkSource::WaitForConnection(double seconds) {
    return channel_->WaitForConnected(
        std::chrono::system_clock::now() +
        std::chrono::duration_cast<std::chrono::system_clock::duration>(
            std::chrono::duration<double>(seconds)));
}

double GrpcWorkSource::HeartbeatSeconds() const {
    std::lock_guard lock(mutex_);
    return heartbeat_seconds_;
}

absl::StatusOr<std::string> GrpcWorkSource::WorkerId() {
    {
        std::lock_guard lock(mutex_);
        if (!worker_id_.empty()) return worker_id_;
    }
    v1::RegisterWorkerRequest request;
    request.set_backend(registration_.backend);
    request.set_threads(registration_.threads);
    request.set_version(registration_.version);
    v1::RegisterWorkerResponse response;
    grpc::ClientContext context;
    SetDeadline(&context, 30);
    if (grpc::Status status = stub_->RegisterWorker(&context, request, &response); !status.ok())
        return FromGrpcStatus(status, address_);
    spdlog::info("registered with the {} as {}", address_, response.worker_id());
    std::lock_guard lock(mutex_);
    worker_id_ = response.worker_id();
    heartbeat_seconds_ = response.heartbeat_seconds() > 0 ? response.heartbeat_seconds() : 2.0;
    return worker_id_;
}

void GrpcWorkSource::Forget(const std::string& worker_id) {
    std::lock_guard lock(mutex_);
    if (worker_id_ == worker_id) worker_id_.clear();
}

absl::Status GrpcWorkSource::Heartbeat() {
    absl::StatusOr<std::string> id = WorkerId();
    if (!id.ok()) return id.status();
    v1::HeartbeatRequest request;
    request.set_worker_id(*id);
    v1::HeartbeatResponse response;
    grpc::ClientContext context;
    SetDeadline(&context, 10);
    const grpc::Status status = stub_->Heartbeat(&context, request, &response);
    if (status.error_code() == grpc::StatusCode::NOT_FOUND)
        Forget(*id);  // forgotten: register again next time
    return FromGrpcStatus(status, address_);
}

absl::Status GrpcWorkSource::Unregister() {
    std::string id;
    {
        std::lock_guard lock(mutex_);
        id.swap(worker_id_);
    }
    if (id.empty()) return absl::OkStatus();
    v1::UnregisterWorkerRequest request;
    request.set_worker_id(id);
    v1::UnregisterWorkerResponse response;
    grpc::ClientContext context;
    SetDeadline(&context, 10);
    return FromGrpcStatus(stub_->UnregisterWorker(&context, request, &response), address_);
}

absl::StatusOr<WorkGrant> GrpcWorkSource::Lease(uint32_t chunks) {
    absl::StatusOr<std::string> id = WorkerId();
    if (!id.ok()) return id.status();
    v1::LeaseBatchesRequest request;
    request.set_worker_id(*id);
    request.set_chunks(chunks);
    v1::LeaseBatchesResponse response;
    grpc::ClientContext context;
    SetDeadline(&context, 60);
    const grpc::Status status = stub_->LeaseBatches(&context, request, &response);
    if (status.error_code() == grpc::StatusCode::NOT_FOUND) Forget(*id);
    if (!status.ok()) return FromGrpcStatus(status, address_);
    WorkGrant grant;
    if (response.batches().empty()) return grant;
    const v1::JobInputs& job = response.job();
    absl::StatusOr<JobSpec> settings = FromProto(job.settings());
    if (!settings.ok())
        return absl::InternalError(
            absl::StrCat(address_, ": a job's settings: ", settings.status().message()));
    const bool gathers = GathersAtHitPoints(settings->integrator);
    if ((job.hit_point_count() == 0) == gathers || job.hit_point_count() > kMaxHitPoints ||
        settings->width == 0 || settings->height == 0)
        return absl::InternalError(
            absl::StrCat(address_, ": a ", std::string(IntegratorName(settings->integrator)),
                         " job of ", job.hit_point_count(), " hit points and a ", settings->width,
                         "x", settings->height, " film"));
    absl::StatusOr<std::shared_ptr<const JobPayload>> payload = PayloadFor(job, *settings);
    if (!payload.ok()) return payload.status();
    absl::StatusOr<std::shared_ptr<const GatherRegions>> regions =
        RegionsFor(response.radii_digest(), job.hit_point_count());
    if (!regions.ok()) return regions.status();
    grant.job_id = job.job_id();
    grant.job = *payload;
    grant.regions = *regions;
    // What a batch's sample slice indexes: the slots of the epoch's camera pass (pixels x its
    // samples a pixel x their slots), where the photon mappers sample direct light, or the
    // pixels.
    const uint64_t items =
        uint64_t(settings->width) * uint64_t(settings->height) *
        (gathers ? uint64_t(EpochCameraSamples(*settings, response.batches(0).epoch()).per_pixel) *
                       SlotsPerCameraSample(*settings)
                 : 1);
    for (const v1::BatchSpec& spec : response.batches()) {
        grant.batches.push_back(FromProto(spec));
        if (grant.batches.back().epoch != grant.batches.front().epoch)
            return absl::InternalError(absl::StrCat(address_, ": a lease mixed epochs"));
        if (grant.batches.back().sample_end > items)
            return absl::InternalError(
                absl::StrCat(address_, ": a batch's sample slice lies outside the job's ", items,
                             gathers ? " camera samples" : " pixels"));
    }
    grant.epoch = grant.batches.front().epoch;
    return grant;
}

absl::StatusOr<TallyVerdict> GrpcWorkSource::Report(const std::string& job_id, BatchResult result) {
    absl::StatusOr<std::string> id = WorkerId();
    if (!id.ok()) return id.status();
    v1::ReportTallyRequest request;
    request.set_worker_id(*id);
    request.set_job_id(job_id);
    *request.mutable_result() = ToProto(result);
    v1::ReportTallyResponse response;
    grpc::ClientContext context;
    SetDeadline(&context, 120);
    const grpc::Status status = stub_->ReportTally(&context, request, &response);
    if (status.error_code() == grpc::StatusCode::NOT_FOUND) Forget(*id);
    if (!status.ok()) return FromGrpcStatus(status, address_);
    absl::StatusOr<TallyVerdict> verdict = TallyVerdictFromProto(response.verdict(), "verdict");
    if (!verdict.ok())
        return absl::InternalError(absl::StrCat(address_, ": ", verdict.status().message()));
    return *verdict;
}

absl::StatusOr<std::string> GrpcWorkSource::FetchBlob(const std::string& digest,
                                                      bool keep_on_disk) {
    if (!IsHexDigest(digest))
        return absl::InternalError(absl::StrCat(address_, ": malformed blob digest"));
    const std::filesystem::path cached =
        cache_dir_.empty() ? std::filesystem::path() : std::filesystem::path(cache_dir_) / digest;
    if (keep_on_disk && !cached.empty()) {
        std::ifstream in(cached, std::ios::binary);
        std::stringstream bytes;
        bytes << in.rdbuf();
        if (in && Sha256Hex(bytes.str()) == digest) return bytes.str();
    }
    v1::FetchBlobRequest request;
    request.set_digest(digest);
    grpc::ClientContext context;
    SetDeadline(&context, 600);
    std::unique_ptr<grpc::ClientReader<v1::BlobChunk>> reader = stub_->FetchBlob(&context, request);
    std::string bytes;
    v1::BlobChunk chunk;
    uint64_t total = 0;
    while (reader->Read(&chunk)) {
        if (bytes.empty() && chunk.total_bytes() != 0) {
            total = chunk.total_bytes();
            if (total > uint64_t{kMaxMessageBytes} * 4)
                return absl::InternalError(
                    absl::StrCat(address_, ": blob of ", total, " bytes is over the limit"));
            bytes.reserve(total);
        }
        bytes += chunk.data();
        if (bytes.size() > total)
            return absl::InternalError(absl::StrCat(address_, ": blob longer than announced"));
    }
    if (grpc::Status status = reader->Finish(); !status.ok())
        return FromGrpcStatus(status, address_);
    if (bytes.size() != total || Sha256Hex(bytes) != digest)
        return absl::DataLossError(
            absl::StrCat(address_, ": blob ", digest.substr(0, 12), " arrived corrupted"));
    if (keep_on_disk && !cached.empty()) {
        std::error_code error;
        std::filesystem::create_directories(cache_dir_, error);
        const std::filesystem::path partial = cached.string() + ".partial";
        std::ofstream(partial, std::ios::binary)
            .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        std::filesystem::rename(partial, cached, error);
        if (error) spdlog::warn("{}: cannot cache a blob here: {}", cache_dir_, error.message());
    }
    return bytes;
}

absl::StatusOr<std::shared_ptr<const JobPayload>> GrpcWorkSource::PayloadFor(
    const v1::JobInputs& job, const JobSpec& spec) {
    const std::string key = absl::StrCat(job.prepared_scene_digest(), "/", job.hit_points_digest(),
                                         "/", Sha256Hex(job.settings().SerializeAsString()));
    {
        std::lock_guard lock(mutex_);
        if (std::shared_ptr<const JobPayload> payload = Lookup(payloads_, key)) return payload;
    }
    const auto start = std::chrono::steady_clock::now();
    absl::StatusOr<std::string> scene_bytes = FetchBlob(job.prepared_scene_digest(), true);
    if (!scene_bytes.ok()) return scene_bytes.status();
    // The coordinator parsed the scene's files once and sends what tracing needs (a prepared
    // scene); it is hostile input all the same. Photons look textures up at a point; camera
    // samples traced here (every integrator's: ppm's epoch passes for direct light and
    // emission too) filter them over their footprint, as the coordinator's camera pass does.
    absl::StatusOr<Scene> scene = DecodeSceneBlob(*scene_bytes, /*texture_filter=*/true);
    if (!scene.ok())
        return absl::DataLossError(absl::StrCat(address_, ": ", scene.status().message()));
    absl::StatusOr<std::string> hit_point_bytes = FetchBlob(job.hit_points_digest(), true);
    if (!hit_point_bytes.ok()) return hit_point_bytes.status();
    // A stochastic job's hit points are traced here, epoch by epoch (CpuBackend::BeginEpoch).
    const uint64_t sent = TracesHitPointsEachEpoch(spec.integrator) ? 0 : job.hit_point_count();
    absl::StatusOr<std::vector<HitPoint>> hit_points = DecodeHitPoints(*hit_point_bytes, sent);
    if (!hit_points.ok()) return hit_points.status();
    for (size_t i = 0; i < hit_points->size(); ++i) {
        const uint32_t coat = (*hit_points)[i].coat;
        if (coat != kNoCoat &&
            (coat >= scene->materials.size() || !scene->materials[coat].HasCoat()))
            return absl::DataLossError(absl::StrCat(address_, ": hit point ", i, " names material ",
                                                    coat, " as its coat"));
    }
    auto payload = std::make_shared<const JobPayload>(
        std::move(*scene), std::make_shared<const std::vector<HitPoint>>(std::move(*hit_points)),
        spec);
    spdlog::info("job {}: scene ({} bytes) and {} hit points ({} bytes) fetched in {:.2f} s",
                 job.job_id(), scene_bytes->size(), job.hit_point_count(), hit_point_bytes->size(),
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    std::lock_guard lock(mutex_);
    Remember(payloads_, key, std::shared_ptr<const JobPayload>(payload), kPayloadsKept);
    return std::shared_ptr<const JobPayload>(payload);
}

absl::StatusOr<std::shared_ptr<const GatherRegions>> GrpcWorkSource::RegionsFor(
    const std::string& digest, uint64_t count) {
    {
        std::lock_guard lock(mutex_);
        if (std::shared_ptr<const GatherRegions> regions = Lookup(regions_, digest)) return regions;
    }
    absl::StatusOr<std::string> bytes = FetchBlob(digest, false);
    if (!bytes.ok()) return bytes.status();
    absl::StatusOr<GatherRegions> decoded = DecodeGatherRegions(*bytes, count);
    if (!decoded.ok()) return decoded.status();
    auto regions = std::make_shared<const GatherRegions>(std::move(*decoded));
    std::lock_guard lock(mutex_);
    Remember(regions_, digest, std::shared_ptr<const GatherRegions>(regions), kRadiiKept);
    return std::shared_ptr<const GatherRegions>(regions);
}

}  // namespace pf
