// The camera passes the integrators that gather at hit points (ppm, sppm, rpm) trace on a
// worker each epoch, written once above the Backend interface: both backends hold one and
// call it the same way. sppm's and rpm's hit points are the epoch's StochasticCameraPass,
// traced whole (or taken from the coordinator where it runs in the process); ppm keeps its
// fixed hit points and traces, by parts as batches need them, the epoch's pass of direct light
// (CameraPassPart) and its emission pass (TraceBatchEmission).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/camera/camera_pass.h"
#include "core/geometry/tracer.h"
#include "core/job/batch.h"
#include "core/job/hit_point.h"
#include "core/job/job_spec.h"
#include "core/ppm/direct_light.h"
#include "core/scene/emitters.h"
#include "core/scene/scene.h"
#include "core/scene/scene_features.h"

namespace pf {

class EpochPasses {
public:
    // For job `spec` (an integrator that GathersAtHitPoints) over `scene`, lit by `emitters`;
    // `fixed` are ppm's hit points (the coordinator's), indexed by pixel here. All but
    // `features` (copied) must outlive this. INVALID_ARGUMENT where the film or a fixed hit point
    // is not valid.
    static absl::StatusOr<EpochPasses> Create(const JobSpec& spec, const Scene& scene,
                                              const Emitters& emitters,
                                              std::span<const HitPoint> fixed,
                                              const SceneFeatures& features);

    // sppm and rpm: hit points traced anew each epoch.
    bool Stochastic() const { return stochastic_; }
    // Room for the largest epoch's pass: its slots, one per pixel sample (and rpm's gather rays).
    size_t MaxEpochPoints() const;

    // Begins `epoch`: sppm's and rpm's hit points are traced through `tracer`, or copied from
    // `traced` where given; ppm's passes start afresh, traced by parts in CoverDirectPoints
    // and AddEmission.
    void Begin(uint64_t epoch, const Tracer& tracer, const std::vector<HitPoint>* traced);
    // sppm, rpm: the epoch's hit points, where photons gather and direct light is sampled.
    std::span<const HitPoint> HitPoints() const { return epoch_hit_points_; }
    // Where the epoch's direct-light samples take their numbers; none before the first Begin.
    const std::optional<DirectLightSequence>& Sequence() const { return sequence_; }

    // ppm: traces the slots of the epoch's pass that `specs`' direct-light slices lie in,
    // unless held already; returns whether it traced. DirectPoints are then those slots, the
    // first of them slot DirectOffset of the pass.
    bool CoverDirectPoints(const Tracer& tracer, std::span<const BatchSpec> specs);
    std::span<const HitPoint> DirectPoints() const { return direct_points_.Points(); }
    uint64_t DirectOffset() const { return direct_points_.FirstSlot(); }
    // ppm: each batch's share of the epoch's emission pass, into `results` (TraceBatchEmission).
    void AddEmission(const Tracer& tracer, std::span<BatchResult> results) const;

private:
    const JobSpec* spec_ = nullptr;
    const Scene* scene_ = nullptr;
    const Emitters* emitters_ = nullptr;
    bool stochastic_ = false;
    CameraPassSettings film_;
    std::optional<DirectLightSequence> sequence_;
    std::vector<HitPoint> epoch_hit_points_;  // sppm, rpm
    CameraPassPart direct_points_;            // ppm
    PixelHitPoints fixed_;                    // ppm
    CameraPassSettings emission_pass_;        // ppm
};

}  // namespace pf
