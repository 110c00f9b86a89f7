// Listing, cancelling and fetching farm jobs; listing workers. Tables for people, --json for
// scripts.
#include "client/job_commands.h"

#include <spdlog/spdlog.h>

#include <cstdio>
#include <functional>
#include <memory>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "client/convergence_report.h"
#include "client/farm_client.h"
#include "client/output_files.h"
#include "client/submit_command.h"
#include "core/job/integrator.h"
#include "wire/json.h"
#include "wire/proto_convert.h"

namespace pf {
namespace {

namespace v1 = photonfarm::v1;

struct CommandOptions {
    ServerFlags server;
    std::string job_id;
    bool json = false;
    std::string out, png, report_dir;
};

// Connects and runs `body`; one line and exit code 1 on any error.
void Run(const CommandOptions& options, int* exit_code,
         const std::function<absl::Status(FarmClient&)>& body) {
    absl::StatusOr<FarmClient> client = FarmClient::Connect(options.server);
    absl::Status status = client.ok() ? body(*client) : client.status();
    if (!status.ok()) spdlog::error("{}", std::string(status.message()));
    *exit_code = status.ok() ? 0 : 1;
}

void PrintJobRow(const v1::JobStatus& job) {
    const absl::StatusOr<Integrator> known = IntegratorFromProto(job.integrator(), "integrator");
    const std::string integrator = known.ok() ? std::string(IntegratorName(*known)) : "?";
    std::printf("%-20s %-10s %-10s %8.1f%% %10s %8d %9.1f %8d  %s\n", job.job_id().c_str(),
                StateName(job.state()).c_str(), integrator.c_str(), 100 * job.budget_fraction(),
                absl::StrCat(job.photons()).c_str(), static_cast<int>(job.epochs()),
                job.elapsed_seconds(), static_cast<int>(job.workers_active()), job.name().c_str());
}

}  // namespace

void AddJobCommands(CLI::App& app, int* exit_code) {
    auto cancel_options = std::make_shared<CommandOptions>();
    CLI::App* cancel = app.add_subcommand("cancel", "Cancel a farm job (its image so far is kept)");
    cancel->add_option("job", cancel_options->job_id, "Job id")->required();
    AddServerOption(cancel, &cancel_options->server);
    cancel->add_flag("--json", cancel_options->json, "Print the job's status as JSON");
    cancel->callback([cancel_options, exit_code] {
        Run(*cancel_options, exit_code, [&](FarmClient& client) -> absl::Status {
            absl::StatusOr<v1::JobStatus> status = client.Cancel(cancel_options->job_id);
            if (!status.ok()) return status.status();
            if (cancel_options->json)
                std::printf("%s\n", ToJson(*status).c_str());
            else
                std::printf("%s %s\n", status->job_id().c_str(),
                            StateName(status->state()).c_str());
            return absl::OkStatus();
        });
    });

    auto jobs_options = std::make_shared<CommandOptions>();
    CLI::App* jobs = app.add_subcommand("jobs", "List a farm's jobs");
    AddServerOption(jobs, &jobs_options->server);
    jobs->add_flag("--json", jobs_options->json, "Print the list as JSON");
    jobs->callback([jobs_options, exit_code] {
        Run(*jobs_options, exit_code, [&](FarmClient& client) -> absl::Status {
            absl::StatusOr<v1::ListJobsResponse> list = client.ListJobs();
            if (!list.ok()) return list.status();
            if (jobs_options->json) {
                std::printf("%s\n", ToJson(*list).c_str());
                return absl::OkStatus();
            }
            std::printf("%-20s %-10s %-10s %9s %10s %8s %9s %8s  %s\n", "JOB", "STATE",
                        "INTEGRATOR", "BUDGET", "PHOTONS", "EPOCHS", "SECONDS", "WORKERS", "NAME");
            for (const v1::JobStatus& job : list->jobs()) PrintJobRow(job);
            return absl::OkStatus();
        });
    });

    auto workers_options = std::make_shared<CommandOptions>();
    CLI::App* workers = app.add_subcommand("workers", "List the workers registered with a farm");
    AddServerOption(workers, &workers_options->server);
    workers->add_flag("--json", workers_options->json, "Print the list as JSON");
    workers->callback([workers_options, exit_code] {
        Run(*workers_options, exit_code, [&](FarmClient& client) -> absl::Status {
            absl::StatusOr<v1::ListWorkersResponse> list = client.ListWorkers();
            if (!list.ok()) return list.status();
            if (workers_options->json) {
                std::printf("%s\n", ToJson(*list).c_str());
                return absl::OkStatus();
            }
            std::printf("%-22s %-8s %7s %7s %9s %10s  %s\n", "WORKER", "BACKEND", "THREADS",
                        "LEASED", "DONE", "HEARTBEAT", "PEER");
            for (const v1::WorkerStatus& w : list->workers())
                std::printf("%-22s %-8s %7d %7d %9s %8.1f s  %s\n", w.worker_id().c_str(),
                            w.backend().c_str(), static_cast<int>(w.threads()),
                            static_cast<int>(w.batches_leased()),
                            absl::StrCat(w.batches_done()).c_str(), w.seconds_since_heartbeat(),
                            w.peer().c_str());
            return absl::OkStatus();
        });
    });

    auto result_options = std::make_shared<CommandOptions>();
    CLI::App* result =
        app.add_subcommand("result", "Fetch a farm job's image (final once the job is done)");
    result->add_option("job", result_options->job_id, "Job id")->required();
    AddServerOption(result, &result_options->server);
    result->add_option("--out", result_options->out, "Write the image here (float RGB OpenEXR)")
        ->required();
    result->add_option("--png", result_options->png, "Also write a tone-mapped PNG");
    AddReportOption(result, &result_options->report_dir);
    result->callback([result_options, exit_code] {
        absl::Status prepared = PrepareOutputs(result_options->out, result_options->png, "");
        if (prepared.ok() && !result_options->report_dir.empty())
            prepared = PrepareReportDir(result_options->report_dir);
        if (!prepared.ok()) {
            spdlog::error("{}", std::string(prepared.message()));
            *exit_code = 1;
            return;
        }
        Run(*result_options, exit_code, [&](FarmClient& client) -> absl::Status {
            absl::StatusOr<v1::GetResultResponse> response =
                client.GetResult(result_options->job_id);
            if (!response.ok()) return response.status();
            if (!response->has_image())
                return absl::NotFoundError(
                    absl::StrCat("job ", result_options->job_id, " has no image"));
            absl::StatusOr<Image> image = FromProto(response->image());
            if (!image.ok()) return image.status();
            const v1::JobStatus& status = response->status();
            if (status.state() != v1::JOB_STATE_DONE)
                spdlog::warn("job {} is {}: writing its image so far", status.job_id(),
                             StateName(status.state()));
            absl::Status written = WriteImageFiles(*image, JobMetadata(status), result_options->out,
                                                   result_options->png, 0.0f);
            if (!written.ok() || result_options->report_dir.empty()) return written;
            return WriteJobReport(client, status.job_id(), result_options->report_dir);
        });
    });

    auto health_options = std::make_shared<CommandOptions>();
    CLI::App* health = app.add_subcommand(
        "health",
        "Ask the coordinator's gRPC health service whether it serves (exit 0 if so): for probes");
    AddServerOption(health, &health_options->server);
    health->callback([health_options, exit_code] {
        Run(*health_options, exit_code, [&](FarmClient& client) -> absl::Status {
            absl::Status serving = client.CheckHealth();
            if (serving.ok()) std::printf("SERVING\n");
            return serving;
        });
    });
}

}  // namespace pf
