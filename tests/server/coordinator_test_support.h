// Helpers of the coordinator's tests: small jobs, a clock the test moves, and a CPU backend
// that runs leased batches.
#pragma once

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <random>

#include "absl/strings/str_split.h"
#include "core/scene_io/scene_loader.h"
#include "core/util/file_io.h"
#include "embedded/local_render.h"
#include "server/checkpoint_store.h"
#include "server/coordinator.h"
#include "server/in_process_source.h"
#include "server/metrics.h"
#include "tests/support/test_env.h"
#include "worker/backend_factory.h"
#include "worker/worker_loop.h"

namespace pf::coordinator_test {

inline std::string ScenePath(const std::string& name) {
    return std::string(PF_SOURCE_DIR) + "/scenes/" + name;
}

inline JobSpec SmallSpec(uint64_t photons) {
    JobSpec spec;
    spec.width = 32;
    spec.height = 32;
    spec.photon_budget = photons;
    spec.layout = {1u << 12, 4};
    return spec;
}

// The embedded render of cornell-box with SmallSpec(photons) on one thread: what the
// coordinator's merges of the same job must reproduce bit for bit.
inline absl::StatusOr<RenderOutcome> EmbeddedReference(uint64_t photons) {
    RenderSettings settings;
    settings.scene_path = ScenePath("cornell-box.gltf");
    settings.job = SmallSpec(photons);
    settings.threads = 1;
    return RenderLocally(settings);
}

inline JobRequest SmallJob(uint64_t photons, int priority = 0, std::string owner = "tester") {
    absl::StatusOr<SceneBundle> bundle = PackSceneBundle(ScenePath("cornell-box.gltf"));
    EXPECT_TRUE(bundle.ok()) << bundle.status();
    return {"test", std::move(owner), std::move(*bundle), SmallSpec(photons), priority};
}

// A clock the test moves by hand.
struct FakeClock {
    Clock::time_point now = Clock::time_point() + std::chrono::hours(1);
    void Advance(double seconds) {
        now += std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
    }
};

inline CoordinatorOptions Options(FakeClock* clock) {
    CoordinatorOptions options;
    options.lease_seconds = 30;
    options.worker_timeout_seconds = 10;
    options.now = [clock] { return clock->now; };
    return options;
}

inline WorkerRegistration Cpu() { return {"cpu", 1, std::string(kPhotonfarmVersion), ""}; }

// Runs batches the way a worker would, for reports made by hand.
class BatchRunner {
public:
    std::vector<BatchResult> Run(const CoordinatorLease& lease) {
        if (!backend_ || job_ != lease.grant.job) {
            backend_ = *CreateBackend("cpu", lease.grant.job->scene);
            job_ = lease.grant.job;
            EXPECT_TRUE(backend_
                            ->BeginJob({&job_->scene, &job_->emitters, *job_->hit_points,
                                        job_->seed, &job_->spec})
                            .ok());
            epoch_ = UINT64_MAX;
        }
        if (epoch_ != lease.grant.epoch) {
            EXPECT_TRUE(
                backend_->BeginEpoch(lease.grant.epoch, *lease.grant.regions, nullptr).ok());
        }
        epoch_ = lease.grant.epoch;
        return *backend_->RunBatches(lease.grant.batches);
    }

private:
    std::unique_ptr<Backend> backend_;
    std::shared_ptr<const JobPayload> job_;
    uint64_t epoch_ = UINT64_MAX;
};

inline bool SamePixels(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Rgb)) == 0;
}

}  // namespace pf::coordinator_test
