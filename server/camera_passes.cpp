// Camera passes traced with the coordinator's own Embree scene.
#include "server/camera_passes.h"

#include "embree/embree_tracer.h"

namespace pf {

absl::StatusOr<EpochCameraPass> EpochCameraPasses(std::shared_ptr<const JobPayload> payload,
                                                  const CameraPassSettings& film) {
    absl::StatusOr<std::unique_ptr<embree::EmbreeTracer>> tracer =
        embree::EmbreeTracer::Create(payload->scene);
    if (!tracer.ok()) return tracer.status();
    return EpochCameraPasses(std::move(payload), film, std::move(*tracer));
}

EpochCameraPass EpochCameraPasses(std::shared_ptr<const JobPayload> payload,
                                  const CameraPassSettings& film,
                                  std::shared_ptr<const Tracer> tracer) {
    // The passes keep the payload, and so its scene, alive.
    EpochCameraPass passes =
        TracedCameraPasses(payload->scene, std::move(tracer), film, payload->spec);
    return [payload = std::move(payload), passes = std::move(passes)](uint64_t epoch) {
        return passes(epoch);
    };
}

}  // namespace pf
