// The coordinator's Prometheus metrics, served over HTTP (prometheus-cpp's Exposer) at
// /metrics: photons, batches pending and leased (what a HorizontalPodAutoscaler scales the
// workers on), workers by backend, merge latency, refused tallies by reason, and each running
// job's estimated error. Read from the coordinator at every scrape; docs/operations.md lists
// them with how to read them.
#pragma once

#include <prometheus/collectable.h>
#include <prometheus/exposer.h>
#include <prometheus/histogram.h>
#include <prometheus/registry.h>

#include <memory>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "server/coordinator.h"

namespace pf {

class CoordinatorMetrics final : public prometheus::Collectable {
public:
    // Observes `coordinator`'s merges from now on; it must outlive this object's use.
    explicit CoordinatorMetrics(Coordinator& coordinator);
    std::vector<prometheus::MetricFamily> Collect() const override;

private:
    Coordinator& coordinator_;
    std::shared_ptr<prometheus::Registry> registry_;  // the metrics counted as events happen
    prometheus::Histogram* merge_seconds_;
};

// Serves `metrics` at http://ADDRESS/metrics ("host:port"; port 0 picks a free one).
class MetricsServer {
public:
    static absl::StatusOr<std::unique_ptr<MetricsServer>> Start(
        const std::string& address, std::shared_ptr<CoordinatorMetrics> metrics);
    int Port() const { return port_; }

private:
    std::shared_ptr<CoordinatorMetrics> metrics_;  // the exposer holds it weakly
    std::unique_ptr<prometheus::Exposer> exposer_;
    int port_ = 0;
};

}  // namespace pf
