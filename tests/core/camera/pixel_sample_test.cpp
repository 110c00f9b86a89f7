// Where a pixel's camera samples fall (core/camera/pixel_sample.h): for every count k a pixel
// takes an epoch, its samples over the epochs tile the pixel evenly (with a ceil(sqrt(k))^2
// grid and k not a square, the bottom of every pixel was once never sampled), its lens pair
// independent of its pixel pair, and the same numbers for the same (seed, pixel, index).
#include "core/camera/pixel_sample.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace pf {
namespace {

TEST(PixelSampleTest, EveryCountTilesThePixelOverTheEpochs) {
    // 64 even and 64 odd epochs of k samples: k of each half in each of 8 x 8 cells.
    constexpr int kEpochs = 128, kCells = 8;
    for (const int k : {1, 2, 3, 4, 5, 6, 7, 8, 9, 12, 17}) {
        std::vector<int> even(kCells * kCells, 0), odd(kCells * kCells, 0);
        for (uint64_t epoch = 0; epoch < kEpochs; ++epoch)
            for (int s = 0; s < k; ++s) {
                PixelSampler sampler = PixelSampler::InEpoch(42, 7, 1234, epoch, k, s);
                const Point2 p = sampler.Next2D();
                ASSERT_TRUE(p.x >= 0 && p.x < 1 && p.y >= 0 && p.y < 1);
                ++(epoch % 2 == 0 ? even : odd)[static_cast<int>(p.y * kCells) * kCells +
                                                static_cast<int>(p.x * kCells)];
            }
        for (int cell = 0; cell < kCells * kCells; ++cell) {
            EXPECT_EQ(even[cell], k) << "k " << k << ", cell " << cell;
            EXPECT_EQ(odd[cell], k) << "k " << k << ", cell " << cell;
        }
    }
}

TEST(PixelSampleTest, EvenAndOddEpochsAreIndependentSequences) {
    // The first sample of epochs 0 and 1 over many pixels: uncorrelated (one sequence would put
    // them in opposite halves of the pixel, a correlation of -3/4 in each coordinate... here
    // none).
    constexpr int kPixels = 1 << 16;
    double cross = 0;
    for (uint64_t pixel = 0; pixel < kPixels; ++pixel) {
        const Point2 a = PixelSampler::InEpoch(9, 7, pixel, 0, 1, 0).Next2D();
        const Point2 b = PixelSampler::InEpoch(9, 7, pixel, 1, 1, 0).Next2D();
        cross += (a.x - 0.5) * (b.x - 0.5);
    }
    EXPECT_NEAR(cross / kPixels, 0.0, 5.0 / 12 / std::sqrt(double(kPixels)));
}

TEST(PixelSampleTest, OneEpochsSamplesSpreadOverThePixel) {
    // Two samples an epoch: one in each half of the pixel, both ways; four: one per quadrant.
    for (uint64_t pixel = 0; pixel < 100; ++pixel)
        for (uint64_t epoch = 0; epoch < 10; ++epoch) {
            const Point2 a = PixelSampler::InEpoch(3, 7, pixel, epoch, 2, 0).Next2D(),
                         b = PixelSampler::InEpoch(3, 7, pixel, epoch, 2, 1).Next2D();
            EXPECT_NE(a.x < 0.5f, b.x < 0.5f);
            EXPECT_NE(a.y < 0.5f, b.y < 0.5f);
            int quadrants = 0;
            for (int s = 0; s < 4; ++s) {
                const Point2 p = PixelSampler::InEpoch(3, 7, pixel, epoch, 4, s).Next2D();
                quadrants |= 1 << ((p.x >= 0.5f) + 2 * (p.y >= 0.5f));
            }
            EXPECT_EQ(quadrants, 15) << "pixel " << pixel << ", epoch " << epoch;
        }
}

TEST(PixelSampleTest, PairsAndPixelsAreIndependent) {
    // Over many pixels' sample 0: the lens pair uncorrelated with the pixel pair, and the
    // pixel pair uniform (each pixel has scrambles of its own).
    constexpr int kPixels = 1 << 16;
    double mean_x = 0, cross = 0;
    for (uint64_t pixel = 0; pixel < kPixels; ++pixel) {
        PixelSampler sampler(9, 7, pixel, 0);
        const Point2 position = sampler.Next2D(), lens = sampler.Next2D();
        mean_x += position.x;
        cross += (position.x - 0.5) * (lens.x - 0.5) + (position.y - 0.5) * (lens.y - 0.5);
    }
    EXPECT_NEAR(mean_x / kPixels, 0.5, 5 * std::sqrt(1.0 / 12 / kPixels));
    EXPECT_NEAR(cross / kPixels, 0.0, 5 * std::sqrt(2.0) / 12 / std::sqrt(double(kPixels)));
}

TEST(PixelSampleTest, TheSameKeyGivesTheSameSample) {
    PixelSampler a(5, 7, 99, 1000), b(5, 7, 99, 1000), other_seed(6, 7, 99, 1000),
        other_stream(5, 8, 99, 1000);
    const Point2 pa = a.Next2D(), pb = b.Next2D();
    EXPECT_EQ(pa.x, pb.x);
    EXPECT_EQ(pa.y, pb.y);
    const Point2 po = other_seed.Next2D(), ps = other_stream.Next2D();
    EXPECT_TRUE(po.x != pa.x || po.y != pa.y);
    EXPECT_TRUE(ps.x != pa.x || ps.y != pa.y);
}

}  // namespace
}  // namespace pf
