// The coordinator's camera passes for an sppm or rpm job, one an epoch (TracedCameraPasses):
// the hit points traced anew, as its workers trace them; each traced while the epoch before
// it runs.
#pragma once

#include <memory>

#include "absl/status/statusor.h"
#include "core/camera/camera_pass.h"
#include "core/estimate/progressive_estimate.h"
#include "core/job/work_source.h"

namespace pf {

// Passes over the payload's scene, kept alive by the result (with an Embree scene of its
// own); `film` the job's film, its features analysed. The scene's load errors, or Embree's.
// Each call returns epoch e's pass and starts tracing e + 1's on the calling thread's TBB
// arena, so the job holds one pass more than it uses (for sppm, a pass's hit points); calls
// may come from any thread; destroying the result waits for a pass in flight,
// cut short.
absl::StatusOr<EpochCameraPass> EpochCameraPasses(std::shared_ptr<const JobPayload> payload,
                                                  const CameraPassSettings& film);
// The same through `tracer`, an Embree scene of the payload's scene already built (a job's
// preparation has one).
EpochCameraPass EpochCameraPasses(std::shared_ptr<const JobPayload> payload,
                                  const CameraPassSettings& film,
                                  std::shared_ptr<const Tracer> tracer);

}  // namespace pf
