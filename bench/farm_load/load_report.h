// What farm_load measured, and its report: rates over the steady window, round trips, the
// coordinator's merge histogram and its process, snapshot delays, each job's outcome, the
// shares of photons by priority and client, the per-client limit.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "bench/farm_load/agents.h"
#include "bench/farm_load/coordinator_process.h"
#include "client/farm_client.h"

namespace pf::load {

// Prints "farm_load: error: ..." and returns 1.
int Fail(const absl::Status& status);
// Tally entries per recorded batch, on average.
size_t AverageEntries(const std::vector<RecordedJob>& jobs);

struct CounterValues {
    uint64_t leases = 0, empty_leases = 0, reports = 0, accepted = 0, refused = 0, heartbeats = 0,
             registrations = 0, rpc_errors = 0, blob_fetches = 0, blob_bytes = 0, snapshots = 0,
             submissions = 0, submissions_refused = 0;
};

struct JobSample {
    std::string owner;
    int priority = 0;
    bool running = false;
    uint64_t photons = 0;
};

// One second's sample.
struct Sample {
    double t = 0;  // seconds since the run began
    CounterValues counters;
    ProcessSample coordinator;
    std::map<std::string, JobSample> jobs;  // by id, from ListJobs
};

class Samples {
public:
    void Add(double t, const Counters& counters, pid_t coordinator, FarmClient& observer);
    std::string ProgressLine() const;  // the last second's rates and the coordinator's state
    const std::vector<Sample>& All() const { return samples_; }
    // The last sample at or before `t` (the first if none).
    const Sample& At(double t) const;

private:
    std::vector<Sample> samples_;
};

struct LoadReport {
    std::string flags_line;
    std::pair<double, double> window;  // seconds since the start over which rates are taken
    Latencies latencies;
    std::vector<JobOutcome> outcomes;
    std::vector<SnapshotArrival> arrivals;
    Samples samples;
    MergeHistogram merges;
    size_t max_jobs_per_client = 0;
    uint32_t photons_per_batch = 0;
    int coordinator_exit = 0;

    std::string Text() const;
    // Every finished job identical to its reference, none failed, at least one finished, and
    // the coordinator stopped cleanly.
    bool Passed() const;
};

}  // namespace pf::load
