// photonfarm-worker: leases photon batches from a coordinator, runs them, reports the tallies;
// reconnects with back-off when the coordinator is away; on SIGTERM or SIGINT finishes the
// batches in hand, returns its leases and exits cleanly.
#include <spdlog/spdlog.h>
#include <tbb/task_arena.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <mutex>
#include <optional>
#include <random>
#include <thread>

#include "core/util/allocator.h"
#include "core/util/command_line.h"
#include "wire/rpc_status.h"
#include "wire/secure_channel.h"
#include "worker/backend_factory.h"
#include "worker/grpc_work_source.h"
#include "worker/retry_policy.h"
#include "worker/worker_loop.h"

namespace {

// Set once a stop signal arrives; waits end early through the condition variable.
struct StopFlag {
    std::mutex mutex;
    std::condition_variable changed;
    bool stop = false;

    void Set() {
        std::lock_guard lock(mutex);
        stop = true;
        changed.notify_all();
    }
    bool IsSet() {
        std::lock_guard lock(mutex);
        return stop;
    }
    // Waits up to `seconds`; true if stopping.
    bool WaitFor(double seconds) {
        std::unique_lock lock(mutex);
        return changed.wait_for(lock, std::chrono::duration<double>(seconds), [&] { return stop; });
    }
};

sigset_t StopSignals() {
    sigset_t signals;
    sigemptyset(&signals);
    sigaddset(&signals, SIGINT);
    sigaddset(&signals, SIGTERM);
    return signals;
}

// What the command line sets.
struct WorkerFlags {
    std::string coordinator;
    int threads = 0;
    std::string backend = "cpu";
    std::string cache_dir;
    std::string alive_file;
    uint32_t chunks_per_lease = 0;
    pf::ChannelSecurityFlags security;
};

void AddWorkerOptions(CLI::App& app, WorkerFlags* flags) {
    app.add_option("--coordinator", flags->coordinator, "Coordinator address HOST:PORT")
        ->envname("PHOTONFARM_COORDINATOR")
        ->required()
        ->check(pf::HostAndPort(1));
    app.add_option("--threads", flags->threads, "Threads (default: all cores)")
        ->envname("PHOTONFARM_THREADS")
        ->check(CLI::Range(1, 4096));
    app.add_option("--backend", flags->backend,
                   "Backend of the batches: cpu (Embree) or vulkan (compute on a GPU)")
        ->default_val(flags->backend)
        ->check(CLI::IsMember(pf::BackendNames()));
    app.add_flag_callback(
        "--list-devices",
        [flags] {
            const int threads =
                flags->threads > 0 ? flags->threads : tbb::this_task_arena::max_concurrency();
            std::fputs(pf::DescribeDevices(threads).c_str(), stdout);
            throw CLI::Success();
        },
        "List the devices each backend can run on, and exit");
    app.add_option("--cache-dir", flags->cache_dir,
                   "Keep fetched scenes and hit points here across restarts");
    app.add_option("--alive-file", flags->alive_file,
                   "Touch this file at every heartbeat the coordinator answers (for container "
                   "health checks)")
        ->envname("PHOTONFARM_ALIVE_FILE");
    app.add_option("--chunks-per-lease", flags->chunks_per_lease,
                   "Chunks of 2^19 photons to lease at once (default: one per thread)")
        ->check(CLI::Range(1, 1 << 16));
    pf::AddChannelSecurityOptions(&app, &flags->security, pf::kWorkerTokenEnv);
    pf::AddLogLevelOption(app);
}

// Steps the loop until `stop` or an error not worth waiting out (retry_policy.h); 0, or 1 for
// such an error.
int RunUntilStopped(pf::WorkerLoop& loop, pf::GrpcWorkSource& source, tbb::task_arena& arena,
                    StopFlag& stop) {
    pf::Backoff backoff(std::random_device{}());
    bool reported_outage = false;
    while (!stop.IsSet()) {
        absl::StatusOr<size_t> ran;
        arena.execute([&] { ran = loop.Step(); });
        if (ran.ok()) {
            if (reported_outage) spdlog::info("coordinator reachable again");
            reported_outage = false;
            backoff.Reset();
            continue;
        }
        if (!pf::Retryable(ran.status())) {
            spdlog::error("{}", std::string(ran.status().message()));
            return 1;
        }
        if (!reported_outage)
            spdlog::warn("{}; retrying with back-off", std::string(ran.status().message()));
        reported_outage = true;
        const double wait = backoff.NextWait();
        const bool unavailable = absl::IsUnavailable(ran.status());
        if (unavailable || absl::IsDeadlineExceeded(ran.status())) source.WaitForConnection(wait);
        if (stop.WaitFor(unavailable ? 0.0 : wait)) break;
    }
    return 0;
}

// Works for the coordinator until `stop` (or an error not worth waiting out), heartbeating
// beside; then reports what is in hand and leaves. The exit code: 1 also for Vulkan validation
// errors.
int Serve(const WorkerFlags& flags, const pf::ChannelSecurity& security,
          const pf::BackendDevice& device, StopFlag& stop) {
    tbb::task_arena arena(flags.threads > 0 ? flags.threads
                                            : tbb::this_task_arena::max_concurrency());
    pf::GrpcWorkSource source(
        pf::OpenChannel(flags.coordinator, security), flags.coordinator,
        {device.description.substr(0, 64), static_cast<uint32_t>(arena.max_concurrency()),
         std::string(pf::kPhotonfarmVersion), ""},
        flags.cache_dir);
    pf::WorkerLoop loop(
        source, flags.backend,
        flags.chunks_per_lease > 0 ? flags.chunks_per_lease : arena.max_concurrency(),
        /*report_in_background=*/true);

    std::thread heartbeat_thread([&] {
        while (!stop.WaitFor(source.HeartbeatSeconds())) {
            if (absl::Status status = source.Heartbeat(); !status.ok())
                spdlog::debug("heartbeat: {}", std::string(status.message()));
            else if (!flags.alive_file.empty())
                std::ofstream(flags.alive_file, std::ios::trunc) << "alive\n";
        }
    });

    int exit_code = RunUntilStopped(loop, source, arena, stop);
    if (absl::Status status = loop.Flush(); !status.ok())
        spdlog::warn("reporting the last results: {}", std::string(status.message()));
    stop.Set();
    heartbeat_thread.join();
    if (absl::Status status = source.Unregister(); !status.ok())
        spdlog::warn("leaving: {}", std::string(status.message()));
    if (const uint64_t errors = pf::BackendValidationErrors(); errors > 0) {
        spdlog::error("the Vulkan validation layer reported {} errors", errors);
        exit_code = 1;
    }
    const pf::WorkerStats stats = loop.Stats();
    spdlog::info("ran {} batches ({} refused), {} photons", stats.batches_run,
                 stats.batches_refused, stats.photons);
    return exit_code;
}

}  // namespace

int main(int argc, char** argv) {
    pf::KeepLargeBuffersForReuse();
    try {
        pf::SetUpLogging("photonfarm-worker");
        pf::SetUpGrpc();
        CLI::App app{"photonfarm-worker: runs photon batches for a photonfarm coordinator"};
        WorkerFlags flags;
        AddWorkerOptions(app, &flags);
        if (std::optional<int> exit_code =
                pf::ParseCommandLine(app, argc, argv, "photonfarm-worker"))
            return *exit_code;
        const absl::StatusOr<pf::ChannelSecurity> security =
            pf::LoadChannelSecurity(flags.security, pf::kWorkerTokenEnv);
        if (!security.ok()) {
            std::fprintf(stderr, "photonfarm-worker: error: %s\n",
                         std::string(security.status().message()).c_str());
            return 2;
        }
        if (security->plaintext)
            spdlog::warn("--plaintext: talking to the coordinator without TLS");
        // Signals are taken by one thread with sigwait; every other thread inherits the block.
        const sigset_t signals = StopSignals();
        pthread_sigmask(SIG_BLOCK, &signals, nullptr);
        // After the mask, so that the device's own threads (lavapipe's) inherit it too.
        const absl::StatusOr<pf::BackendDevice> device = pf::OpenBackendDevice(flags.backend);
        if (!device.ok()) {
            std::fprintf(stderr, "photonfarm-worker: error: %s\n",
                         std::string(device.status().message()).c_str());
            return 1;
        }
        StopFlag stop;
        std::thread signal_thread([&] {
            int signal = 0;
            sigwait(&signals, &signal);
            if (signal != 0 && !stop.IsSet()) {
                spdlog::info("{}: finishing the batches in hand, then leaving",
                             signal == SIGTERM ? "SIGTERM" : "SIGINT");
                stop.Set();
            }
        });

        const int exit_code = Serve(flags, *security, *device, stop);
        // Wake the signal thread if no signal came, then join it.
        pthread_kill(signal_thread.native_handle(), SIGTERM);
        signal_thread.join();
        return exit_code;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "photonfarm-worker: error: %s\n", error.what());
        return 1;
    }
}
