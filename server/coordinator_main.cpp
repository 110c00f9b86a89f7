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
#include "server/metrics.h"
#include "worker/rpc_status.h"
#include "worker/secure_channel.h"

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

struct SecurityFlags {
    bool plaintext = false;
    std::string cert_file, key_file, worker_ca_file, client_token_file, worker_token_file;
};

void AddSecurityOptions(CLI::App& app, SecurityFlags* flags) {
    app.add_flag(
           "--plaintext", flags->plaintext,
           "No TLS, for this machine or a private network only: everything crosses in clear, and "
           "without tokens anyone who reaches the port may submit, cancel or report")
        ->envname("PHOTONFARM_PLAINTEXT");
    app.add_option("--tls-cert", flags->cert_file, "The coordinator's certificate chain (PEM)")
        ->envname("PHOTONFARM_TLS_CERT");
    app.add_option("--tls-key", flags->key_file, "The private key (PEM) of --tls-cert")
        ->envname("PHOTONFARM_TLS_KEY");
    app.add_option(
           "--worker-ca", flags->worker_ca_file,
           "Mutual TLS: workers must present a certificate signed by one of these CAs (PEM)")
        ->envname("PHOTONFARM_WORKER_CA");
    app.add_option(
           "--client-token-file", flags->client_token_file,
           absl::StrCat(
               "Tokens that open the Jobs service, one per line, \"SECRET\" or \"NAME SECRET\" "
               "(default: the one in ",
               pf::kClientTokenEnv, ")"))
        ->envname(absl::StrCat(pf::kClientTokenEnv, "_FILE"));
    app.add_option("--worker-token-file", flags->worker_token_file,
                   absl::StrCat("Tokens that open the Work service, likewise (default: the one in ",
                                pf::kWorkerTokenEnv, ")"))
        ->envname(absl::StrCat(pf::kWorkerTokenEnv, "_FILE"));
}

absl::StatusOr<pf::ServerSecurity> LoadSecurity(const SecurityFlags& flags) {
    pf::ServerSecurity security;
    security.plaintext = flags.plaintext;
    if (flags.plaintext &&
        !(flags.cert_file.empty() && flags.key_file.empty() && flags.worker_ca_file.empty()))
        return absl::InvalidArgumentError(
            "--plaintext: cannot be combined with --tls-cert, --tls-key or --worker-ca");
    for (const auto& [file, what, pem] :
         {std::tuple{&flags.cert_file, "--tls-cert", &security.cert_pem},
          std::tuple{&flags.key_file, "--tls-key", &security.key_pem},
          std::tuple{&flags.worker_ca_file, "--worker-ca", &security.worker_ca_pem}}) {
        if (file->empty()) continue;
        absl::StatusOr<std::string> content = pf::ReadPemFile(*file, what);
        if (!content.ok()) return content.status();
        *pem = std::move(*content);
    }
    absl::StatusOr<std::vector<pf::Token>> client =
        pf::ReadTokens(flags.client_token_file, pf::kClientTokenEnv);
    if (!client.ok()) return client.status();
    absl::StatusOr<std::vector<pf::Token>> worker =
        pf::ReadTokens(flags.worker_token_file, pf::kWorkerTokenEnv);
    if (!worker.ok()) return worker.status();
    security.client_tokens = std::move(*client);
    security.worker_tokens = std::move(*worker);
    return security;
}

// What protects the port, in the log; plain text loudly.
void LogSecurity(const pf::ServerSecurity& security, const std::string& host, int port) {
    if (!security.plaintext) {
        spdlog::info("listening on {}:{} with TLS{}; {} client and {} worker tokens", host, port,
                     security.worker_ca_pem.empty() ? "" : " (workers present certificates)",
                     security.client_tokens.size(), security.worker_tokens.size());
        return;
    }
    spdlog::warn(
        "listening on {}:{} in PLAIN TEXT (--plaintext): no encryption, for local use only", host,
        port);
    if (security.client_tokens.empty() && security.worker_tokens.empty())
        spdlog::warn(
            "NO TOKENS: anyone who reaches port {} may submit and cancel jobs and report tallies",
            port);
    else
        spdlog::warn("tokens are checked but cross the network in clear");
}

}  // namespace

int main(int argc, char** argv) {
    pf::KeepLargeBuffersForReuse();
    try {
        pf::SetUpLogging("photonfarm-coordinator");
        pf::RouteGrpcLogsToDebug();
        CLI::App app{"photonfarm-coordinator: the render farm's coordinator"};
        std::string listen = "0.0.0.0:50051";
        pf::CoordinatorOptions options;
        app.add_option("--listen", listen,
                       "Address to listen on, HOST:PORT (port 0: any free port)")
            ->default_val(listen)
            ->check(pf::HostAndPort(0));
        app.add_option("--heartbeat-seconds", options.heartbeat_seconds,
                       "How often workers heartbeat")
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
        std::string metrics_listen;
        app.add_option("--metrics-listen", metrics_listen,
                       "Serve Prometheus metrics at http://HOST:PORT/metrics (plain HTTP: bind it "
                       "to a private address)")
            ->envname("PHOTONFARM_METRICS_LISTEN")
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
        pf::ServerOptions server_options;
        app.add_option(
               "--max-message-bytes", server_options.max_message_bytes,
               "Largest message a client or worker may send (a submitted scene travels in one)")
            ->default_val(server_options.max_message_bytes)
            ->check(CLI::Range(1 << 20, pf::kMaxMessageBytes));
        SecurityFlags security;
        AddSecurityOptions(app, &security);
        pf::AddLogLevelOption(app);
        if (std::optional<int> exit_code =
                pf::ParseCommandLine(app, argc, argv, "photonfarm-coordinator"))
            return *exit_code;
        if (options.worker_timeout_seconds <= options.heartbeat_seconds) {
            std::fprintf(stderr,
                         "photonfarm-coordinator: error: --worker-timeout-seconds must exceed "
                         "--heartbeat-seconds\n");
            return 2;
        }
        absl::StatusOr<pf::ServerSecurity> loaded = LoadSecurity(security);
        if (!loaded.ok()) {
            std::fprintf(stderr, "photonfarm-coordinator: error: %s\n",
                         std::string(loaded.status().message()).c_str());
            return 2;
        }
        server_options.address = listen;
        server_options.security = std::move(*loaded);
        BlockStopSignals();  // before any thread starts, so every thread inherits the mask
        pf::Coordinator coordinator(options);
        if (!options.checkpoint_dir.empty()) {
            const size_t resumed = coordinator.RestoreCheckpoints();
            spdlog::info("checkpoints in {} every {} s; {} jobs resumed", options.checkpoint_dir,
                         options.checkpoint_seconds, resumed);
        }
        absl::StatusOr<std::unique_ptr<pf::CoordinatorServer>> server =
            pf::CoordinatorServer::Start(coordinator, server_options);
        if (!server.ok()) {
            std::fprintf(stderr, "photonfarm-coordinator: error: %s\n",
                         std::string(server.status().message()).c_str());
            return 1;
        }
        std::unique_ptr<pf::MetricsServer> metrics;
        if (!metrics_listen.empty()) {
            absl::StatusOr<std::unique_ptr<pf::MetricsServer>> started = pf::MetricsServer::Start(
                metrics_listen, std::make_shared<pf::CoordinatorMetrics>(coordinator));
            if (!started.ok()) {
                std::fprintf(stderr, "photonfarm-coordinator: error: %s\n",
                             std::string(started.status().message()).c_str());
                return 1;
            }
            metrics = std::move(*started);
        }
        const std::string host = listen.substr(0, listen.rfind(':'));
        // A line on stdout with the bound address (and one with the metrics'), for scripts
        // that asked for port 0.
        std::printf("listening on %s:%d\n", host.c_str(), (*server)->Port());
        if (metrics)
            std::printf("metrics on %s:%d\n",
                        metrics_listen.substr(0, metrics_listen.rfind(':')).c_str(),
                        metrics->Port());
        std::fflush(stdout);
        LogSecurity(server_options.security, host, (*server)->Port());
        const int signal = WaitForStopSignal();
        spdlog::info("{}: shutting down", signal == SIGTERM ? "SIGTERM" : "SIGINT");
        (*server)->Shutdown();
        return 0;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "photonfarm-coordinator: error: %s\n", error.what());
        return 1;
    }
}
