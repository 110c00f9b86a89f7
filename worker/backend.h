// The one interface every photon backend implements (CPU with Embree, Vulkan compute):
// given a job's fixed inputs and an epoch's radii, run batches and return their results.
// Results depend only on (inputs, radii, seed, batch spec), never on scheduling.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/job/batch.h"
#include "core/job/gather_regions.h"
#include "core/job/hit_point.h"
#include "core/job/job_spec.h"
#include "core/scene/emitters.h"
#include "core/scene/scene.h"

namespace pf {

// A job's inputs; everything referenced must outlive the backend's use of the job.
struct JobInputs {
    const Scene* scene = nullptr;
    const Emitters* emitters = nullptr;
    std::span<const HitPoint> hit_points;
    uint64_t seed = 0;
    // The integrator, the film (its size resolved) and the photon maps' settings; null for
    // progressive photon mapping's batches alone (tests, benchmarks).
    const JobSpec* spec = nullptr;
};

class Backend {
public:
    virtual ~Backend() = default;
    virtual std::string_view Name() const = 0;
    // Makes `job` the job that following epochs and batches belong to.
    virtual absl::Status BeginJob(const JobInputs& job) = 0;
    // Begins epoch `epoch`: sets its gather regions, one per hit point (copied); none for the
    // integrators that render pixels. For stochastic progressive photon mapping the
    // backend first traces the epoch's hit points itself (StochasticCameraPass), as the
    // coordinator does, unless `traced` gives them (copied): the coordinator's own pass, where
    // it runs in this process (WorkGrant::epoch_hit_points). Null otherwise.
    virtual absl::Status BeginEpoch(uint64_t epoch, const GatherRegions& regions,
                                    const std::vector<HitPoint>* traced) = 0;
    // Runs the batches, in parallel where the backend can; results in the order of `specs`.
    // Errors are the device's (a lost GPU), never the batches'.
    virtual absl::StatusOr<std::vector<BatchResult>> RunBatches(
        std::span<const BatchSpec> specs) = 0;
};

}  // namespace pf
