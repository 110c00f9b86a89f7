// photonfarm: the client command line. One file per subcommand; this one parses and dispatches.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "client/compare_command.h"
#include "client/job_commands.h"
#include "client/render_command.h"
#include "client/submit_command.h"
#include "core/util/allocator.h"

int main(int argc, char** argv) {
    pf::KeepLargeBuffersForReuse();
    try {
        CLI::App app{"photonfarm: progressive photon mapping, on one machine or a render farm"};
        app.require_subcommand(1);
        app.fallthrough();  // global options such as --log-level may follow the subcommand
        std::string log_level = "info";
        app.add_option("--log-level", log_level, "trace, debug, info, warn, error or off")
            ->default_val("info")->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}));
        app.parse_complete_callback([&] { spdlog::set_level(spdlog::level::from_str(log_level)); });
        int exit_code = 0;
        pf::AddRenderCommand(app, &exit_code);
        pf::AddSubmitCommand(app, &exit_code);
        pf::AddWatchCommand(app, &exit_code);
        pf::AddJobCommands(app, &exit_code);
        pf::AddCompareCommand(app, &exit_code);
        // Logs and errors go to stderr, one line each; stdout stays free for results.
        spdlog::set_default_logger(spdlog::stderr_color_mt("photonfarm"));
        spdlog::set_pattern("photonfarm: %^%l%$: %v");
        try {
            app.parse(argc, argv);
        } catch (const CLI::CallForHelp& help) {
            return app.exit(help);
        } catch (const CLI::CallForAllHelp& help) {
            return app.exit(help);
        } catch (const CLI::ParseError& error) {
            std::fprintf(stderr, "photonfarm: error: %s (see --help)\n", error.what());
            return 2;
        }
        return exit_code;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "photonfarm: error: %s\n", error.what());
        return 1;
    }
}
