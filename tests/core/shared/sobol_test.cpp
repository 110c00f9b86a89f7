// The scrambled (0,2)-sequence (core/shared/sobol.h): Sobol's second dimension, that Owen
// scrambling keeps nets nets, that the index shuffle moves aligned runs whole, and that every
// aligned run of 2^m points is a (0,m,2)-net whatever the seeds.
#include "core/shared/sobol.h"

#include <gtest/gtest.h>

#include <set>
#include <vector>

namespace pf::gpu {
namespace {

TEST(SobolTest, SecondDimensionIsSobols) {
    // Sobol's second dimension in eighths, in index order (the textbook's 0 4 6 2 3 7 5 1 is
    // the same points in Gray-code order).
    const int expected[] = {0, 4, 6, 2, 5, 1, 3, 7};
    for (uint32_t i = 0; i < 8; ++i)
        EXPECT_EQ(SobolSecondDimension(i), uint32_t(expected[i]) << 29) << "index " << i;
    EXPECT_EQ(ReverseBits32(1u), 0x80000000u);
    EXPECT_EQ(ReverseBits32(0x12345678u), 0x1e6a2c48u);
}

TEST(SobolTest, ShuffleMovesAlignedRunsWhole) {
    for (uint32_t seed : {0u, 1u, 0xdeadbeefu, 0x9e3779b9u})
        for (int m : {1, 3, 6})
            for (uint32_t run = 0; run < 16; ++run) {
                std::set<uint32_t> runs;
                for (uint32_t i = run << m; i < (run + 1) << m; ++i)
                    runs.insert(OwenScramble(i, seed) >> m);
                EXPECT_EQ(runs.size(), 1u) << "seed " << seed << ", m " << m << ", run " << run;
            }
}

// Whether the 2^m points hold one each of the elementary intervals 2^-a by 2^-(m - a), for
// every a.
bool IsNet(const std::vector<vec2>& points, int m) {
    for (int a = 0; a <= m; ++a) {
        const int columns = 1 << a, rows = 1 << (m - a);
        std::vector<int> count(size_t(1) << m, 0);
        for (const vec2& p : points) {
            const int column = static_cast<int>(p.x * columns), row = static_cast<int>(p.y * rows);
            if (++count[size_t(row) * columns + column] > 1) return false;
        }
    }
    return true;
}

TEST(SobolTest, EveryAlignedRunIsANet) {
    for (uint32_t seed = 0; seed < 8; ++seed) {
        const uint32_t sx = seed * 0x9e3779b9u, sy = seed * 0x85ebca6bu + 1,
                       shuffle = seed * 0xc2b2ae35u + 7;
        for (int m = 0; m <= 10; ++m)
            for (uint32_t run : {0u, 1u, 5u}) {
                std::vector<vec2> points;
                for (uint32_t i = run << m; i < (run + 1) << m; ++i)
                    points.push_back(ScrambledSobol2D(i, sx, sy, shuffle));
                EXPECT_TRUE(IsNet(points, m)) << "seed " << seed << ", m " << m << ", run " << run;
            }
    }
}

TEST(SobolTest, ScramblesAreUniform) {
    // Point 0 over many seeds: uniform in the square (mean 1/2, variance 1/12 per coordinate),
    // where unscrambled it would always be (0, 0).
    constexpr int kSeeds = 1 << 16;
    double sum_x = 0, sum_y = 0, sum_xy = 0;
    for (uint32_t seed = 0; seed < kSeeds; ++seed) {
        const vec2 p = ScrambledSobol2D(0, seed * 0x9e3779b9u, seed * 0x85ebca6bu + 1, seed);
        sum_x += p.x, sum_y += p.y, sum_xy += (p.x - 0.5) * (p.y - 0.5);
    }
    const double sigma = std::sqrt(1.0 / 12 / kSeeds);
    EXPECT_NEAR(sum_x / kSeeds, 0.5, 5 * sigma);
    EXPECT_NEAR(sum_y / kSeeds, 0.5, 5 * sigma);
    EXPECT_NEAR(sum_xy / kSeeds, 0.0, 5 * (1.0 / 12) / std::sqrt(double(kSeeds)));
}

}  // namespace
}  // namespace pf::gpu
