// farm_load's report (load_report.h).
#include "bench/farm_load/load_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"

namespace pf::load {
namespace {

namespace v1 = photonfarm::v1;

CounterValues Read(const Counters& counters) {
    return {counters.leases.load(),
            counters.empty_leases.load(),
            counters.reports.load(),
            counters.accepted.load(),
            counters.refused.load(),
            counters.heartbeats.load(),
            counters.registrations.load(),
            counters.rpc_errors.load(),
            counters.blob_fetches.load(),
            counters.blob_bytes.load(),
            counters.snapshots.load(),
            counters.submissions.load(),
            counters.submissions_refused.load()};
}

// p50, p99 and max of `values` in milliseconds, "p50 1.2 / p99 3.4 / max 5.6 ms (N)".
std::string Percentiles(std::vector<double> values) {
    if (values.empty()) return "none";
    std::sort(values.begin(), values.end());
    auto at = [&](double q) {
        const size_t index = static_cast<size_t>(std::ceil(q * values.size()));
        return 1e3 * values[std::clamp<size_t>(index, 1, values.size()) - 1];
    };
    return absl::StrFormat("p50 %.2f / p99 %.2f / max %.2f ms (%d)", at(0.5), at(0.99),
                           1e3 * values.back(), values.size());
}

// The intervals the shares of photons over time are given for.
constexpr double kShareSeconds = 10;

double MiB(uint64_t bytes) { return static_cast<double>(bytes) / (1 << 20); }

}  // namespace

int Fail(const absl::Status& status) {
    std::fprintf(stderr, "farm_load: error: %s\n", std::string(status.message()).c_str());
    return 1;
}

size_t AverageEntries(const std::vector<RecordedJob>& jobs) {
    size_t entries = 0, batches = 0;
    for (const RecordedJob& job : jobs)
        for (const v1::BatchResult& batch : job.batches) {
            entries += batch.tally().photons_size();
            ++batches;
        }
    return batches ? entries / batches : 0;
}

void Samples::Add(double t, const Counters& counters, pid_t coordinator, FarmClient& observer) {
    Sample sample{t, Read(counters), {}, {}};
    if (absl::StatusOr<ProcessSample> process = SampleProcess(coordinator); process.ok())
        sample.coordinator = *process;
    if (absl::StatusOr<v1::ListJobsResponse> jobs = observer.ListJobs(); jobs.ok())
        for (const v1::JobStatus& job : jobs->jobs())
            sample.jobs[job.job_id()] = {job.owner(), job.priority(),
                                         job.state() == v1::JOB_STATE_RUNNING, job.photons()};
    samples_.push_back(std::move(sample));
}

const Sample& Samples::At(double t) const {
    const Sample* found = &samples_.front();
    for (const Sample& sample : samples_)
        if (sample.t <= t) found = &sample;
    return *found;
}

std::string Samples::ProgressLine() const {
    const Sample& now = samples_.back();
    const Sample& before = samples_.size() > 1 ? samples_[samples_.size() - 2] : now;
    const double dt = std::max(now.t - before.t, 1e-9);
    size_t running = 0;
    for (const auto& [id, job] : now.jobs) running += job.running;
    return absl::StrFormat(
        "%4.0f s: %6.0f leases/s %6.0f reports/s, %zu jobs running; coordinator %.2f cores, "
        "RSS %.0f MiB, %u threads, %u fds",
        now.t, (now.counters.leases - before.counters.leases) / dt,
        (now.counters.reports - before.counters.reports) / dt, running,
        (now.coordinator.cpu_seconds - before.coordinator.cpu_seconds) / dt,
        MiB(now.coordinator.rss_bytes), now.coordinator.threads, now.coordinator.fds);
}

std::string LoadReport::Text() const {
    std::string text = absl::StrCat("\nfarm_load: ", flags_line, "\n");
    const Sample& begin = samples.At(window.first);
    const Sample& end = samples.At(window.second);
    const double dt = std::max(end.t - begin.t, 1e-9);
    auto rate = [&](uint64_t CounterValues::*field) {
        return (end.counters.*field - begin.counters.*field) / dt;
    };
    absl::StrAppendFormat(
        &text,
        "rates over %.0f-%.0f s: %.0f leases/s (%.0f more found no work), %.0f reports/s "
        "(%.0f accepted, %.1f refused), %.3g photons/s merged, %.0f heartbeats/s, %.1f "
        "snapshots/s\n",
        begin.t, end.t, rate(&CounterValues::leases) - rate(&CounterValues::empty_leases),
        rate(&CounterValues::empty_leases), rate(&CounterValues::reports),
        rate(&CounterValues::accepted), rate(&CounterValues::refused),
        rate(&CounterValues::accepted) * photons_per_batch, rate(&CounterValues::heartbeats),
        rate(&CounterValues::snapshots));
    const CounterValues& last = samples.All().back().counters;
    absl::StrAppendFormat(&text,
                          "whole run: %u registrations, %u blob fetches (%.1f MiB), %u failed "
                          "calls, %u submissions (%u refused by the per-client limit)\n",
                          last.registrations, last.blob_fetches, MiB(last.blob_bytes),
                          last.rpc_errors, last.submissions, last.submissions_refused);
    absl::StrAppend(
        &text, "lease round trip (leases that found work): ", Percentiles(latencies.lease), "\n");
    absl::StrAppend(
        &text, "report round trip (the merge included): ", Percentiles(latencies.report), "\n");
    absl::StrAppend(&text, "heartbeat round trip: ", Percentiles(latencies.heartbeat), "\n");
    if (merges.count > 0)
        absl::StrAppendFormat(&text,
                              "coordinator's merge (its histogram): %.0f merges, mean %.3f ms, "
                              "p50 <= %.2f ms, p99 <= %.2f ms\n",
                              merges.count, 1e3 * merges.sum / merges.count,
                              1e3 * merges.Quantile(0.5), 1e3 * merges.Quantile(0.99));
    // The coordinator's process: cores over the window and the busiest 5 s, memory, threads.
    double busiest = 0;
    uint32_t threads = 0, fds = 0;
    for (const Sample& sample : samples.All()) {
        const Sample& earlier = samples.At(sample.t - 5);
        if (sample.t - earlier.t >= 4.5)
            busiest = std::max(busiest,
                               (sample.coordinator.cpu_seconds - earlier.coordinator.cpu_seconds) /
                                   (sample.t - earlier.t));
        threads = std::max(threads, sample.coordinator.threads);
        fds = std::max(fds, sample.coordinator.fds);
    }
    absl::StrAppendFormat(
        &text,
        "coordinator: %.2f cores over the window (busiest 5 s: %.2f); RSS %.0f MiB at %.0f s, "
        "%.0f MiB at %.0f s, peak %.0f MiB; at most %u threads and %u fds\n",
        (end.coordinator.cpu_seconds - begin.coordinator.cpu_seconds) / dt, busiest,
        MiB(begin.coordinator.rss_bytes), begin.t, MiB(end.coordinator.rss_bytes), end.t,
        MiB(samples.All().back().coordinator.peak_rss_bytes), threads, fds);

    // Snapshot delay: from an epoch's merge (the job's convergence log, on its own clock, from
    // the anchor its submission gave) to a watcher's receipt of it.
    std::map<std::string, const JobOutcome*> by_id;
    for (const JobOutcome& outcome : outcomes) by_id[outcome.job_id] = &outcome;
    std::vector<double> delays;
    for (const SnapshotArrival& arrival : arrivals) {
        auto it = by_id.find(arrival.job_id);
        if (it == by_id.end() || it->second->interrupted || arrival.epochs == 0 ||
            arrival.epochs > it->second->epoch_seconds.size())
            continue;
        delays.push_back(arrival.at -
                         (it->second->anchor + it->second->epoch_seconds[arrival.epochs - 1]));
    }
    absl::StrAppend(&text, "snapshot delay (epoch merged to image received by a watcher): ",
                    Percentiles(delays), "\n");

    // Jobs.
    std::map<std::string, size_t> states;
    size_t identical = 0, interrupted = 0;
    std::map<int, std::pair<double, size_t>> seconds_by_priority;
    for (const JobOutcome& outcome : outcomes) {
        ++states[outcome.state];
        if (outcome.state != "done") continue;
        identical += outcome.identical;
        interrupted += outcome.interrupted;
        if (!outcome.identical)
            absl::StrAppendFormat(&text,
                                  "  job %s (slot %d): image DIFFERS from its reference (%u "
                                  "photons, the reference %u)\n",
                                  outcome.job_id, outcome.slot, outcome.photons,
                                  outcome.reference_photons);
        auto& [seconds, count] = seconds_by_priority[outcome.priority];
        seconds += outcome.ended - outcome.submitted;
        ++count;
    }
    absl::StrAppend(&text, "jobs:");
    for (const auto& [state, count] : states) absl::StrAppend(&text, " ", count, " ", state);
    absl::StrAppendFormat(&text,
                          "; %d of %d done are bit-identical to their reference (%d of them "
                          "ran across a coordinator restart)\n",
                          identical, states["done"], interrupted);
    for (const auto& [priority, sum] : seconds_by_priority)
        absl::StrAppendFormat(&text, "  priority %d: %d jobs done, %.1f s each on average\n",
                              priority, sum.second, sum.first / sum.second);

    // Shares of the photons merged in the window, by priority and by client, and the longest
    // time a running job merged nothing while others did.
    std::map<int, uint64_t> by_priority;
    std::map<int, std::map<int, uint64_t>> over_time;  // by interval of kShareSeconds
    std::map<std::string, uint64_t> by_owner;
    std::map<std::string, double> idle_since;
    double longest_idle = 0;
    size_t most_running = 0;
    const std::vector<Sample>& all = samples.All();
    for (size_t i = 1; i < all.size(); ++i) {
        std::map<std::string, size_t> running_by_owner;
        for (const auto& [id, job] : all[i].jobs)
            if (job.running) most_running = std::max(most_running, ++running_by_owner[job.owner]);
        if (all[i].t <= window.first || all[i].t > window.second) continue;
        uint64_t total = 0;
        for (const auto& [id, job] : all[i].jobs) {
            auto before = all[i - 1].jobs.find(id);
            const uint64_t gained =
                before == all[i - 1].jobs.end() ? 0 : job.photons - before->second.photons;
            by_priority[job.priority] += gained;
            over_time[static_cast<int>((all[i].t - 1) / kShareSeconds)][job.priority] += gained;
            by_owner[job.owner] += gained;
            total += gained;
            if (!job.running || gained > 0 || before == all[i - 1].jobs.end())
                idle_since.erase(id);
            else if (!idle_since.count(id))
                idle_since[id] = all[i - 1].t;
        }
        for (const auto& [id, since] : idle_since)
            if (total > 0) longest_idle = std::max(longest_idle, all[i].t - since);
    }
    uint64_t total = 0;
    for (const auto& [priority, photons] : by_priority) total += photons;
    absl::StrAppend(&text, "photons merged in the window by priority:");
    for (const auto& [priority, photons] : by_priority)
        absl::StrAppendFormat(&text, " %d: %.1f%%", priority,
                              100.0 * photons / std::max<uint64_t>(total, 1));
    absl::StrAppend(&text, "; by client:");
    for (const auto& [owner, photons] : by_owner)
        absl::StrAppendFormat(&text, " %s: %.1f%%", owner,
                              100.0 * photons / std::max<uint64_t>(total, 1));
    absl::StrAppend(&text, "\n");
    if (by_priority.size() > 1) {
        absl::StrAppendFormat(&text,
                              "shares by priority over time (%.0f-s intervals):", kShareSeconds);
        for (const auto& [interval, shares] : over_time) {
            uint64_t photons = 0;
            for (const auto& [priority, gained] : shares) photons += gained;
            absl::StrAppendFormat(&text, "\n  %3.0f s:", (interval + 1) * kShareSeconds);
            for (const auto& [priority, gained] : shares)
                absl::StrAppendFormat(&text, " %d: %4.1f%%", priority,
                                      100.0 * gained / std::max<uint64_t>(photons, 1));
        }
        absl::StrAppend(&text, "\n");
    }
    absl::StrAppendFormat(&text,
                          "longest a running job merged nothing while others did: %.0f s; "
                          "most jobs one client ran at once: %d (limit %d)\n",
                          longest_idle, most_running, max_jobs_per_client);
    absl::StrAppendFormat(&text, "coordinator stopped with exit code %d\n%s\n", coordinator_exit,
                          Passed() ? "PASS" : "FAIL");
    return text;
}

bool LoadReport::Passed() const {
    size_t done = 0;
    for (const JobOutcome& outcome : outcomes) {
        if (outcome.state == "failed") return false;
        if (outcome.state == "done" && !outcome.identical) return false;
        done += outcome.state == "done";
    }
    return done > 0 && coordinator_exit == 0;
}

}  // namespace pf::load
