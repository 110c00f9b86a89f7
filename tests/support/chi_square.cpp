// Chi-square statistic with bin pooling and the Wilson-Hilferty approximation of its
// distribution (accurate to well under 1% in the tail for the tens of degrees of freedom used).
#include "tests/support/chi_square.h"

#include <cmath>
#include <vector>

namespace pf::testing {

bool ChiSquarePasses(std::span<const double> observed, std::span<const double> expected,
                     double significance) {
    constexpr double kMinExpected = 5.0;
    double statistic = 0, pooled_observed = 0, pooled_expected = 0;
    int bins = 0;
    for (size_t i = 0; i < observed.size(); ++i) {
        if (expected[i] < kMinExpected) {
            pooled_observed += observed[i];
            pooled_expected += expected[i];
            continue;
        }
        statistic += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
        ++bins;
    }
    if (pooled_expected > 0) {
        statistic += (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) /
                     pooled_expected;
        ++bins;
    }
    const double dof = bins - 1;
    if (dof < 1) return false;
    // Wilson & Hilferty 1931: (X/k)^(1/3) is nearly normal with mean 1 - 2/(9k), var 2/(9k).
    const double z = (std::cbrt(statistic / dof) - (1 - 2 / (9 * dof))) / std::sqrt(2 / (9 * dof));
    const double p_value = 0.5 * std::erfc(z / std::sqrt(2.0));
    return p_value > significance;
}

}  // namespace pf::testing
