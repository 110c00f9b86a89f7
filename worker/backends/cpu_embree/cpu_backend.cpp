// CPU batch execution.
#include "worker/backends/cpu_embree/cpu_backend.h"

#include <tbb/parallel_for.h>

#include "absl/strings/str_cat.h"
#include "core/ppm/photon_pass.h"
#include "core/util/check.h"

namespace pf::embree {

absl::Status CpuBackend::BeginJob(const JobInputs& job) {
    if (job.scene == nullptr || job.emitters == nullptr || !job.emitters->HasPower())
        return absl::InvalidArgumentError("job has no scene or no light");
    job_ = job;
    grid_ = HashGrid();
    return absl::OkStatus();
}

void CpuBackend::BeginEpoch(std::span<const float> radius_sq) {
    PF_CHECK(radius_sq.size() == job_.hit_points.size());
    grid_.Build(job_.hit_points, radius_sq);
}

std::vector<BatchResult> CpuBackend::RunBatches(std::span<const BatchSpec> specs) {
    const PhotonPassInputs inputs{job_.scene, job_.emitters, &tracer_, job_.hit_points, &grid_, job_.seed};
    std::vector<BatchResult> results(specs.size());
    // One batch per task: a batch's result is a pure function of its spec, so any thread
    // may run any batch.
    tbb::parallel_for(size_t{0}, specs.size(), [&](size_t i) {
        results[i] = RunPhotonBatch(inputs, specs[i], scratch_.local());
    });
    return results;
}

}  // namespace pf::embree
