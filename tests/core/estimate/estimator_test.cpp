// The progressive estimate's update rule (Hachisuka et al. 2008, eq. 7-10) on ordinary and
// edge-case inputs.
#include "core/estimate/estimator.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/job/job_spec.h"
#include "core/sampling/rng.h"

namespace pf {
namespace {

bool Finite(const PointEstimate& e) {
    return std::isfinite(e.photon_count) && std::isfinite(e.radius_sq) && IsFinite(e.flux);
}

TEST(EstimatorTest, NoNewPhotonsLeavesTheEstimateUnchanged) {
    const PointEstimate before{12.0, 0.25, Rgbd(1, 2, 3)};
    const PointEstimate after = UpdateEstimate(before, 0.0, Rgbd(5.0), kDefaultAlpha);
    EXPECT_EQ(after.photon_count, before.photon_count);
    EXPECT_EQ(after.radius_sq, before.radius_sq);
    EXPECT_EQ(after.flux, before.flux);
}

TEST(EstimatorTest, FirstPassKeepsAlphaOfThePhotonsAndShrinksTheAreaByAlpha) {
    const PointEstimate after = UpdateEstimate({0.0, 4.0, Rgbd(0.0)}, 30.0, Rgbd(6.0), 0.5);
    EXPECT_DOUBLE_EQ(after.photon_count, 15.0);
    EXPECT_DOUBLE_EQ(after.radius_sq, 2.0);
    EXPECT_DOUBLE_EQ(after.flux.x, 3.0);  // tau scales with the area
}

TEST(EstimatorTest, GeneralUpdateMatchesTheEquations) {
    const double n = 100, m = 50, alpha = 0.7, r2 = 0.01;
    const PointEstimate after = UpdateEstimate({n, r2, Rgbd(2.0)}, m, Rgbd(1.0), alpha);
    const double ratio = (n + alpha * m) / (n + m);
    EXPECT_DOUBLE_EQ(after.photon_count, n + alpha * m);
    EXPECT_DOUBLE_EQ(after.radius_sq, r2 * ratio);
    EXPECT_DOUBLE_EQ(after.flux.y, 3.0 * ratio);
}

TEST(EstimatorTest, AlphaOneNeverShrinksTheRadius) {
    PointEstimate estimate{0.0, 1.0, Rgbd(0.0)};
    for (int pass = 0; pass < 100; ++pass)
        estimate = UpdateEstimate(estimate, 10.0, Rgbd(1.0), 1.0);
    EXPECT_EQ(estimate.radius_sq, 1.0);
    EXPECT_DOUBLE_EQ(estimate.photon_count, 1000.0);
    EXPECT_DOUBLE_EQ(estimate.flux.x, 100.0);
}

TEST(EstimatorTest, RadiusStopsAtItsFloorAndTheEstimateGoesOnAtThatRadius) {
    // Every pass finds 1000 photons however small R is (a caustic's focus): with alpha 0.01
    // R^2 would fall a hundredfold per pass; the floor stops it, and from there tau grows by
    // the new flux unshrunk, a density estimate of fixed radius.
    constexpr double kFloor = 1e-12;
    PointEstimate estimate{0.0, 1.0, Rgbd(0.0)};
    for (int pass = 0; pass < 100; ++pass) {
        const PointEstimate next = UpdateEstimate(estimate, 1000.0, Rgbd(1.0), 0.01, kFloor);
        ASSERT_LE(next.radius_sq, estimate.radius_sq);
        ASSERT_GE(next.radius_sq, kFloor);
        estimate = next;
    }
    EXPECT_DOUBLE_EQ(estimate.radius_sq, kFloor);
    const PointEstimate after = UpdateEstimate(estimate, 1000.0, Rgbd(1.0), 0.01, kFloor);
    EXPECT_EQ(after.radius_sq, kFloor);
    EXPECT_DOUBLE_EQ(after.flux.x, estimate.flux.x + 1.0);
    EXPECT_TRUE(IsFinite(EstimateRadiance(after, 1e6)));
}

TEST(EstimatorTest, AlphaNearZeroStaysFiniteAndPositive) {
    PointEstimate estimate{0.0, 1.0, Rgbd(0.0)};
    for (int pass = 0; pass < 200; ++pass) {
        estimate = UpdateEstimate(estimate, 1000.0, Rgbd(1.0), 1e-9);
        ASSERT_TRUE(Finite(estimate));
        ASSERT_GE(estimate.radius_sq, 0.0);
    }
    EXPECT_LT(estimate.radius_sq, 1e-6);
    // The radiance estimate, tau / R^2, must not blow up as R^2 underflows.
    EXPECT_TRUE(IsFinite(EstimateRadiance(estimate, 1e6)));
}

TEST(EstimatorTest, RadiusNeverGrowsAndDensityIsPreservedByTheShrink) {
    Rng rng(3);
    PointEstimate estimate{0.0, 0.04, Rgbd(0.0)};
    for (int pass = 0; pass < 1000; ++pass) {
        const double m = std::floor(rng.NextFloat() * 20);
        const Rgbd phi(m * 0.1);
        const PointEstimate next = UpdateEstimate(estimate, m, phi, kDefaultAlpha);
        ASSERT_LE(next.radius_sq, estimate.radius_sq);
        if (m > 0) {
            // tau'/R'^2 == (tau + Phi)/R^2: the shrink moves flux with area, not density.
            ASSERT_NEAR(next.flux.x / next.radius_sq,
                        (estimate.flux.x + phi.x) / estimate.radius_sq,
                        1e-9 * (estimate.flux.x + phi.x) / estimate.radius_sq);
        }
        estimate = next;
    }
}

TEST(EstimatorTest, CountsBeyondTwoToTheFortyStayExactAndFinite) {
    const double n = std::ldexp(1.0, 41), m = std::ldexp(1.0, 40);
    const PointEstimate after = UpdateEstimate({n, 1e-6, Rgbd(1e12)}, m, Rgbd(5e11), 0.5);
    EXPECT_EQ(after.photon_count, n + 0.5 * m);  // exact in double below 2^53
    EXPECT_TRUE(Finite(after));
    const Rgbd radiance = EstimateRadiance(after, std::ldexp(1.0, 45));
    EXPECT_TRUE(IsFinite(radiance));
    EXPECT_GT(radiance.x, 0.0);
}

TEST(EstimatorTest, RadianceIsZeroBeforeAnyPhotonAndNeverNaN) {
    EXPECT_EQ(EstimateRadiance({0.0, 1.0, Rgbd(0.0)}, 0.0), Rgbd(0.0));
    EXPECT_EQ(EstimateRadiance({5.0, 0.0, Rgbd(1.0)}, 10.0), Rgbd(0.0));
    const Rgbd radiance = EstimateRadiance({10.0, 2.0, Rgbd(kPiD * 2.0)}, 4.0);
    EXPECT_DOUBLE_EQ(radiance.x, 0.25);  // tau / (pi R^2 N_emitted)
}

}  // namespace
}  // namespace pf
