// The Jobs service's read-only answers built from a coordinator: the gRPC service and the
// dashboard's JSON endpoints (server/dashboard_api.h) share them, so a script reading either
// sees the same fields.
#pragma once

#include "photonfarm/v1/jobs.pb.h"
#include "server/coordinator.h"

namespace pf {

photonfarm::v1::ListJobsResponse JobListView(const Coordinator& coordinator);
photonfarm::v1::ListWorkersResponse WorkerListView(const Coordinator& coordinator);
// A job's status, one point per merged epoch, and its image's pixel count.
photonfarm::v1::GetConvergenceResponse ConvergenceView(const Job& job, Clock::time_point now);

}  // namespace pf
