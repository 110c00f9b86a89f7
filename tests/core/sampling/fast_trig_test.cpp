// The polynomial sin/cos against libm over the unit interval and its quadrant boundaries.
#include "core/sampling/fast_trig.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pf {
namespace {

TEST(FastTrigTest, MatchesLibmOverAFullTurn) {
    double worst = 0;
    for (int i = 0; i <= 1 << 20; ++i) {
        const float u = static_cast<float>(i) / (1 << 20) * 0.99999994f;
        float s, c;
        SinCosTurns(u, &s, &c);
        const double angle = 2 * M_PI * static_cast<double>(u);
        worst = std::max({worst, std::abs(s - std::sin(angle)), std::abs(c - std::cos(angle))});
    }
    EXPECT_LT(worst, 4e-7);
}

TEST(FastTrigTest, QuadrantsHaveTheRightSigns) {
    const float cases[][3] = {{0.0f, 0.0f, 1.0f},
                              {0.25f, 1.0f, 0.0f},
                              {0.5f, 0.0f, -1.0f},
                              {0.75f, -1.0f, 0.0f},
                              {0.125f, 0.70710678f, 0.70710678f},
                              {0.625f, -0.70710678f, -0.70710678f}};
    for (const auto& [u, sine, cosine] : cases) {
        float s, c;
        SinCosTurns(u, &s, &c);
        EXPECT_NEAR(s, sine, 4e-7f) << u;
        EXPECT_NEAR(c, cosine, 4e-7f) << u;
    }
}

}  // namespace
}  // namespace pf
