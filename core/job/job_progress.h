// A job's state and progress as the coordinator reports them (listings, snapshots, the
// dashboard): plain data, put on the wire by wire/proto_convert.h.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/film/image_metrics.h"
#include "core/job/integrator.h"

namespace pf {

enum class JobState { kRunning, kDone, kCancelled, kFailed };

// A job's state for listings and snapshots.
struct JobProgress {
    std::string job_id, name;
    std::string owner;  // who submitted it (JobRequest::owner)
    JobState state = JobState::kRunning;
    int priority = 0;
    Integrator integrator = Integrator::kPpm;
    uint64_t epochs = 0, photons = 0, hit_points = 0;
    uint64_t camera_samples =
        0;  // camera paths traced over the merged epochs (Estimate::CameraSamples)
    double initial_radius = 0;   // R0, world units
    std::string scene_features;  // what the scene uses (SceneFeatures::ToString)
    double elapsed_seconds = 0;
    double photons_per_second = 0;
    double budget_fraction = 0;
    std::optional<double> estimated_error;  // relative (ErrorEstimate::RelativeError), once known
    std::optional<ImageDifference> measured_error;  // against the reference, when the job has one
    uint64_t nonfinite_discarded = 0;  // NaN/Inf paths and samples dropped (ProgressiveEstimate)
    uint32_t workers_active = 0;
    // The current epoch's batches waiting for a worker, and those under a live lease.
    uint32_t batches_pending = 0, batches_leased = 0;
    std::string message;                // why it failed or was cancelled
    std::vector<std::string> warnings;  // found when it was submitted
};

}  // namespace pf
