// photonfarm-coordinator: holds jobs and their progressive estimates, hands photon batches to
// workers, merges their tallies, streams snapshots to clients.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>
#include <exception>
#include <optional>

#include "core/util/allocator.h"
#include "core/util/command_line.h"
#include "server/coordinator.h"
#include "server/coordinator_server.h"

namespace {

// Waits for SIGINT or SIGTERM on this thread (blocked everywhere, so no handler runs).
int WaitForStopSignal() {
    sigset_t signals;
    sigemptyset(&signals);
    sigaddset(&signals, SIGINT);
    sigaddset(&signals, SIGTERM);
    int signal = 0;
    sigwait(&signals, &signal);
    return signal;
}

void BlockStopSignals() {
    sigset_t signals;
    sigemptyset(&signals);
    sigaddset(&signals, SIGINT);
    sigaddset(&signals, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &signals, nullptr);
}

}  // namespace

int main(int argc, char** argv) {
    pf::KeepLargeBuffersForReuse();
    try {
        pf::SetUpLogging("photonfarm-coordinator");
        CLI::App app{"photonfarm-coordinator: the render farm's coordinator"};
        std::string listen = "0.0.0.0:50051";
        pf::CoordinatorOptions options;
        app.add_option("--listen", listen, "Address to listen on, HOST:PORT (port 0: any free port)")->default_val(listen);
        app.add_option("--heartbeat-seconds", options.heartbeat_seconds, "How often workers heartbeat")
            ->default_val(options.heartbeat_seconds)->check(pf::FiniteRange(0.05, 3600.0));
        app.add_option("--worker-timeout-seconds", options.worker_timeout_seconds,
                       "A worker silent this long is gone and its leases are handed out again")
            ->default_val(options.worker_timeout_seconds)->check(pf::FiniteRange(0.1, 86400.0));
        app.add_option("--lease-seconds", options.lease_seconds, "A batch not reported within this is handed out again")
            ->default_val(options.lease_seconds)->check(pf::FiniteRange(0.1, 86400.0));
        app.add_option("--max-jobs", options.max_running_jobs, "Jobs running at once")
            ->default_val(options.max_running_jobs)->check(CLI::Range(1, 100000));
        app.add_option("--max-scene-triangles", options.scene_limits.max_triangles,
                       "Largest scene a job may bring, in triangles stored (an instanced object's once)")
            ->default_val(options.scene_limits.max_triangles)->check(CLI::Range(uint64_t{1}, uint64_t{1} << 31));
        app.add_option("--max-scene-instances", options.scene_limits.max_instances,
                       "Most object instances a scene may place")
            ->default_val(options.scene_limits.max_instances)->check(CLI::Range(uint64_t{1}, uint64_t{1} << 31));
        app.add_option("--max-image-pixels", options.scene_limits.max_image_pixels, "Largest texture a scene may bring, in pixels")
            ->default_val(options.scene_limits.max_image_pixels)->check(CLI::Range(uint64_t{1}, uint64_t{1} << 31));
        pf::AddLogLevelOption(app);
        if (std::optional<int> exit_code = pf::ParseCommandLine(app, argc, argv, "photonfarm-coordinator")) return *exit_code;
        if (options.worker_timeout_seconds <= options.heartbeat_seconds) {
            std::fprintf(stderr, "photonfarm-coordinator: error: --worker-timeout-seconds must exceed --heartbeat-seconds\n");
            return 2;
        }
        BlockStopSignals();  // before any thread starts, so every thread inherits the mask
        pf::Coordinator coordinator(options);
        absl::StatusOr<std::unique_ptr<pf::CoordinatorServer>> server = pf::CoordinatorServer::Start(coordinator, listen);
        if (!server.ok()) {
            spdlog::error("{}", std::string(server.status().message()));
            return 1;
        }
        const std::string host = listen.substr(0, listen.rfind(':'));
        // One line on stdout with the bound address, for scripts that asked for port 0.
        std::printf("listening on %s:%d\n", host.c_str(), (*server)->Port());
        std::fflush(stdout);
        spdlog::info("listening on {}:{} (plain text: no TLS or tokens yet)", host, (*server)->Port());
        const int signal = WaitForStopSignal();
        spdlog::info("{}: shutting down", signal == SIGTERM ? "SIGTERM" : "SIGINT");
        (*server)->Shutdown();
        return 0;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "photonfarm-coordinator: error: %s\n", error.what());
        return 1;
    }
}
