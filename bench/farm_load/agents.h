// farm_load's agents, one thread each, every one on its own gRPC channel (its own TLS
// connection) to the coordinator: simulated workers that register, heartbeat, lease one batch
// at a time, fetch the blobs a worker fetches, wait the batch's compute time and report its
// recorded tally; job slots, each a client submitting its job again and again and checking
// every final image against the reference; watchers streaming snapshots with images.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "bench/farm_load/recorded_job.h"
#include "photonfarm/v1/jobs.pb.h"
#include "wire/secure_channel.h"

namespace pf::load {

using SteadyClock = std::chrono::steady_clock;

// Seconds since the run began.
double SinceStart(SteadyClock::time_point start);

// Ends the run: sleeps that return early when it is time to stop.
class Stopper {
public:
    void Stop();
    bool Stopped() const;
    // False when stopped before `seconds` passed.
    bool SleepFor(double seconds);

private:
    mutable std::mutex mutex_;
    std::condition_variable changed_;
    bool stopped_ = false;
};

// Counted by every agent, read by the sampler each second.
struct Counters {
    std::atomic<uint64_t> leases{0}, empty_leases{0}, reports{0}, accepted{0}, refused{0},
        heartbeats{0}, registrations{0}, rpc_errors{0}, blob_fetches{0}, blob_bytes{0},
        snapshots{0}, submissions{0}, submissions_refused{0};
};

// Round-trip times in seconds, one list per agent, merged when the run ends.
struct Latencies {
    std::vector<double> lease, report, heartbeat;
    void Merge(const Latencies& other);
};

struct LoadContext {
    std::string address;
    ChannelSecurity worker_security;
    std::vector<ChannelSecurity> client_security;  // one per client
    std::map<uint64_t, const RecordedJob*> jobs_by_seed;
    photonfarm::v1::SceneBundle scene;
    double batch_seconds = 0.5;  // a simulated worker's compute time per batch
    SteadyClock::time_point start;
    Counters counters;
    Stopper stop_submitting;  // slots submit no new jobs
    Stopper stop_workers;     // everything else ends
};

// One simulated worker until ctx.stop_workers; unregisters at the end.
Latencies RunSimulatedWorker(LoadContext& ctx);

// One finished (or lost) job as its slot saw it.
struct JobOutcome {
    std::string job_id;
    size_t slot = 0;
    int priority = 0;
    std::string client;
    double submitted = 0, ended = 0;  // seconds since the run began
    double anchor =
        0;  // when the coordinator's clock for the job began, seconds since the run began
    std::string
        state;  // "done", "cancelled", "failed", "lost" (gone in a crash before its checkpoint)
    bool identical = false;  // the final image equals the reference bit for bit
    uint64_t photons = 0, reference_photons = 0;
    std::vector<double> epoch_seconds;  // when each epoch merged, on the job's clock
    bool interrupted = false;           // the coordinator restarted while it ran
};

// Where a watcher finds the job to watch next.
class SlotBoard {
public:
    explicit SlotBoard(size_t slots) : current_(slots), serial_(slots, 0) {}
    void Publish(size_t slot, const std::string& job_id);
    void Finish(size_t slot);  // no more jobs in this slot
    // The slot's job after `seen` (its serial), waiting; false once the slot is finished.
    bool Next(size_t slot, uint64_t& seen, std::string& job_id);
    bool AllFinished();

private:
    std::mutex mutex_;
    std::condition_variable changed_;
    std::vector<std::string> current_;
    std::vector<uint64_t> serial_;  // UINT64_MAX: finished
};

struct SlotSettings {
    size_t slot = 0;
    size_t client = 0;  // index into ctx.client_security
    std::string client_name;
    int priority = 0;
    const RecordedJob* job = nullptr;
};
// Submits the slot's job, follows it to its end, checks the image; again until
// ctx.stop_submitting. `restarts` counts coordinator restarts (a job running across one is
// marked interrupted).
std::vector<JobOutcome> RunJobSlot(LoadContext& ctx, SlotBoard& board, const SlotSettings& slot,
                                   const std::atomic<uint32_t>& restarts);

// A snapshot as a watcher received it.
struct SnapshotArrival {
    std::string job_id;
    uint64_t epochs = 0;
    double at = 0;  // seconds since the run began
};
// Watches every job of `slot` with images until the slot is finished.
std::vector<SnapshotArrival> RunWatcher(LoadContext& ctx, SlotBoard& board, size_t slot,
                                        size_t client);

}  // namespace pf::load
