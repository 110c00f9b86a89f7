// photonfarm-coordinator: holds jobs and their progressive estimates, hands photon batches to
// workers, merges their tallies, streams snapshots to clients.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>
#include <exception>
#include <optional>
#include <tuple>

#include "absl/strings/str_cat.h"
#include "core/util/allocator.h"
#include "core/util/command_line.h"
#include "server/coordinator.h"
#include "server/coordinator_server.h"
#include "server/dashboard_server.h"
#include "server/metrics.h"
#include "wire/rpc_status.h"
#include "wire/server_security.h"

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

// What the command line sets.
struct CoordinatorFlags {
    std::string listen = "0.0.0.0:50051";
    std::string metrics_listen;
    std::string web_listen;
    pf::CoordinatorOptions options;
    pf::ServerOptions server;
    pf::ServerSecurityFlags security;
};

void AddCoordinatorOptions(CLI::App& app, CoordinatorFlags* flags) {
    pf::CoordinatorOptions& options = flags->options;
    app.add_option("--listen", flags->listen,
                   "Address to listen on, HOST:PORT (port 0: any free port)")
        ->default_val(flags->listen)
        ->check(pf::HostAndPort(0));
    app.add_option("--heartbeat-seconds", options.heartbeat_seconds, "How often workers heartbeat")
        ->default_val(options.heartbeat_seconds)
        ->check(pf::FiniteRange(0.05, 3600.0));
    app.add_option("--worker-timeout-seconds", options.worker_timeout_seconds,
                   "A worker silent this long is gone and its leases are handed out again")
        ->default_val(options.worker_timeout_seconds)
        ->check(pf::FiniteRange(0.1, 86400.0));
    app.add_option("--lease-seconds", options.lease_seconds,
                   "A batch not reported within this is handed out again")
        ->default_val(options.lease_seconds)
        ->check(pf::FiniteRange(0.1, 86400.0));
    app.add_option("--max-jobs", options.max_running_jobs, "Jobs running at once")
        ->default_val(options.max_running_jobs)
        ->check(CLI::Range(1, 100000));
    app.add_option(
           "--max-scene-triangles", options.scene_limits.max_triangles,
           "Largest scene a job may bring, in triangles stored (an instanced object's once)")
        ->default_val(options.scene_limits.max_triangles)
        ->check(CLI::Range(uint64_t{1}, uint64_t{1} << 31));
    app.add_option("--max-scene-instances", options.scene_limits.max_instances,
                   "Most object instances a scene may place")
        ->default_val(options.scene_limits.max_instances)
        ->check(CLI::Range(uint64_t{1}, uint64_t{1} << 31));
    app.add_option("--max-image-pixels", options.scene_limits.max_image_pixels,
                   "Largest texture a scene may bring, in pixels")
        ->default_val(options.scene_limits.max_image_pixels)
        ->check(CLI::Range(uint64_t{1}, uint64_t{1} << 31));
    app.add_option("--metrics-listen", flags->metrics_listen,
                   "Serve Prometheus metrics at http://HOST:PORT/metrics (plain HTTP: bind it "
                   "to a private address)")
        ->envname("PHOTONFARM_METRICS_LISTEN")
        ->check(pf::HostAndPort(0));
    app.add_option("--web-listen", flags->web_listen,
                   "Serve the browser dashboard at HOST:PORT: HTTPS with the coordinator's "
                   "certificate, plain HTTP only with --plaintext; client tokens log in")
        ->envname("PHOTONFARM_WEB_LISTEN")
        ->check(pf::HostAndPort(0));
    app.add_option("--checkpoint-dir", options.checkpoint_dir,
                   "Keep every job's state here, and resume the jobs found here at start "
                   "(after a crash or a stop)")
        ->envname("PHOTONFARM_CHECKPOINT_DIR");
    app.add_option(
           "--checkpoint-seconds", options.checkpoint_seconds,
           "How often running jobs are checkpointed (also when a job ends, and at shutdown)")
        ->envname("PHOTONFARM_CHECKPOINT_SECONDS")
        ->default_val(options.checkpoint_seconds)
        ->check(pf::FiniteRange(0.01, 86400.0));
    pf::ClientLimits& limits = options.client_limits;
    app.add_option("--max-jobs-per-client", limits.max_jobs_per_client,
                   "Jobs one client (token name, or address without tokens) may run at once")
        ->default_val(limits.max_jobs_per_client)
        ->check(CLI::Range(1, 100000));
    app.add_option("--max-watchers-per-job", limits.max_watchers_per_job,
                   "Snapshot streams open at once on one job")
        ->default_val(limits.max_watchers_per_job)
        ->check(CLI::Range(1, 100000));
    app.add_option("--max-bundle-bytes", limits.max_bundle_bytes,
                   "Largest scene bundle a job may bring, in bytes")
        ->default_val(limits.max_bundle_bytes)
        ->check(CLI::Range(uint64_t{1}, pf::kMaxBundleBytes));
    app.add_option("--max-render-pixels", limits.max_render_pixels,
                   "Largest image a job may ask for, width x height")
        ->default_val(limits.max_render_pixels)
        ->check(CLI::Range(uint64_t{1}, uint64_t{1} << 30));
    app.add_option("--max-photons-per-batch", limits.max_photons_per_batch,
                   "Most photons a job's batch may hold")
        ->default_val(limits.max_photons_per_batch)
        ->check(CLI::Range(1u, pf::kMaxPhotonsPerBatch));
    app.add_option("--max-message-bytes", flags->server.max_message_bytes,
                   "Largest message a client or worker may send (a submitted scene travels in one)")
        ->default_val(flags->server.max_message_bytes)
        ->check(CLI::Range(1 << 20, pf::kMaxMessageBytes));
    pf::AddServerSecurityOptions(app, &flags->security);
    pf::AddLogLevelOption(app);
}

// Runs the coordinator until SIGINT or SIGTERM: resumes the checkpointed jobs, serves gRPC
// (and the metrics), prints the bound addresses for scripts. 0, or 1 when it cannot listen.
int Serve(const CoordinatorFlags& flags) {
    pf::Coordinator coordinator(flags.options);
    if (!flags.options.checkpoint_dir.empty()) {
        const size_t resumed = coordinator.RestoreCheckpoints();
        spdlog::info("checkpoints in {} every {} s; {} jobs resumed", flags.options.checkpoint_dir,
                     flags.options.checkpoint_seconds, resumed);
    }
    absl::StatusOr<std::unique_ptr<pf::CoordinatorServer>> server =
        pf::CoordinatorServer::Start(coordinator, flags.server);
    if (!server.ok()) {
        std::fprintf(stderr, "photonfarm-coordinator: error: %s\n",
                     std::string(server.status().message()).c_str());
        return 1;
    }
    std::unique_ptr<pf::MetricsServer> metrics;
    if (!flags.metrics_listen.empty()) {
        absl::StatusOr<std::unique_ptr<pf::MetricsServer>> started = pf::MetricsServer::Start(
            flags.metrics_listen, std::make_shared<pf::CoordinatorMetrics>(coordinator));
        if (!started.ok()) {
            std::fprintf(stderr, "photonfarm-coordinator: error: %s\n",
                         std::string(started.status().message()).c_str());
            return 1;
        }
        metrics = std::move(*started);
    }
    std::unique_ptr<pf::DashboardServer> dashboard;
    if (!flags.web_listen.empty()) {
        absl::StatusOr<std::unique_ptr<pf::DashboardServer>> started = pf::DashboardServer::Start(
            flags.web_listen, flags.server.security, coordinator, (*server)->Access());
        if (!started.ok()) {
            std::fprintf(stderr, "photonfarm-coordinator: error: %s\n",
                         std::string(started.status().message()).c_str());
            return 1;
        }
        dashboard = std::move(*started);
    }
    const std::string host = flags.listen.substr(0, flags.listen.rfind(':'));
    // A line on stdout with the bound address (and one with the metrics'), for scripts
    // that asked for port 0.
    std::printf("listening on %s:%d\n", host.c_str(), (*server)->Port());
    if (metrics)
        std::printf("metrics on %s:%d\n",
                    flags.metrics_listen.substr(0, flags.metrics_listen.rfind(':')).c_str(),
                    metrics->Port());
    if (dashboard) std::printf("dashboard on %s\n", dashboard->Url().c_str());
    std::fflush(stdout);
    pf::LogServerSecurity(flags.server.security, host, (*server)->Port());
    const int signal = WaitForStopSignal();
    spdlog::info("{}: shutting down", signal == SIGTERM ? "SIGTERM" : "SIGINT");
    dashboard.reset();
    (*server)->Shutdown();
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    pf::KeepLargeBuffersForReuse();
    try {
        pf::SetUpLogging("photonfarm-coordinator");
        pf::SetUpGrpc();
        CLI::App app{"photonfarm-coordinator: the render farm's coordinator"};
        CoordinatorFlags flags;
        AddCoordinatorOptions(app, &flags);
        if (std::optional<int> exit_code =
                pf::ParseCommandLine(app, argc, argv, "photonfarm-coordinator"))
            return *exit_code;
        if (flags.options.worker_timeout_seconds <= flags.options.heartbeat_seconds) {
            std::fprintf(stderr,
                         "photonfarm-coordinator: error: --worker-timeout-seconds must exceed "
                         "--heartbeat-seconds\n");
            return 2;
        }
        absl::StatusOr<pf::ServerSecurity> loaded = pf::LoadServerSecurity(flags.security);
        if (!loaded.ok()) {
            std::fprintf(stderr, "photonfarm-coordinator: error: %s\n",
                         std::string(loaded.status().message()).c_str());
            return 2;
        }
        flags.server.address = flags.listen;
        flags.server.security = std::move(*loaded);
        BlockStopSignals();  // before any thread starts, so every thread inherits the mask
        return Serve(flags);
    } catch (const std::exception& error) {
        std::fprintf(stderr, "photonfarm-coordinator: error: %s\n", error.what());
        return 1;
    }
}
