// The stiff and extreme cases of docs/numerics.md as a table: each case's criterion, what it
// measured, the bound, whether it passed, and whether the criterion failed the measurement
// given a known 2% bias ("fails": as it must; "-": not a criterion about a mean). Exit code 1
// if any case failed or passed a biased measurement.
#include <spdlog/spdlog.h>

#include <cstdio>
#include <string>

#include "tests/support/numerics_cases.h"

int main() {
    spdlog::set_level(spdlog::level::warn);  // the table, not the renders' progress
    int failed = 0;
    std::printf("%-10s %-34s %12s %12s  %-4s  %-8s  %s\n", "group", "case", "measured", "bound",
                "pass", "2% bias", "criterion");
    for (const pf::testing::NumericsCase& c : pf::testing::NumericsCases()) {
        const pf::testing::NumericsResult result = c.run();
        const bool passed = result.Passed() && result.biased_that_passed.empty();
        failed += !passed;
        const std::string bias = result.biased_checks == 0           ? "-"
                                 : result.biased_that_passed.empty() ? "fails"
                                                                     : "PASSES";
        std::printf("%-10s %-34s %12.4g %12.4g  %-4s  %-8s  %s%s%s%s\n", c.group.c_str(),
                    c.name.c_str(), result.measured, result.bound, result.Passed() ? "yes" : "NO",
                    bias.c_str(), c.criterion.c_str(), result.detail.empty() ? "" : " -- ",
                    result.detail.c_str(),
                    result.biased_that_passed.empty()
                        ? ""
                        : (" -- biased and passed: " + result.biased_that_passed).c_str());
        std::fflush(stdout);
    }
    return failed == 0 ? 0 : 1;
}
