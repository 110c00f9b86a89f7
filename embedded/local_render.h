// Rendering on one machine with no server: a coordinator and a worker loop in this process,
// the same code the farm runs (server/coordinator.h, worker/worker_loop.h), with the job's
// inputs handed over in memory.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "core/estimate/convergence.h"
#include "core/film/image.h"
#include "core/job/job_spec.h"
#include "core/job/scene_settings.h"
#include "server/job.h"

namespace pf {

struct RenderSettings {
    std::string scene_path;
    std::string scene_root;  // the bundle's root where wider than the scene's folder
    JobSpec job;
    // The settings the user chose (flags): the scene file's own (a pbrt Integrator, Sampler)
    // fill the rest (ApplySceneSettings).
    GivenSettings given;
    int threads = 0;                         // 0: all hardware threads
    std::string backend = "cpu";             // the photon backend (worker/backend_factory.h)
    std::shared_ptr<const Image> reference;  // every epoch is measured against it, when set
    const std::atomic<bool>* stop =
        nullptr;  // set from elsewhere (a signal) to stop after an epoch
    // Serve the browser dashboard here ("host:port") while rendering: plain HTTP, no tokens,
    // so the caller keeps it on a loopback address unless the user said otherwise.
    std::string web_listen;
};

struct RenderProgress {
    uint64_t epochs = 0;
    Integrator integrator = Integrator::kPpm;
    uint64_t photons = 0;
    uint64_t camera_samples = 0;            // camera paths traced (path, pm, sppm: every epoch's)
    uint64_t segments = 0;                  // photon rays traced
    double seconds = 0;                     // since the camera pass began
    double fraction = 0;                    // of the budget, in [0, 1]
    uint32_t workers = 0;                   // workers active on a farm job (0: not shown)
    std::optional<double> estimated_error;  // relative, from the half-estimates, once known
    std::optional<double> measured_error;   // relative (sqrt of relMSE), against the reference
    uint64_t nonfinite_discarded = 0;       // NaN/Inf paths and samples dropped (should be 0)
};

struct RenderOutcome {
    JobSpec job;  // as rendered: the flags, the scene's own settings and the defaults
    Image image;
    RenderProgress progress;
    uint64_t hit_points = 0;
    double initial_radius = 0;
    std::string scene_features;  // what the scene uses (SceneFeatures::ToString)
    double camera_pass_seconds = 0;
    std::vector<ConvergencePoint> convergence;  // one point per epoch
    std::vector<std::string> warnings;          // the job's (also logged as they arise)
    uint64_t peak_memory_bytes = 0;  // this process's peak resident memory, at the end (getrusage)
};

// Called after every merged epoch, on the rendering thread; `job` gives the current image.
using EpochCallback = std::function<void(const RenderProgress&, const Job& job)>;

// Packs the scene into a bundle and renders it. Errors: the scene's load errors, bad settings
// (naming the command-line flag).
absl::StatusOr<RenderOutcome> RenderLocally(const RenderSettings& settings,
                                            const EpochCallback& on_epoch = {});

}  // namespace pf
