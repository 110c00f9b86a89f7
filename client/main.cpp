// photonfarm: the client command line. One file per subcommand or family of them (render;
// submit and watch; compare; cancel, jobs, workers, result and health in job_commands); this
// one parses and dispatches.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <optional>

#include "client/compare_command.h"
#include "client/job_commands.h"
#include "client/render_command.h"
#include "client/submit_command.h"
#include "core/util/allocator.h"
#include "core/util/command_line.h"
#include "wire/rpc_status.h"

int main(int argc, char** argv) {
    pf::KeepLargeBuffersForReuse();
    try {
        CLI::App app{"photonfarm: progressive photon mapping, on one machine or a render farm"};
        app.require_subcommand(1);
        app.fallthrough();  // global options such as --log-level may follow the subcommand
        pf::AddLogLevelOption(app);
        int exit_code = 0;
        pf::AddRenderCommand(app, &exit_code);
        pf::AddSubmitCommand(app, &exit_code);
        pf::AddWatchCommand(app, &exit_code);
        pf::AddJobCommands(app, &exit_code);
        pf::AddCompareCommand(app, &exit_code);
        pf::SetUpLogging("photonfarm");
        pf::SetUpGrpc();
        if (std::optional<int> parse_exit = pf::ParseCommandLine(app, argc, argv, "photonfarm"))
            return *parse_exit;
        return exit_code;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "photonfarm: error: %s\n", error.what());
        return 1;
    }
}
