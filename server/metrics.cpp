// Metric families built from the coordinator's state at scrape time.
#include "server/metrics.h"

#include <map>

#include "absl/strings/str_cat.h"

namespace pf {
namespace {

prometheus::MetricFamily Family(const std::string& name, const std::string& help,
                                prometheus::MetricType type) {
    return {name, help, type, {}};
}

void Add(prometheus::MetricFamily& family, double value,
         std::vector<prometheus::ClientMetric::Label> labels = {}) {
    prometheus::ClientMetric metric;
    metric.label = std::move(labels);
    if (family.type == prometheus::MetricType::Counter)
        metric.counter.value = value;
    else
        metric.gauge.value = value;
    family.metric.push_back(std::move(metric));
}

// "vulkan: NVIDIA H100 ..." -> "vulkan"; a backend without a device name stays as it is.
std::string BackendKind(const std::string& backend) { return backend.substr(0, backend.find(':')); }

const char* StateName(JobState state) {
    switch (state) {
        case JobState::kRunning:
            return "running";
        case JobState::kDone:
            return "done";
        case JobState::kCancelled:
            return "cancelled";
        case JobState::kFailed:
            return "failed";
    }
    return "unknown";
}

}  // namespace

CoordinatorMetrics::CoordinatorMetrics(Coordinator& coordinator)
    : coordinator_(coordinator), registry_(std::make_shared<prometheus::Registry>()) {
    // From 100 us to about 13 s: a merge of a few entries to a whole epoch's finish.
    merge_seconds_ =
        &prometheus::BuildHistogram()
             .Name("photonfarm_merge_seconds")
             .Help("Time an accepted tally takes to be stored and merged into its job's estimate")
             .Register(*registry_)
             .Add({}, prometheus::Histogram::BucketBoundaries{1e-4, 3e-4, 1e-3, 3e-3, 0.01, 0.03,
                                                              0.1, 0.3, 1, 3, 10});
    coordinator_.SetMergeObserver(
        [histogram = merge_seconds_](double seconds) { histogram->Observe(seconds); });
}

std::vector<prometheus::MetricFamily> CoordinatorMetrics::Collect() const {
    using prometheus::MetricType;
    std::vector<prometheus::MetricFamily> families = registry_->Collect();

    auto photons =
        Family("photonfarm_photons_total", "Photons in accepted tallies", MetricType::Counter);
    Add(photons, static_cast<double>(coordinator_.PhotonsAccepted()));
    auto rate = Family("photonfarm_photons_per_second",
                       "Photons merged per second by the running jobs, each over its run so far",
                       MetricType::Gauge);
    auto pending = Family(
        "photonfarm_batches_pending",
        "Batches of the running jobs' current epochs that wait for a worker: scale workers on this",
        MetricType::Gauge);
    auto leased =
        Family("photonfarm_batches_leased", "Batches under a live lease", MetricType::Gauge);
    auto jobs = Family("photonfarm_jobs", "Jobs held, by state", MetricType::Gauge);
    auto error =
        Family("photonfarm_job_estimated_error",
               "Each running job's relative error estimated without a reference (0.01 = 1%)",
               MetricType::Gauge);
    auto job_rate = Family("photonfarm_job_photons_per_second",
                           "Each running job's photons per second so far", MetricType::Gauge);
    double total_rate = 0, total_pending = 0, total_leased = 0;
    std::map<std::string, double> by_state = {
        {"running", 0}, {"done", 0}, {"cancelled", 0}, {"failed", 0}};
    for (const JobProgress& job : coordinator_.ListJobs()) {
        ++by_state[StateName(job.state)];
        if (job.state != JobState::kRunning) continue;
        total_rate += job.photons_per_second;
        total_pending += job.batches_pending;
        total_leased += job.batches_leased;
        Add(job_rate, job.photons_per_second, {{"job", job.job_id}});
        if (job.estimated_error) Add(error, *job.estimated_error, {{"job", job.job_id}});
    }
    Add(rate, total_rate);
    Add(pending, total_pending);
    Add(leased, total_leased);
    for (const auto& [state, count] : by_state) Add(jobs, count, {{"state", state}});

    auto workers =
        Family("photonfarm_workers", "Workers registered, by backend", MetricType::Gauge);
    auto threads = Family("photonfarm_worker_threads", "Worker threads registered, by backend",
                          MetricType::Gauge);
    std::map<std::string, std::pair<double, double>> by_backend = {{"cpu", {0, 0}},
                                                                   {"vulkan", {0, 0}}};
    for (const WorkerView& worker : coordinator_.ListWorkers()) {
        auto& [count, thread_count] = by_backend[BackendKind(worker.registration.backend)];
        ++count;
        thread_count += worker.registration.threads;
    }
    for (const auto& [backend, counts] : by_backend) {
        Add(workers, counts.first, {{"backend", backend}});
        Add(threads, counts.second, {{"backend", backend}});
    }

    auto refused = Family("photonfarm_tallies_refused_total", "Tallies refused, by reason",
                          MetricType::Counter);
    const RefusalCounts counts = coordinator_.Refusals();
    for (const auto& [reason, count] :
         {std::pair{"duplicate", counts.duplicate}, std::pair{"stale", counts.stale},
          std::pair{"job_gone", counts.job_gone},
          std::pair{"unknown_worker", counts.unknown_worker},
          std::pair{"malformed", counts.malformed}, std::pair{"not_leased", counts.not_leased}})
        Add(refused, static_cast<double>(count), {{"reason", reason}});

    for (auto* family : {&photons, &rate, &pending, &leased, &jobs, &error, &job_rate, &workers,
                         &threads, &refused})
        families.push_back(std::move(*family));
    return families;
}

absl::StatusOr<std::unique_ptr<MetricsServer>> MetricsServer::Start(
    const std::string& address, std::shared_ptr<CoordinatorMetrics> metrics) {
    auto server = std::make_unique<MetricsServer>();
    try {
        server->exposer_ = std::make_unique<prometheus::Exposer>(address, /*num_threads=*/1);
    } catch (const std::exception& error) {
        return absl::UnavailableError(
            absl::StrCat("metrics: cannot listen on ", address, ": ", error.what()));
    }
    server->metrics_ = std::move(metrics);
    server->exposer_->RegisterCollectable(server->metrics_);
    const std::vector<int> ports = server->exposer_->GetListeningPorts();
    if (ports.empty())
        return absl::UnavailableError(absl::StrCat("metrics: cannot listen on ", address));
    server->port_ = ports.front();
    return server;
}

}  // namespace pf
