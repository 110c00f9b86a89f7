// Logger, --log-level and parse errors, shared by the three executables.
#include "core/util/command_line.h"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <cctype>
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
            const std::string problem = check(value);
            return problem.empty() ? problem : problem + ", not '" + text + "'";
        },
        description);
}

std::string Format(double value) {
    std::ostringstream out;
    out << value;
    return out.str();
}

// A count as the user would write it back: 20000000 as 20M, where exact.
std::string FormatCount(uint64_t value) {
    static constexpr std::pair<uint64_t, const char*> kUnits[] = {
        {1'000'000'000'000, "T"}, {1'000'000'000, "G"}, {1'000'000, "M"}, {1'000, "k"}};
    for (const auto& [unit, name] : kUnits)
        if (value >= unit && value % unit == 0) return std::to_string(value / unit) + name;
    return std::to_string(value);
}

// Whole numbers are parsed exactly, in 128 bits: 24 digits times the largest unit stay far
// below 2^127, and every uint64 and int64 fits.
__extension__ typedef __int128 Whole;

// Why `text` is not a whole number, or "" when it is. Accepts [-]digits[.digits][unit], the
// sign only where `allow_sign`, the fraction and unit only where `allow_units`; the value must
// come out whole ("1.5k" is 1500, "1.0005k" is refused).
std::string ParseWhole(const std::string& text, bool allow_sign, bool allow_units, Whole* value) {
    size_t i = 0;
    const bool negative = allow_sign && !text.empty() && text[0] == '-';
    if (negative) ++i;
    Whole integer = 0, fraction = 0, fraction_scale = 1;
    const size_t digits_begin = i;
    for (; i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])); ++i)
        integer = integer * 10 + (text[i] - '0');
    if (i == digits_begin) return "not a number";
    if (i - digits_begin > 24) return "too many digits";
    if (allow_units && i < text.size() && text[i] == '.') {
        const size_t fraction_begin = ++i;
        for (; i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])); ++i) {
            fraction = fraction * 10 + (text[i] - '0');
            fraction_scale *= 10;
        }
        if (i == fraction_begin) return "not a number";
        if (i - fraction_begin > 12) return "too many digits";
    }
    Whole unit = 1;
    if (i < text.size()) {
        const std::string suffix = text.substr(i);
        if (!allow_units || suffix.size() != 1)
            return allow_units && std::isalpha(static_cast<unsigned char>(suffix[0]))
                       ? "unknown unit '" + suffix + "' (k, M, G or T)"
                       : "not a number";
        switch (std::tolower(static_cast<unsigned char>(suffix[0]))) {
            case 'k':
                unit = 1'000;
                break;
            case 'm':
                unit = 1'000'000;
                break;
            case 'g':
                unit = 1'000'000'000;
                break;
            case 't':
                unit = 1'000'000'000'000;
                break;
            default:
                return "unknown unit '" + suffix + "' (k, M, G or T)";
        }
    }
    if (fraction * unit % fraction_scale != 0) return "not a whole number";
    *value = (integer * unit + fraction * unit / fraction_scale) * (negative ? -1 : 1);
    return "";
}

// A validator of whole numbers in [low, high], rewriting the text to the plain integer for
// CLI11 to convert.
CLI::Validator WholeValidator(const std::string& description, Whole low, Whole high,
                              bool allow_units, const std::string& range) {
    return CLI::Validator(
        [=](std::string& text) -> std::string {
            Whole value = 0;
            const std::string problem = ParseWhole(text, low < 0, allow_units, &value);
            const std::string refusal =
                (allow_units ? "must be a count in " : "must be a whole number in ") + range +
                ", not '" + text + "'";
            if (!problem.empty()) return refusal + ": " + problem;
            if (value < low || value > high) return refusal;
            text = value < 0 ? "-" + std::to_string(static_cast<uint64_t>(-value))
                             : std::to_string(static_cast<uint64_t>(value));
            return std::string();
        },
        description);
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

CLI::Validator WholeNumber(uint64_t low, uint64_t high) {
    return WholeValidator("UINT", Whole{low}, Whole{high}, /*allow_units=*/false,
                          "[" + std::to_string(low) + ", " + std::to_string(high) + "]");
}

CLI::Validator SignedWholeNumber(int64_t low, int64_t high) {
    return WholeValidator("INT", Whole{low}, Whole{high}, /*allow_units=*/false,
                          "[" + std::to_string(low) + ", " + std::to_string(high) + "]");
}

CLI::Validator CountWithUnit(uint64_t low, uint64_t high) {
    return WholeValidator("COUNT", Whole{low}, Whole{high}, /*allow_units=*/true,
                          "[" + FormatCount(low) + ", " + FormatCount(high) +
                              "] (k, M, G, T: 10^3, 10^6, 10^9, 10^12)");
}

CLI::Validator HostAndPort(int lowest_port) {
    const std::string range = "[" + std::to_string(lowest_port) + ", 65535]";
    return CLI::Validator(
        [=](std::string& text) -> std::string {
            const size_t colon = text.rfind(':');
            const std::string expected = "must be HOST:PORT with a port in " + range;
            if (colon == std::string::npos || colon == 0) return expected + ", not '" + text + "'";
            const std::string host = text.substr(0, colon), port = text.substr(colon + 1);
            // An IPv6 host has colons of its own, and brackets around them.
            if (host.find(':') != std::string::npos && !(host.front() == '[' && host.back() == ']'))
                return expected + " (an IPv6 host in brackets), not '" + text + "'";
            Whole value = 0;
            if (!ParseWhole(port, /*allow_sign=*/false, /*allow_units=*/false, &value).empty() ||
                value < lowest_port || value > 65535)
                return expected + ", not port '" + port + "'";
            return std::string();
        },
        "HOST:PORT");
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
