// Logger, --log-level and parse errors, shared by the three executables.
#include "core/util/command_line.h"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <cstdio>

namespace pf {

void SetUpLogging(const std::string& program) {
    spdlog::set_default_logger(spdlog::stderr_color_mt(program));
    spdlog::set_pattern(program + ": %^%l%$: %v");
}

void AddLogLevelOption(CLI::App& app) {
    app.add_option_function<std::string>(
           "--log-level", [](const std::string& level) { spdlog::set_level(spdlog::level::from_str(level)); },
           "trace, debug, info, warn, error or off (default info)")
        ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}));
}

std::optional<int> ParseCommandLine(CLI::App& app, int argc, char** argv, const std::string& program) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& error) {
        if (error.get_exit_code() == 0) return app.exit(error);  // --help
        std::fprintf(stderr, "%s: error: %s (see --help)\n", program.c_str(), error.what());
        return 2;
    }
    return std::nullopt;
}

}  // namespace pf
