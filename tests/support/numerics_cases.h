// The stiff and extreme cases of docs/numerics.md, each with its pass criterion stated and its
// measurement returned: run one by one by tests/integration/numerics_test.cpp, and all in a
// row by bench/numerics_report, which prints them as a table.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace pf::testing {

struct NumericsResult {
    double measured = 0;  // the quantity the criterion bounds
    double bound = 0;     // pass when measured <= bound (and `ok`)
    bool ok = true;  // everything else the case checks held (finite images, monotone radii, ...)
    std::string detail;  // what failed, or a note on what was seen
    bool Passed() const { return ok && measured <= bound; }
};

struct NumericsCase {
    std::string group;      // stiff, scale, power, estimator
    std::string name;       // unique, usable as a test name
    std::string criterion;  // the pass criterion in words, with its derivation's result
    std::function<NumericsResult()> run;
};

std::vector<NumericsCase> NumericsCases();

}  // namespace pf::testing
