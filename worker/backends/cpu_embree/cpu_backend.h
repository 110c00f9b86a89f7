// The CPU backend: batches' chunks run in parallel on the calling TBB arena, photons traced
// through a Tracer (Embree), gathered through a hit-point hash grid rebuilt each epoch; or,
// for the integrators that render pixels, pixels in parallel.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "core/camera/camera_pass.h"
#include "core/geometry/tracer.h"
#include "core/pm/photon_map.h"
#include "core/ppm/direct_light.h"
#include "core/ppm/epoch_passes.h"
#include "core/ppm/hash_grid.h"
#include "core/ppm/photon_pass.h"
#include "core/render/pixel_pass.h"
#include "worker/backend.h"

namespace pf::embree {

class CpuBackend final : public Backend {
public:
    // `tracer` must be built over the scene of every job given to BeginJob, and outlive this.
    explicit CpuBackend(const Tracer& tracer) : tracer_(tracer) {}

    std::string_view Name() const override { return "cpu"; }
    absl::Status BeginJob(const JobInputs& job) override;
    absl::Status BeginEpoch(uint64_t epoch, const GatherRegions& regions,
                            const std::vector<HitPoint>* traced) override;
    absl::StatusOr<std::vector<BatchResult>> RunBatches(std::span<const BatchSpec> specs) override;

private:
    const Tracer& tracer_;
    JobInputs job_;
    SceneFeatures features_;  // the job's, selecting the photon loop's variant
    HashGrid grid_;
    PhotonPassScratch scratch_;
    RadianceFunction radiance_;               // path, pm: a camera sample's radiance
    std::shared_ptr<const PhotonMaps> maps_;  // pm: the job's photon maps
    std::optional<EpochPasses> passes_;       // ppm, sppm, rpm: each epoch's camera passes
};

}  // namespace pf::embree
