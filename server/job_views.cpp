// Listings and convergence logs as the Jobs service's messages.
#include "server/job_views.h"

#include "wire/proto_convert.h"

namespace pf {

namespace v1 = photonfarm::v1;

v1::ListJobsResponse JobListView(const Coordinator& coordinator) {
    v1::ListJobsResponse response;
    for (const JobProgress& progress : coordinator.ListJobs())
        *response.add_jobs() = ToProto(progress);
    return response;
}

v1::ListWorkersResponse WorkerListView(const Coordinator& coordinator) {
    v1::ListWorkersResponse response;
    for (const WorkerView& view : coordinator.ListWorkers()) {
        v1::WorkerStatus* worker = response.add_workers();
        worker->set_worker_id(view.worker_id);
        worker->set_backend(view.registration.backend);
        worker->set_threads(view.registration.threads);
        worker->set_version(view.registration.version);
        worker->set_peer(view.registration.peer);
        worker->set_seconds_since_heartbeat(view.seconds_since_heartbeat);
        worker->set_batches_leased(view.batches_leased);
        worker->set_batches_done(view.batches_done);
        worker->set_photons_reported(view.photons_reported);
        worker->set_seconds_registered(view.seconds_registered);
        if (view.seconds_registered > 0)
            worker->set_photons_per_second(static_cast<double>(view.photons_reported) /
                                           view.seconds_registered);
    }
    return response;
}

v1::GetConvergenceResponse ConvergenceView(const Job& job, Clock::time_point now) {
    v1::GetConvergenceResponse response;
    *response.mutable_status() = ToProto(job.Progress(now));
    for (const ConvergencePoint& point : job.Convergence()) *response.add_points() = ToProto(point);
    if (std::shared_ptr<const Image> image = job.CurrentImage())
        response.set_pixels(static_cast<uint64_t>(image->width) * image->height);
    return response;
}

}  // namespace pf
