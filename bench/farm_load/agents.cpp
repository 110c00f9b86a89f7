// farm_load's agents (agents.h).
#include "bench/farm_load/agents.h"

#include <grpcpp/client_context.h>

#include <cstring>
#include <deque>
#include <set>

#include "absl/strings/str_cat.h"
#include "client/farm_client.h"
#include "core/job/work_source.h"
#include "photonfarm/v1/work.grpc.pb.h"
#include "wire/proto_convert.h"
#include "wire/rpc_status.h"

namespace pf::load {
namespace {

namespace v1 = photonfarm::v1;

// Deadlines of a worker's calls: far over what they take, so that a stalled coordinator shows
// as errors rather than a hung harness.
constexpr double kCallSeconds = 30;
// How long a slot waits before trying again after a refused or failed call.
constexpr double kRetrySeconds = 0.5;
// A watch stream is opened again after this long, so that no stalled stream holds the
// harness at its end.
constexpr double kWatchSeconds = 10;
// Blobs a worker remembers having fetched (a real worker caches a few jobs' blobs).
constexpr size_t kBlobsKept = 64;

double SecondsSince(SteadyClock::time_point start) {
    return std::chrono::duration<double>(SteadyClock::now() - start).count();
}

class SimulatedWorker {
public:
    explicit SimulatedWorker(LoadContext& ctx)
        : ctx_(ctx), stub_(v1::Work::NewStub(OpenChannel(ctx.address, ctx.worker_security))) {}

    Latencies Run() {
        auto next_heartbeat = SteadyClock::now();
        while (!ctx_.stop_workers.Stopped()) {
            if (worker_id_.empty() && !Register()) continue;
            if (SteadyClock::now() >= next_heartbeat) {
                Heartbeat();
                next_heartbeat =
                    SteadyClock::now() + std::chrono::duration_cast<SteadyClock::duration>(
                                             std::chrono::duration<double>(heartbeat_seconds_));
            }
            v1::LeaseBatchesResponse lease;
            if (!Lease(lease)) continue;
            if (lease.batches().empty()) {
                ++ctx_.counters.empty_leases;
                continue;
            }
            auto job = ctx_.jobs_by_seed.find(lease.job().settings().seed());
            if (job == ctx_.jobs_by_seed.end()) {  // not one of ours: leave it to expire
                ++ctx_.counters.rpc_errors;
                continue;
            }
            for (const std::string& digest :
                 {lease.job().prepared_scene_digest(), lease.job().hit_points_digest(),
                  lease.radii_digest()})
                Fetch(digest);
            for (const v1::BatchSpec& spec : lease.batches()) {
                if (!ctx_.stop_workers.SleepFor(ctx_.batch_seconds)) break;
                Report(lease.job().job_id(), ReplayedResult(*job->second, spec));
            }
        }
        if (!worker_id_.empty()) {
            grpc::ClientContext context;
            SetDeadline(&context, kCallSeconds);
            v1::UnregisterWorkerRequest request;
            request.set_worker_id(worker_id_);
            v1::UnregisterWorkerResponse response;
            (void)stub_->UnregisterWorker(&context, request, &response);
        }
        return std::move(latencies_);
    }

private:
    // A failed call: the coordinator forgot us (register again) or is away (wait a moment).
    void Failed(const grpc::Status& status) {
        ++ctx_.counters.rpc_errors;
        if (status.error_code() == grpc::StatusCode::NOT_FOUND)
            worker_id_.clear();
        else
            ctx_.stop_workers.SleepFor(kRetrySeconds);
    }

    bool Register() {
        grpc::ClientContext context;
        SetDeadline(&context, kCallSeconds);
        v1::RegisterWorkerRequest request;
        request.set_backend("cpu");
        request.set_threads(1);
        request.set_version(std::string(kPhotonfarmVersion));
        v1::RegisterWorkerResponse response;
        const grpc::Status status = stub_->RegisterWorker(&context, request, &response);
        if (!status.ok()) {
            Failed(status);
            return false;
        }
        ++ctx_.counters.registrations;
        worker_id_ = response.worker_id();
        heartbeat_seconds_ = response.heartbeat_seconds();
        return true;
    }

    void Heartbeat() {
        grpc::ClientContext context;
        SetDeadline(&context, kCallSeconds);
        v1::HeartbeatRequest request;
        request.set_worker_id(worker_id_);
        v1::HeartbeatResponse response;
        const auto start = SteadyClock::now();
        const grpc::Status status = stub_->Heartbeat(&context, request, &response);
        if (!status.ok()) return Failed(status);
        latencies_.heartbeat.push_back(SecondsSince(start));
        ++ctx_.counters.heartbeats;
    }

    bool Lease(v1::LeaseBatchesResponse& response) {
        grpc::ClientContext context;
        SetDeadline(&context, kCallSeconds);
        v1::LeaseBatchesRequest request;
        request.set_worker_id(worker_id_);
        request.set_chunks(1);
        const auto start = SteadyClock::now();
        const grpc::Status status = stub_->LeaseBatches(&context, request, &response);
        if (!status.ok()) {
            Failed(status);
            return false;
        }
        ++ctx_.counters.leases;
        // An empty answer waited for work on purpose: only leases that found work are timed.
        if (!response.batches().empty()) latencies_.lease.push_back(SecondsSince(start));
        return true;
    }

    void Fetch(const std::string& digest) {
        if (std::find(blobs_.begin(), blobs_.end(), digest) != blobs_.end()) return;
        grpc::ClientContext context;
        SetDeadline(&context, kCallSeconds);
        v1::FetchBlobRequest request;
        request.set_digest(digest);
        std::unique_ptr<grpc::ClientReader<v1::BlobChunk>> reader =
            stub_->FetchBlob(&context, request);
        v1::BlobChunk chunk;
        uint64_t bytes = 0;
        while (reader->Read(&chunk)) bytes += chunk.data().size();
        const grpc::Status status = reader->Finish();
        if (!status.ok()) return Failed(status);
        ++ctx_.counters.blob_fetches;
        ctx_.counters.blob_bytes += bytes;
        blobs_.push_back(digest);
        if (blobs_.size() > kBlobsKept) blobs_.pop_front();
    }

    void Report(const std::string& job_id, v1::BatchResult result) {
        grpc::ClientContext context;
        SetDeadline(&context, kCallSeconds);
        v1::ReportTallyRequest request;
        request.set_worker_id(worker_id_);
        request.set_job_id(job_id);
        *request.mutable_result() = std::move(result);
        v1::ReportTallyResponse response;
        const auto start = SteadyClock::now();
        const grpc::Status status = stub_->ReportTally(&context, request, &response);
        if (!status.ok()) return Failed(status);
        latencies_.report.push_back(SecondsSince(start));
        ++ctx_.counters.reports;
        ++(response.verdict() == v1::TALLY_VERDICT_ACCEPTED ? ctx_.counters.accepted
                                                            : ctx_.counters.refused);
    }

    LoadContext& ctx_;
    std::unique_ptr<v1::Work::Stub> stub_;
    std::string worker_id_;
    double heartbeat_seconds_ = 2;
    std::deque<std::string> blobs_;  // fetched, most recent last
    Latencies latencies_;
};

bool Terminal(v1::JobState state) {
    return state == v1::JOB_STATE_DONE || state == v1::JOB_STATE_CANCELLED ||
           state == v1::JOB_STATE_FAILED;
}

// Whether two images hold the same bits.
bool Identical(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height && a.pixels.size() == b.pixels.size() &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Rgb)) == 0;
}

}  // namespace

double SinceStart(SteadyClock::time_point start) { return SecondsSince(start); }

void Stopper::Stop() {
    std::lock_guard lock(mutex_);
    stopped_ = true;
    changed_.notify_all();
}

bool Stopper::Stopped() const {
    std::lock_guard lock(mutex_);
    return stopped_;
}

bool Stopper::SleepFor(double seconds) {
    std::unique_lock lock(mutex_);
    return !changed_.wait_for(lock, std::chrono::duration<double>(seconds),
                              [&] { return stopped_; });
}

void Latencies::Merge(const Latencies& other) {
    lease.insert(lease.end(), other.lease.begin(), other.lease.end());
    report.insert(report.end(), other.report.begin(), other.report.end());
    heartbeat.insert(heartbeat.end(), other.heartbeat.begin(), other.heartbeat.end());
}

Latencies RunSimulatedWorker(LoadContext& ctx) { return SimulatedWorker(ctx).Run(); }

void SlotBoard::Publish(size_t slot, const std::string& job_id) {
    std::lock_guard lock(mutex_);
    current_[slot] = job_id;
    ++serial_[slot];
    changed_.notify_all();
}

void SlotBoard::Finish(size_t slot) {
    std::lock_guard lock(mutex_);
    serial_[slot] = UINT64_MAX;
    changed_.notify_all();
}

bool SlotBoard::Next(size_t slot, uint64_t& seen, std::string& job_id) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return serial_[slot] != seen; });
    if (serial_[slot] == UINT64_MAX) return false;
    seen = serial_[slot];
    job_id = current_[slot];
    return true;
}

bool SlotBoard::AllFinished() {
    std::lock_guard lock(mutex_);
    return std::all_of(serial_.begin(), serial_.end(),
                       [](uint64_t serial) { return serial == UINT64_MAX; });
}

std::vector<JobOutcome> RunJobSlot(LoadContext& ctx, SlotBoard& board, const SlotSettings& slot,
                                   const std::atomic<uint32_t>& restarts) {
    std::vector<JobOutcome> outcomes;
    absl::StatusOr<FarmClient> client =
        FarmClient::Connect(ctx.address, ctx.client_security[slot.client], kCallSeconds);
    if (!client.ok()) {
        std::fprintf(stderr, "farm_load: slot %zu: %s\n", slot.slot,
                     std::string(client.status().message()).c_str());
        board.Finish(slot.slot);
        return outcomes;
    }
    v1::SubmitJobRequest request;
    *request.mutable_scene() = ctx.scene;
    *request.mutable_settings() = slot.job->settings;
    request.mutable_settings()->set_priority(slot.priority);
    for (uint64_t round = 0; !ctx.stop_submitting.Stopped(); ++round) {
        request.set_name(absl::StrCat("slot-", slot.slot, "-", round));
        JobOutcome outcome{.slot = slot.slot,
                           .priority = slot.priority,
                           .client = slot.client_name,
                           .submitted = SinceStart(ctx.start)};
        const uint32_t restarts_before = restarts.load();
        ++ctx.counters.submissions;
        absl::StatusOr<v1::JobStatus> submitted = client->Submit(request);
        if (!submitted.ok()) {
            if (submitted.status().code() == absl::StatusCode::kResourceExhausted)
                ++ctx.counters.submissions_refused;
            else
                ++ctx.counters.rpc_errors;
            ctx.stop_submitting.SleepFor(kRetrySeconds);
            continue;
        }
        outcome.job_id = submitted->job_id();
        outcome.anchor = SinceStart(ctx.start) - submitted->elapsed_seconds();
        board.Publish(slot.slot, outcome.job_id);
        // Follow the job to its end, through coordinator restarts.
        while (true) {
            absl::StatusOr<v1::Snapshot> last = client->Watch(
                outcome.job_id, 0, false, [](const v1::Snapshot&) { return true; }, kWatchSeconds);
            if (last.ok() && Terminal(last->status().state())) break;
            if (!last.ok() && last.status().code() == absl::StatusCode::kNotFound) {
                outcome.state = "lost";
                break;
            }
            ctx.stop_workers.SleepFor(kRetrySeconds);
            if (ctx.stop_workers.Stopped()) {
                outcome.state = "unfinished";
                break;
            }
        }
        outcome.ended = SinceStart(ctx.start);
        outcome.interrupted = restarts.load() != restarts_before;
        outcome.reference_photons = slot.job->photons;
        if (outcome.state.empty()) {
            absl::StatusOr<v1::GetResultResponse> result = client->GetResult(outcome.job_id);
            absl::StatusOr<JobConvergence> convergence = client->Convergence(outcome.job_id);
            if (!result.ok() || !convergence.ok()) {
                outcome.state = "unread";
            } else {
                outcome.state = StateName(result->status().state());
                outcome.photons = result->status().photons();
                absl::StatusOr<Image> image = FromProto(result->image());
                outcome.identical = image.ok() && Identical(*image, slot.job->reference) &&
                                    outcome.photons == slot.job->photons;
                for (const ConvergencePoint& point : convergence->points)
                    outcome.epoch_seconds.push_back(point.seconds);
            }
        }
        outcomes.push_back(std::move(outcome));
    }
    board.Finish(slot.slot);
    return outcomes;
}

std::vector<SnapshotArrival> RunWatcher(LoadContext& ctx, SlotBoard& board, size_t slot,
                                        size_t client_index) {
    std::vector<SnapshotArrival> arrivals;
    absl::StatusOr<FarmClient> client =
        FarmClient::Connect(ctx.address, ctx.client_security[client_index], kCallSeconds);
    if (!client.ok()) return arrivals;
    uint64_t seen = 0;
    std::string job_id;
    while (board.Next(slot, seen, job_id)) {
        // Watched to its end (again after a restart or a stream past kWatchSeconds).
        absl::StatusOr<v1::Snapshot> last;
        do {
            bool first = true;  // sent when the stream opens, not by a merge
            last = client->Watch(
                job_id, 0, true,
                [&](const v1::Snapshot& snapshot) {
                    ++ctx.counters.snapshots;
                    if (!first)
                        arrivals.push_back(
                            {job_id, snapshot.status().epochs(), SinceStart(ctx.start)});
                    first = false;
                    return !ctx.stop_workers.Stopped();
                },
                kWatchSeconds);
        } while (!(last.ok() && Terminal(last->status().state())) &&
                 !(!last.ok() && last.status().code() == absl::StatusCode::kNotFound) &&
                 ctx.stop_workers.SleepFor(kRetrySeconds));
    }
    return arrivals;
}

}  // namespace pf::load
