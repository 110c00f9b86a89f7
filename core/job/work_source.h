// Where a worker gets its work and sends its results: the coordinator in this process (the
// embedded `photonfarm render`) or one across the network (photonfarm-worker). The worker
// loop (worker_loop.h) is the same for both; only this interface differs.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "absl/status/statusor.h"
#include "core/job/batch.h"
#include "core/job/gather_regions.h"
#include "core/job/hit_point.h"
#include "core/job/job_spec.h"
#include "core/scene/emitters.h"
#include "core/scene/scene.h"

namespace pf {

// What every batch of a job needs, fixed for the job. Not copyable: the emitters refer to
// the scene.
struct JobPayload {
    JobPayload(Scene scene_in, std::shared_ptr<const std::vector<HitPoint>> hit_points_in,
               const JobSpec& spec_in)
        : scene(std::move(scene_in)),
          emitters(scene),
          hit_points(std::move(hit_points_in)),
          seed(PhotonSeed(spec_in)),
          spec(spec_in) {}
    JobPayload(const JobPayload&) = delete;
    JobPayload& operator=(const JobPayload&) = delete;

    Scene scene;
    Emitters emitters;
    std::shared_ptr<const std::vector<HitPoint>>
        hit_points;  // empty for the integrators that render pixels
    uint64_t seed;   // of the photons, light and pixel samples (PhotonSeed)
    // The job's settings, its film size resolved (FilmFor): the integrator and its settings.
    JobSpec spec;
};

// Batches leased to this worker, all of one epoch of one job, with what they need.
struct WorkGrant {
    std::string job_id;
    std::shared_ptr<const JobPayload> job;
    uint64_t epoch = 0;
    std::shared_ptr<const GatherRegions> regions;  // the epoch's, one per hit point
    std::vector<BatchSpec> batches;                // empty: no work now
    // sppm: the epoch's hit points as the coordinator traced them, where it runs in this
    // process (the embedded render), so the worker need not trace the same pass again; null
    // across the network (workers trace their own: the wire carries radii only).
    std::shared_ptr<const std::vector<HitPoint>> epoch_hit_points;
};

// photonfarm's version: a coordinator accepts only workers of its own version, since every
// worker must compute the same bytes for a batch.
inline constexpr std::string_view kPhotonfarmVersion = PF_VERSION;

// How a worker describes itself when it registers.
struct WorkerRegistration {
    std::string backend;
    uint32_t threads = 0;
    std::string version;
    std::string peer;  // where it connects from, for listings (set by the coordinator)
};

enum class TallyVerdict { kAccepted, kDuplicate, kStale, kJobGone, kNotLeased };

class WorkSource {
public:
    virtual ~WorkSource() = default;
    // Leases batches covering about `chunks` chunks (batch.h; at least one batch), waiting a
    // short while for work to appear. An error means the source is unreachable or refuses
    // this worker (the loop backs off and retries).
    virtual absl::StatusOr<WorkGrant> Lease(uint32_t chunks) = 0;
    virtual absl::StatusOr<TallyVerdict> Report(const std::string& job_id, BatchResult result) = 0;
};

}  // namespace pf
