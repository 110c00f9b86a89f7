// Conversion between the core's batch types and their wire form (photonfarm.v1). Decoding
// treats every message as hostile: anything malformed is refused with INVALID_ARGUMENT and
// never reaches the estimate.
#pragma once

#include <cstdint>

#include "absl/status/statusor.h"
#include "core/estimate/convergence.h"
#include "core/film/image.h"
#include "core/film/image_metrics.h"
#include "core/job/batch.h"
#include "core/job/job_progress.h"
#include "core/job/job_spec.h"
#include "core/scene/scene_bundle.h"
#include "photonfarm/v1/batch.pb.h"
#include "photonfarm/v1/jobs.pb.h"
#include "wire/enums.h"

namespace pf {

photonfarm::v1::BatchSpec ToProto(const BatchSpec& spec);
BatchSpec FromProto(const photonfarm::v1::BatchSpec& spec);

photonfarm::v1::BatchResult ToProto(const BatchResult& result);
// Checks, for a job with `hit_point_count` hit points (0 for the integrators that render
// pixels) whose sample slices index `item_count` items (its hit points, or its pixels):
// entries sorted and in range, one photon count and three finite, non-negative flux values
// per entry, counts > 0, the sample slice inside the items with three finite, non-negative
// values per item.
absl::StatusOr<BatchResult> FromProto(const photonfarm::v1::BatchResult& result,
                                      uint32_t hit_point_count, uint32_t item_count);

photonfarm::v1::SceneBundle ToProto(const SceneBundle& bundle);
// Checks paths and limits (CheckSceneBundle) and refuses a path given twice.
absl::StatusOr<SceneBundle> FromProto(const photonfarm::v1::SceneBundle& bundle);

// Job settings, zero meaning "the default"; checked by CheckJobSpec naming the fields.
photonfarm::v1::JobSettings ToProto(const JobSpec& spec);
absl::StatusOr<JobSpec> FromProto(const photonfarm::v1::JobSettings& settings);

// A job's status for listings and snapshots (owner stays on the coordinator).
photonfarm::v1::JobStatus ToProto(const JobProgress& progress);

photonfarm::v1::Image ToProto(const Image& image);
absl::StatusOr<Image> FromProto(const photonfarm::v1::Image& image);

// The convergence log (RMSE, relative MSE and non-finite pixels of a measurement; PSNR and
// the largest difference stay behind).
photonfarm::v1::ReferenceError ToProto(const ImageDifference& difference);
ImageDifference FromProto(const photonfarm::v1::ReferenceError& error);
photonfarm::v1::ConvergencePoint ToProto(const ConvergencePoint& point);
ConvergencePoint FromProto(const photonfarm::v1::ConvergencePoint& point, uint64_t pixels);
}  // namespace pf
