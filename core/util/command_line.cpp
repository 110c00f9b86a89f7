// Logger, --log-level and parse errors, shared by the three executables.
#include "core/util/command_line.h"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace pf {
namespace {

// A validator over the option's text read as a double: `check` says what is wrong, or "".
CLI::Validator NumberValidator(const std::string& description,
                               std::function<std::string(double)> check) {
    return CLI::Validator(
        [check = std::move(check)](std::string& text) -> std::string {
            char* end = nullptr;
            const double value = std::strtod(text.c_str(), &end);
            if (end == text.c_str() || *end != '\0') return "must be a number, not '" + text + "'";
            if (!std::isfinite(value)) return "must be a finite number, not '" + text + "'";
            return check(value);
        },
        description);
}

std::string Format(double value) {
    std::ostringstream out;
    out << value;
    return out.str();
}

}  // namespace

CLI::Validator FiniteNumber() {
    return NumberValidator("FINITE", [](double) { return std::string(); });
}

CLI::Validator FinitePositive() {
    return NumberValidator(
        "POSITIVE", [](double value) { return value > 0 ? std::string() : "must be positive"; });
}

CLI::Validator FiniteRange(double low, double high) {
    return NumberValidator(
        "[" + Format(low) + " - " + Format(high) + "]", [low, high](double value) {
            return value >= low && value <= high
                       ? std::string()
                       : "must lie in [" + Format(low) + ", " + Format(high) + "]";
        });
}

void SetUpLogging(const std::string& program) {
    spdlog::set_default_logger(spdlog::stderr_color_mt(program));
    spdlog::set_pattern(program + ": %^%l%$: %v");
}

void AddLogLevelOption(CLI::App& app) {
    app.add_option_function<std::string>(
           "--log-level",
           [](const std::string& level) { spdlog::set_level(spdlog::level::from_str(level)); },
           "trace, debug, info, warn, error or off (default info)")
        ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}));
}

std::optional<int> ParseCommandLine(CLI::App& app, int argc, char** argv,
                                    const std::string& program) {
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
