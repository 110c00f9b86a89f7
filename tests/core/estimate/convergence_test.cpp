// The convergence log's fits and CSV.
#include "core/estimate/convergence.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace pf {
namespace {

TEST(ConvergenceTest, FitPowerLawRecoversAnExactPowerLaw) {
    std::vector<double> x, y;
    for (double v = 1e3; v <= 1e7; v *= 1.7) {
        x.push_back(v);
        y.push_back(3.5 * std::pow(v, -1.0 / 3.0));
    }
    const std::optional<PowerLaw> fit = FitPowerLaw(x, y);
    ASSERT_TRUE(fit.has_value());
    EXPECT_NEAR(fit->slope, -1.0 / 3.0, 1e-12);
    EXPECT_NEAR(std::exp(fit->log_scale), 3.5, 1e-9);
}

TEST(ConvergenceTest, FitPowerLawSkipsUnusablePairsAndRefusesTooFew) {
    // Zero, negative, NaN and Inf values are left out; what remains is an exact y = x^-1/2.
    const std::vector<double> x = {0, 1, 4, -2, 16, NAN, 64, 100};
    const std::vector<double> y = {1, 1, 0.5, 1, 0.25, 1, 0.125, INFINITY};
    const std::optional<PowerLaw> fit = FitPowerLaw(x, y);
    ASSERT_TRUE(fit.has_value());
    EXPECT_NEAR(fit->slope, -0.5, 1e-12);
    EXPECT_FALSE(FitPowerLaw(std::vector<double>{5}, std::vector<double>{1}).has_value());
    EXPECT_FALSE(
        FitPowerLaw(std::vector<double>{5, 5, 5}, std::vector<double>{1, 2, 3}).has_value());
}

TEST(ConvergenceTest, FitsLeaveOutTheFirstEpochsAndMissingErrors) {
    // Points past kFitSkipEpochs follow RMSE = photons^-0.4 (estimated) and photons^-0.3
    // (measured); the earlier ones are wild and must not count.
    std::vector<ConvergencePoint> points;
    for (uint64_t epoch = 1; epoch <= 40; ++epoch) {
        ConvergencePoint point;
        point.epochs = epoch;
        point.photons = epoch * 1000;
        point.seconds = 0.5 * static_cast<double>(epoch);
        const double n = static_cast<double>(point.photons);
        const bool early = epoch <= kFitSkipEpochs;
        if (epoch >= 2) point.estimated = ErrorEstimate{true, early ? 100.0 : std::pow(n, -0.4), 0};
        point.measured = ImageDifference{early ? 100.0 : std::pow(n, -0.3)};
        points.push_back(point);
    }
    const ConvergenceFits fits = FitConvergence(points);
    ASSERT_TRUE(fits.estimated_vs_photons && fits.measured_vs_photons && fits.measured_vs_seconds);
    EXPECT_NEAR(fits.estimated_vs_photons->slope, -0.4, 1e-12);
    EXPECT_NEAR(fits.measured_vs_photons->slope, -0.3, 1e-12);
    EXPECT_NEAR(fits.measured_vs_seconds->slope, -0.3,
                1e-12);  // seconds proportional to photons here
}

TEST(ConvergenceTest, LogStaysBoundedSpreadOverTheRunAndEndsAtTheLatestEpoch) {
    ConvergenceLog log;
    constexpr uint64_t kLongRunEpochs = 100'003;
    for (uint64_t epoch = 1; epoch <= kLongRunEpochs; ++epoch) {
        ConvergencePoint point;
        point.epochs = epoch;
        log.Add(point);
        ASSERT_LE(log.Points().size(), ConvergenceLog::kMaxPoints + 1) << "epoch " << epoch;
        ASSERT_EQ(log.Points().back().epochs, epoch) << "the latest epoch is always there";
    }
    const std::vector<ConvergencePoint>& points = log.Points();
    EXPECT_GT(points.size(), ConvergenceLog::kMaxPoints / 2);
    // Evenly spread: a stride of 32 epochs (100003 / 4096 rounded up to a power of two), then the
    // latest.
    for (size_t i = 0; i + 1 < points.size(); ++i) ASSERT_EQ(points[i].epochs, 32 * (i + 1));
}

TEST(ConvergenceTest, CsvHasOneRowPerPointAndEmptyCellsWhereUnknown) {
    ConvergencePoint first{1.25, 1, 4096, std::nullopt, std::nullopt, 64};
    ConvergencePoint second{
        2.5, 2, 8192, ErrorEstimate{true, 0.02, 0.0004, 0.01}, ImageDifference{0.03, 0.0009},
        64,  9};
    second.measured->nonfinite_pixels = 16;
    const std::vector<ConvergencePoint> points = {first, second};
    EXPECT_EQ(ConvergenceCsv(points),
              "seconds,epochs,photons,estimated_rmse,estimated_rel_error,estimated_bias_rmse,"
              "reference_rmse,"
              "reference_rel_mse,reference_rel_error,reference_nonfinite_fraction,camera_samples\n"
              "1.250000,1,4096,,,,,,,,0\n"
              "2.500000,2,8192,0.02,0.02,0.01,0.03,0.0009,0.03,0.25,9\n");
    EXPECT_FALSE(WorkIsCameraSamples(points)) << "photons grow: a photon mapper's log";
}

TEST(ConvergenceTest, LogsWithoutGrowingPhotonsAreMeasuredInCameraSamples) {
    // The path tracer traces no photons, classic photon mapping all of its maps' before its
    // first epoch: their fits and plots run against camera samples.
    std::vector<ConvergencePoint> points;
    for (uint64_t epoch = 1; epoch <= 8; ++epoch) {
        const double error = 0.1 / std::sqrt(double(epoch));
        points.push_back({double(epoch), epoch, 0, ErrorEstimate{true, error, error * error, 0},
                          std::nullopt, 64, epoch * 1000});
    }
    EXPECT_TRUE(WorkIsCameraSamples(points));
    const ConvergenceFits fits = FitConvergence(points);
    ASSERT_TRUE(fits.estimated_vs_photons.has_value());
    EXPECT_NEAR(fits.estimated_vs_photons->slope, -0.5, 1e-9)
        << "error against camera samples falls as 1/sqrt(n)";
    for (ConvergencePoint& point : points) point.photons = 2'000'000;  // a pm job's maps
    EXPECT_TRUE(WorkIsCameraSamples(points));
}

}  // namespace
}  // namespace pf
