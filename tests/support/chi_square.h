// Pearson's chi-square goodness-of-fit test for the sampling tests.
#pragma once

#include <span>

namespace pf::testing {

// True if observed counts are consistent with expected counts at significance level
// `significance` (e.g. 1e-4). Bins with small expected counts are pooled first, as usual.
bool ChiSquarePasses(std::span<const double> observed, std::span<const double> expected,
                     double significance = 1e-4);

}  // namespace pf::testing
