// CPU batch execution.
#include "worker/backends/cpu_embree/cpu_backend.h"

#include "absl/strings/str_cat.h"
#include "core/ppm/photon_pass.h"
#include "core/util/check.h"

namespace pf::embree {

absl::Status CpuBackend::BeginJob(const JobInputs& job) {
    if (job.scene == nullptr || job.emitters == nullptr || !job.emitters->HasPower())
        return absl::InvalidArgumentError("job has no scene or no light");
    job_ = job;
    features_ = AnalyseFeatures(*job.scene, *job.emitters);
    grid_ = HashGrid();
    return absl::OkStatus();
}

absl::Status CpuBackend::BeginEpoch(std::span<const float> radius_sq) {
    PF_CHECK(radius_sq.size() == job_.hit_points.size());
    grid_.Build(job_.hit_points, radius_sq);
    return absl::OkStatus();
}

absl::StatusOr<std::vector<BatchResult>> CpuBackend::RunBatches(std::span<const BatchSpec> specs) {
    return RunPhotonBatches({job_.scene, job_.emitters, &tracer_, job_.hit_points, &grid_, job_.seed, features_}, specs,
                            scratch_);
}

}  // namespace pf::embree
