// Stiff and extreme cases (docs/numerics.md): each case of tests/support/numerics_cases.h as
// one test, passing when its stated criterion holds and, for a criterion about a mean (the
// stiff, scale and power cases), failing when the same criterion is applied to the case's own
// measurement given a known 2% bias: a criterion that passed those could not catch one.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "tests/support/numerics_cases.h"

namespace pf::testing {
namespace {

class Numerics : public ::testing::TestWithParam<NumericsCase> {};

TEST_P(Numerics, MeetsItsCriterion) {
    const NumericsCase& c = GetParam();
    const NumericsResult result = c.run();
    RecordProperty("measured", std::to_string(result.measured));
    RecordProperty("bound", std::to_string(result.bound));
    RecordProperty("detail", result.detail);
    EXPECT_TRUE(result.ok) << c.name << ": " << result.detail;
    EXPECT_LE(result.measured, result.bound)
        << c.name << " (" << c.criterion << "): " << result.detail;
    if (c.group == "stiff" || c.group == "scale" || c.group == "power") {
        EXPECT_GT(result.biased_checks, 0) << c.name << " must show that a 2% bias fails it";
    }
    EXPECT_EQ(result.biased_that_passed, "")
        << c.name << ": its criterion passed a measurement biased so (" << c.criterion
        << "; measured " << result.measured << ", bound " << result.bound << ")";
}

INSTANTIATE_TEST_SUITE_P(Cases, Numerics, ::testing::ValuesIn(NumericsCases()),
                         [](const ::testing::TestParamInfo<NumericsCase>& param) {
                             std::string name = param.param.group + "_" + param.param.name;
                             std::replace_if(
                                 name.begin(), name.end(),
                                 [](char ch) { return !std::isalnum(ch); }, '_');
                             return name;
                         });

}  // namespace
}  // namespace pf::testing
