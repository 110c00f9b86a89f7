// The stiff and extreme cases of docs/numerics.md as a table: each case's criterion, what it
// measured, the bound, and whether it passed. Exit code 1 if any failed.
#include <spdlog/spdlog.h>

#include <cstdio>

#include "tests/support/numerics_cases.h"

int main() {
    spdlog::set_level(spdlog::level::warn);  // the table, not the renders' progress
    int failed = 0;
    std::printf("%-10s %-34s %12s %12s  %-4s  %s\n", "group", "case", "measured", "bound", "pass",
                "criterion");
    for (const pf::testing::NumericsCase& c : pf::testing::NumericsCases()) {
        const pf::testing::NumericsResult result = c.run();
        const bool passed = result.Passed();
        failed += !passed;
        std::printf("%-10s %-34s %12.4g %12.4g  %-4s  %s%s%s\n", c.group.c_str(), c.name.c_str(),
                    result.measured, result.bound, passed ? "yes" : "NO", c.criterion.c_str(),
                    result.detail.empty() ? "" : " -- ", result.detail.c_str());
        std::fflush(stdout);
    }
    return failed == 0 ? 0 : 1;
}
