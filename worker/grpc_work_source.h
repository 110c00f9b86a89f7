// A WorkSource across the network: the coordinator's Work service over gRPC. Registers on
// first use and again whenever the coordinator has forgotten this worker; fetches a job's
// scene and hit points once (content-addressed, checked, cached in memory and optionally on
// disk) and each epoch's radii.
#pragma once

#include <grpcpp/channel.h>

#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

#include "core/job/work_source.h"
#include "photonfarm/v1/work.grpc.pb.h"

namespace pf {

class GrpcWorkSource final : public WorkSource {
public:
    // `address` names the coordinator in errors; `cache_dir` (may be empty: no disk cache)
    // keeps scene and hit point blobs across restarts.
    GrpcWorkSource(std::shared_ptr<grpc::Channel> channel, std::string address,
                   WorkerRegistration registration, std::string cache_dir);

    absl::StatusOr<WorkGrant> Lease(uint32_t chunks) override;
    absl::StatusOr<TallyVerdict> Report(const std::string& job_id, BatchResult result) override;
    // Registers first if needed. Thread-safe, like the rest of this class.
    absl::Status Heartbeat();
    // Returns this worker's leases to the coordinator; a later call registers anew.
    absl::Status Unregister();
    double HeartbeatSeconds() const;
    // Waits up to `seconds` for the channel to the coordinator to be connected, asking it to
    // connect: after a failed attempt, gRPC 1.51's channel may otherwise sit idle, failing
    // every call at once, after the coordinator is back. True once connected.
    bool WaitForConnection(double seconds);

private:
    absl::StatusOr<std::string> WorkerId();
    void Forget(const std::string& worker_id);
    absl::StatusOr<std::string> FetchBlob(const std::string& digest, bool keep_on_disk);
    absl::StatusOr<std::shared_ptr<const JobPayload>> PayloadFor(
        const photonfarm::v1::JobInputs& job, const JobSpec& spec);
    absl::StatusOr<std::shared_ptr<const GatherRegions>> RegionsFor(const std::string& digest,
                                                                    uint64_t count);

    std::shared_ptr<grpc::Channel> channel_;
    std::unique_ptr<photonfarm::v1::Work::Stub> stub_;
    const std::string address_;
    const WorkerRegistration registration_;
    const std::string cache_dir_;

    mutable std::mutex mutex_;
    std::string worker_id_;  // empty: not registered
    double heartbeat_seconds_ = 2;
    // Recently used payloads (by scene and hit point digests) and gather regions (by digest).
    std::list<std::pair<std::string, std::shared_ptr<const JobPayload>>> payloads_;
    std::list<std::pair<std::string, std::shared_ptr<const GatherRegions>>> regions_;
};

}  // namespace pf
