// Camera passes traced with the coordinator's own Embree scene, each epoch's while the epoch
// before it runs.
#include "server/camera_passes.h"

#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include <mutex>
#include <optional>
#include <utility>

#include "core/pm/density_radii.h"
#include "embree/embree_tracer.h"

namespace pf {
namespace {

// Passes traced one epoch ahead: asked for epoch e's pass, returns it (traced while epoch e - 1
// ran, else now) and starts tracing e + 1's in the background, on the TBB arena that created
// it. A pass is a function of its epoch alone, so the
// image is the same; what an epoch's end costs the coordinator is then the merge, not the
// pass, while the workers wait for the next epoch's batches.
class PrefetchedPasses {
public:
    explicit PrefetchedPasses(EpochCameraPass passes)
        : passes_(std::move(passes)), arena_(tbb::task_arena::attach()) {}
    PrefetchedPasses(const PrefetchedPasses&) = delete;
    PrefetchedPasses& operator=(const PrefetchedPasses&) = delete;
    ~PrefetchedPasses() {  // a pass no epoch will take is cut short
        group_.cancel();
        arena_.execute([&] { group_.wait(); });
    }

    CameraPassResult operator()(uint64_t epoch) {
        std::lock_guard lock(mutex_);
        std::optional<CameraPassResult> result;
        if (const std::optional<uint64_t> ahead = std::exchange(ahead_, std::nullopt)) {
            const bool wanted = *ahead == epoch;
            if (!wanted) group_.cancel();  // cut it short
            arena_.execute([&] { group_.wait(); });
            // A pass that failed (say, out of memory) is traced again here, where its error
            // reaches the caller.
            if (wanted && !failed_) result = std::move(next_);
            next_ = {};
            failed_ = false;
        }
        if (!result) result = passes_(epoch);
        ahead_ = epoch + 1;
        arena_.execute([&] {
            group_.run([this, next = epoch + 1] {
                try {
                    next_ = passes_(next);
                } catch (...) {
                    failed_ = true;
                }
            });
        });
        return std::move(*result);
    }

private:
    EpochCameraPass passes_;
    tbb::task_arena arena_;
    tbb::task_group group_;
    std::mutex mutex_;
    std::optional<uint64_t> ahead_;  // the epoch whose pass group_ traces into next_
    CameraPassResult next_;
    bool failed_ = false;  // that pass threw
};

}  // namespace

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
    // rpm's slots take the radius their place and kind call for, every epoch, from pilot maps
    // kept for the job (unless one radius was asked for all).
    SlotRadii radii;
    const JobSpec& spec = payload->spec;
    if (spec.integrator == Integrator::kRpm && spec.initial_radius == 0 &&
        payload->scene.hints.initial_radius == 0) {
        auto density = std::make_shared<const DensityRadii>(
            payload->scene, payload->emitters, *tracer, film.features, /*everything=*/true,
            ReverseRadiiSettings(spec, payload->scene), /*cells=*/true);
        radii = [density](std::span<const HitPoint> hit_points, std::span<const float> footprint) {
            return density->CellRadii(hit_points, footprint, 0.0f);
        };
    }
    // The passes keep the payload, and so its scene, alive.
    auto passes = std::make_shared<PrefetchedPasses>(
        [payload, traced = TracedCameraPasses(payload->scene, payload->emitters, std::move(tracer),
                                              film, payload->spec, std::move(radii))](
            uint64_t epoch) { return traced(epoch); });
    return [passes = std::move(passes)](uint64_t epoch) { return (*passes)(epoch); };
}

}  // namespace pf
