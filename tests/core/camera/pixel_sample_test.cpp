// Where a pixel's camera samples fall (core/camera/pixel_sample.h): for every count k, k cells
// of equal area that tile the pixel, so that no part of a pixel goes unsampled (with a
// ceil(sqrt(k))^2 grid and k not a square, the bottom cells were never used).
#include "core/camera/pixel_sample.h"

#include <gtest/gtest.h>

#include <vector>

namespace pf {
namespace {

TEST(PixelSampleTest, EveryCountTilesThePixelWithCellsOfEqualArea) {
    for (const int k : {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 12, 15, 16, 17, 31, 64}) {
        // Each cell: the rectangle from jitter (0, 0) to jitter (1, 1).
        double area = 0;
        std::vector<Point2> low(k), high(k);
        for (int s = 0; s < k; ++s) {
            low[s] = PixelSampleOffset(k, s, 0, 0), high[s] = PixelSampleOffset(k, s, 1, 1);
            const double cell = double(high[s].x - low[s].x) * double(high[s].y - low[s].y);
            EXPECT_NEAR(cell, 1.0 / k, 1e-6) << "k " << k << ", sample " << s;
            area += cell;
        }
        EXPECT_NEAR(area, 1.0, 1e-5) << "k " << k;
        // Every point of a fine grid over the pixel lies in exactly one cell.
        constexpr int kGrid = 97;
        for (int i = 0; i < kGrid; ++i) {
            for (int j = 0; j < kGrid; ++j) {
                const float x = (i + 0.5f) / kGrid, y = (j + 0.5f) / kGrid;
                int inside = 0;
                for (int s = 0; s < k; ++s)
                    inside += x >= low[s].x && x < high[s].x && y >= low[s].y && y < high[s].y;
                ASSERT_EQ(inside, 1) << "k " << k << " at " << x << ", " << y;
            }
        }
    }
}

TEST(PixelSampleTest, ASquareCountIsTheSquareGrid) {
    const Point2 p = PixelSampleOffset(9, 5, 0.25f, 0.5f);  // column 2, row 1 of 3 x 3
    EXPECT_NEAR(p.x, (2 + 0.25f) / 3, 1e-6f);
    EXPECT_NEAR(p.y, (1 + 0.5f) / 3, 1e-6f);
}

}  // namespace
}  // namespace pf
