// Rendering on one machine with no server: the camera pass, then epochs of photon batches run
// by a backend on a TBB arena of the requested size and merged by ProgressiveEstimate —
// the same batch and merge code the farm runs.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

#include "absl/status/statusor.h"
#include "core/film/image.h"
#include "core/ppm/batch.h"
#include "core/ppm/estimator.h"
#include "core/ppm/job_spec.h"
#include "core/ppm/progressive_estimate.h"

namespace pf {

struct RenderSettings {
    std::string scene_path;
    JobSpec job;
    int threads = 0;               // 0: all hardware threads
    const std::atomic<bool>* stop = nullptr;  // set from elsewhere (a signal) to stop after an epoch
};

struct RenderProgress {
    uint64_t epochs = 0;
    uint64_t photons = 0;
    uint64_t segments = 0;  // photon rays traced
    double seconds = 0;     // since the camera pass began
    double fraction = 0;    // of the budget, in [0, 1]
};

struct RenderOutcome {
    Image image;
    RenderProgress progress;
    uint64_t hit_points = 0;
    double initial_radius = 0;
    double camera_pass_seconds = 0;
};

// Called after every merged epoch, on the rendering thread.
using EpochCallback = std::function<void(const RenderProgress&, const ProgressiveEstimate&)>;

// Loads the scene and renders it. Errors: the scene's load errors, a scene the camera sees
// nothing of, bad settings.
absl::StatusOr<RenderOutcome> RenderLocally(const RenderSettings& settings, const EpochCallback& on_epoch = {});

}  // namespace pf
