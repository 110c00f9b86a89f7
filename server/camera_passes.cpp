// Camera passes traced with the coordinator's own Embree scene.
#include "server/camera_passes.h"

#include "embree/embree_tracer.h"

namespace pf {

absl::StatusOr<EpochCameraPass> StochasticCameraPasses(std::shared_ptr<const JobPayload> payload,
                                                       const CameraPassSettings& film) {
    absl::StatusOr<std::unique_ptr<embree::EmbreeTracer>> tracer =
        embree::EmbreeTracer::Create(payload->scene);
    if (!tracer.ok()) return tracer.status();
    return EpochCameraPass([payload = std::move(payload),
                            tracer = std::shared_ptr<const Tracer>(std::move(*tracer)),
                            film](uint64_t epoch) {
        return RunCameraPass(payload->scene, *tracer, StochasticCameraPass(film, epoch));
    });
}

}  // namespace pf
