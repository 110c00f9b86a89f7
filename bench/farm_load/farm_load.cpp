// The farm under load: one real photonfarm-coordinator (TLS on 127.0.0.1), N simulated
// workers, M job slots submitted by K clients, W watchers streaming snapshots with images
// (agents.h). Every job is a real ppm job whose first epoch was traced here once and is
// replayed by the workers (recorded_job.h), so the coordinator does its real work (decode,
// fold, epochs, images) while the harness traces nothing. Prints leases and reports per
// second, round trips and the coordinator's merge latency, its CPU, memory, threads and file
// descriptors, the watchers' snapshot delay, each priority's and client's share of the
// photons, and checks every finished job's image against its reference bit for bit.
//   ./build/bench/farm_load --workers 200 --jobs 8 --clients 4 --watchers 16 --seconds 60
// Exit code 1 when a job's image differs, a job failed or a check could not run.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <random>
#include <thread>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "bench/farm_load/agents.h"
#include "bench/farm_load/coordinator_process.h"
#include "bench/farm_load/load_report.h"
#include "client/farm_client.h"
#include "core/scene_io/scene_loader.h"
#include "core/util/command_line.h"
#include "tests/support/farm_credentials.h"
#include "wire/proto_convert.h"
#include "wire/rpc_status.h"

namespace pf::load {
namespace {

namespace v1 = photonfarm::v1;

struct Flags {
    size_t workers = 50, jobs = 8, clients = 4, watchers = 8;
    double seconds = 60, batch_seconds = 0.5, warmup_seconds = 5, drain_seconds = 180;
    double print_every = 10, crash_at = 0;
    JobShape shape;
    std::vector<int> priorities = {0};
    size_t max_jobs_per_client = 16;
    int record_threads = 2;
};

// The clients' tokens, "client-K SECRET" a line, in `dir`.
std::string WriteClientTokens(const std::string& dir, size_t clients,
                              std::vector<std::string>& secrets) {
    const std::string path = dir + "/load-client-tokens";
    std::ofstream file(path);
    for (size_t k = 0; k < clients; ++k) {
        std::random_device random;
        secrets.push_back(absl::StrCat(absl::Hex(random(), absl::kZeroPad8),
                                       absl::Hex(random(), absl::kZeroPad8),
                                       absl::Hex(random(), absl::kZeroPad8)));
        file << "client-" << k + 1 << " " << secrets.back() << "\n";
    }
    return path;
}

int Run(const Flags& flags) {
    spdlog::set_level(spdlog::level::warn);  // the recordings' coordinator: one line per job
    SetUpGrpc();
    const testing::FarmCredentials& credentials = testing::TestCredentials(PF_SOURCE_DIR);
    std::vector<std::string> secrets;
    const std::string client_tokens = WriteClientTokens(credentials.dir, flags.clients, secrets);

    absl::StatusOr<SceneBundle> bundle =
        PackSceneBundle(std::string(PF_SOURCE_DIR) + "/scenes/cornell-box.gltf");
    if (!bundle.ok()) return Fail(bundle.status());
    std::vector<RecordedJob> recorded;
    double record_seconds = 0;
    for (size_t slot = 0; slot < flags.jobs; ++slot) {
        absl::StatusOr<RecordedJob> job =
            RecordJob(*bundle, LoadJobSettings(flags.shape, 1000 + slot), flags.record_threads);
        if (!job.ok()) return Fail(job.status());
        record_seconds += job->record_seconds;
        recorded.push_back(std::move(*job));
    }
    std::printf("recorded %zu jobs in %.1f s (%zu tally entries a batch on average)\n",
                recorded.size(), record_seconds, AverageEntries(recorded));

    std::vector<std::string> coordinator_flags = {
        "--tls-cert",
        credentials.Path("coordinator.pem"),
        "--tls-key",
        credentials.Path("coordinator.key"),
        "--worker-ca",
        credentials.Path("ca.pem"),
        "--client-token-file",
        client_tokens,
        "--worker-token-file",
        credentials.Path("worker-tokens"),
        "--log-level",
        "error",
        "--max-jobs-per-client",
        std::to_string(flags.max_jobs_per_client),
        "--max-watchers-per-job",
        std::to_string(std::max<size_t>(64, flags.watchers + 1))};
    if (flags.crash_at > 0) {
        coordinator_flags.insert(coordinator_flags.end(),
                                 {"--checkpoint-dir", credentials.Path("load-checkpoints"),
                                  "--checkpoint-seconds", "1"});
    }
    absl::StatusOr<std::unique_ptr<CoordinatorProcess>> coordinator = CoordinatorProcess::Start(
        std::string(PF_BINARY_DIR) + "/server/photonfarm-coordinator", coordinator_flags);
    if (!coordinator.ok()) return Fail(coordinator.status());

    LoadContext ctx;
    ctx.address = (*coordinator)->Address();
    ctx.worker_security = credentials.Worker();
    for (const std::string& secret : secrets) {
        ChannelSecurity security = credentials.Client();
        security.token = secret;
        ctx.client_security.push_back(security);
    }
    for (const RecordedJob& job : recorded) ctx.jobs_by_seed[job.settings.seed()] = &job;
    ctx.scene = ToProto(*bundle);
    ctx.batch_seconds = flags.batch_seconds;
    ctx.start = SteadyClock::now();

    std::atomic<uint32_t> restarts{0};
    SlotBoard board(flags.jobs);
    std::vector<Latencies> worker_latencies(flags.workers);
    std::vector<std::vector<JobOutcome>> outcomes(flags.jobs);
    std::vector<std::vector<SnapshotArrival>> arrivals(flags.watchers);
    std::vector<std::thread> workers, slots, watchers;
    for (size_t i = 0; i < flags.workers; ++i)
        workers.emplace_back([&, i] { worker_latencies[i] = RunSimulatedWorker(ctx); });
    for (size_t i = 0; i < flags.jobs; ++i) {
        const size_t client = i % flags.clients;
        const SlotSettings slot{i, client, absl::StrCat("client-", client + 1),
                                flags.priorities[i % flags.priorities.size()], &recorded[i]};
        slots.emplace_back(
            [&, slot] { outcomes[slot.slot] = RunJobSlot(ctx, board, slot, restarts); });
    }
    for (size_t i = 0; i < flags.watchers; ++i)
        watchers.emplace_back([&, i] {
            arrivals[i] = RunWatcher(ctx, board, i % flags.jobs, i % flags.jobs % flags.clients);
        });

    // Sample once a second until every slot has drained.
    absl::StatusOr<FarmClient> observer =
        FarmClient::Connect(ctx.address, ctx.client_security[0], 30);
    if (!observer.ok()) return Fail(observer.status());
    Samples samples;
    double next_print = flags.print_every;
    bool crashed = false;
    for (double t = 1;; t += 1) {
        std::this_thread::sleep_until(ctx.start + std::chrono::duration_cast<SteadyClock::duration>(
                                                      std::chrono::duration<double>(t)));
        samples.Add(t, ctx.counters, (*coordinator)->Pid(), *observer);
        if (t >= next_print) {
            std::printf("%s\n", samples.ProgressLine().c_str());
            std::fflush(stdout);
            next_print += flags.print_every;
        }
        if (flags.crash_at > 0 && !crashed && t >= flags.crash_at) {
            crashed = true;
            ++restarts;
            if (absl::Status status = (*coordinator)->CrashAndRestart(); !status.ok())
                return Fail(status);
            std::printf("%.0f s: coordinator killed (SIGKILL) and restarted on %s\n", t,
                        ctx.address.c_str());
        }
        if (t >= flags.seconds) ctx.stop_submitting.Stop();
        if (t >= flags.seconds + flags.drain_seconds) break;
        if (t >= flags.seconds && board.AllFinished()) break;
    }
    ctx.stop_submitting.Stop();
    ctx.stop_workers.Stop();
    for (std::thread& thread : slots) thread.join();
    for (std::thread& thread : watchers) thread.join();
    for (std::thread& thread : workers) thread.join();

    LoadReport report;
    report.flags_line = absl::StrCat(
        flags.workers, " workers, ", flags.jobs, " job slots of ", flags.clients,
        " clients (priorities ", absl::StrJoin(flags.priorities, ","), "), ", flags.watchers,
        " watchers; jobs of ", flags.shape.width, "x", flags.shape.height, ", ", flags.shape.epochs,
        " epochs of ", flags.shape.batches_per_epoch, " batches of ", flags.shape.photons_per_batch,
        " photons; a batch takes ", flags.batch_seconds, " s");
    report.window = {flags.warmup_seconds, flags.seconds};
    for (const Latencies& latencies : worker_latencies) report.latencies.Merge(latencies);
    for (std::vector<JobOutcome>& slot : outcomes)
        report.outcomes.insert(report.outcomes.end(), slot.begin(), slot.end());
    for (std::vector<SnapshotArrival>& watcher : arrivals)
        report.arrivals.insert(report.arrivals.end(), watcher.begin(), watcher.end());
    report.samples = std::move(samples);
    absl::StatusOr<MergeHistogram> merges = (*coordinator)->ScrapeMerges();
    if (merges.ok()) report.merges = *merges;
    report.max_jobs_per_client = flags.max_jobs_per_client;
    report.photons_per_batch = flags.shape.photons_per_batch;
    absl::StatusOr<int> exit_code = (*coordinator)->Stop();
    report.coordinator_exit = exit_code.ok() ? *exit_code : -1;
    std::printf("%s", report.Text().c_str());
    return report.Passed() ? 0 : 1;
}

}  // namespace
}  // namespace pf::load

int main(int argc, char** argv) {
    pf::load::Flags flags;
    CLI::App app{"farm_load: one coordinator under many simulated workers, jobs and watchers"};
    app.add_option("--workers", flags.workers, "Simulated workers, each on its own connection")
        ->check(CLI::Range(1, 100000));
    app.add_option("--jobs", flags.jobs, "Job slots: each submits its job again as it finishes")
        ->check(CLI::Range(1, 10000));
    app.add_option("--clients", flags.clients, "Clients (tokens) the slots are spread over")
        ->check(CLI::Range(1, 10000));
    app.add_option("--watchers", flags.watchers, "Snapshot streams with images, over the slots");
    app.add_option("--seconds", flags.seconds, "How long slots keep submitting")
        ->check(CLI::Range(1.0, 86400.0));
    app.add_option("--batch-seconds", flags.batch_seconds,
                   "A simulated worker's compute time per batch")
        ->check(CLI::Range(0.0, 3600.0));
    app.add_option("--warmup-seconds", flags.warmup_seconds, "Left out of the rates at the start");
    app.add_option("--print-every", flags.print_every, "Seconds between progress lines")
        ->check(CLI::Range(1.0, 3600.0));
    app.add_option("--crash-at", flags.crash_at,
                   "Kill the coordinator (SIGKILL) at this second and restart it from its "
                   "checkpoints (0: never)");
    app.add_option("--priorities", flags.priorities, "Priorities, cycled over the slots")
        ->delimiter(',');
    app.add_option("--max-jobs-per-client", flags.max_jobs_per_client,
                   "The coordinator's per-client limit");
    app.add_option("--width", flags.shape.width);
    app.add_option("--height", flags.shape.height);
    app.add_option("--photons-per-batch", flags.shape.photons_per_batch);
    app.add_option("--batches-per-epoch", flags.shape.batches_per_epoch);
    app.add_option("--epochs", flags.shape.epochs, "Epochs per job");
    app.add_option("--record-threads", flags.record_threads, "Threads tracing the recorded epochs");
    if (std::optional<int> exit_code = pf::ParseCommandLine(app, argc, argv, "farm_load"))
        return *exit_code;
    return pf::load::Run(flags);
}
