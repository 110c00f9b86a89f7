// The enums that cross the wire, each mapped by one explicit switch a direction. The wire's
// UNSPECIFIED (0, proto3's absent field) is not a core value: in job settings it means the
// default (ppm, the cone filter, the kd-tree), and FromProto says so by taking that default;
// a state or verdict that is unspecified or unknown is an error naming the field.
#pragma once

#include <string_view>

#include "absl/status/statusor.h"
#include "core/job/integrator.h"
#include "core/job/job_progress.h"
#include "core/job/job_spec.h"
#include "core/job/work_source.h"
#include "photonfarm/v1/jobs.pb.h"
#include "photonfarm/v1/work.pb.h"

namespace pf {

photonfarm::v1::Integrator ToProto(Integrator integrator);
photonfarm::v1::PhotonTracing ToProto(PhotonTracing tracing);
photonfarm::v1::PhotonIndex ToProto(PhotonIndex index);
photonfarm::v1::DensityFilter ToProto(DensityFilter filter);
photonfarm::v1::JobState ToProto(JobState state);
photonfarm::v1::TallyVerdict ToProto(TallyVerdict verdict);

// INVALID_ARGUMENT naming `field` for a value the wire does not define (a newer peer's, or a
// hostile one's). UNSPECIFIED gives the setting's default (JobSpec's, PhotonMapSettings').
absl::StatusOr<Integrator> IntegratorFromProto(int integrator, const char* field);
absl::StatusOr<PhotonTracing> PhotonTracingFromProto(int tracing, const char* field);
absl::StatusOr<PhotonIndex> PhotonIndexFromProto(int index, const char* field);
absl::StatusOr<DensityFilter> DensityFilterFromProto(int filter, const char* field);
// UNSPECIFIED is an error too: every status and verdict says what it is.
absl::StatusOr<JobState> JobStateFromProto(int state, const char* field);
absl::StatusOr<TallyVerdict> TallyVerdictFromProto(int verdict, const char* field);

}  // namespace pf
