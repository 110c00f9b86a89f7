// Sampling routines against their stated densities (chi-square) and the RNG's basic contract.
#include "core/sampling/sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/sampling/distribution.h"
#include "core/sampling/rng.h"
#include "tests/support/chi_square.h"

namespace pf {
namespace {

constexpr int kSamples = 400000;

TEST(RngTest, FloatsLieInUnitIntervalAndStreamsDiffer) {
    Rng a(HashSeed(1, 2, 3)), b(HashSeed(1, 2, 4));
    int equal = 0;
    for (int i = 0; i < 10000; ++i) {
        const float u = a.NextFloat();
        ASSERT_GE(u, 0.0f);
        ASSERT_LT(u, 1.0f);
        equal += a.NextUint() == b.NextUint();
    }
    EXPECT_LT(equal, 5);
}

TEST(SamplingTest, CosineHemisphereMatchesCosineDensity) {
    // Under p = cos(theta)/pi, cos^2(theta) and phi are independent and uniform.
    constexpr int kThetaBins = 10, kPhiBins = 20;
    std::vector<double> observed(kThetaBins * kPhiBins, 0.0);
    Rng rng(7);
    for (int i = 0; i < kSamples; ++i) {
        const Vec3 d = SampleCosineHemisphere(rng.NextFloat(), rng.NextFloat());
        ASSERT_NEAR(Length(d), 1.0f, 1e-5f);
        ASSERT_GE(d.z, 0.0f);
        const int t = std::min(kThetaBins - 1, static_cast<int>(d.z * d.z * kThetaBins));
        const float phi = std::atan2(d.y, d.x) + kPi;
        const int p = std::min(kPhiBins - 1, static_cast<int>(phi / (2 * kPi) * kPhiBins));
        observed[t * kPhiBins + p] += 1;
    }
    const std::vector<double> expected(observed.size(), double(kSamples) / observed.size());
    EXPECT_TRUE(testing::ChiSquarePasses(observed, expected));
}

TEST(SamplingTest, UniformConeMatchesSolidAngle) {
    constexpr int kBins = 16;
    const float cos_max = 0.6f;
    std::vector<double> observed(kBins, 0.0);
    Rng rng(11);
    for (int i = 0; i < kSamples; ++i) {
        const Vec3 d = SampleUniformCone(rng.NextFloat(), rng.NextFloat(), cos_max);
        ASSERT_GE(d.z, cos_max - 1e-6f);
        // Solid angle is linear in cos(theta): equal-width bins in cos(theta) are equally likely.
        observed[std::min(kBins - 1, static_cast<int>((1 - d.z) / (1 - cos_max) * kBins))] += 1;
    }
    const std::vector<double> expected(kBins, double(kSamples) / kBins);
    EXPECT_TRUE(testing::ChiSquarePasses(observed, expected));
}

TEST(SamplingTest, UniformTriangleCoversAreaEvenly) {
    // Bin the triangle (0,0),(1,0),(0,1) into a grid; each bin's expected share is its area.
    constexpr int kGrid = 12;
    std::vector<double> observed(kGrid * kGrid, 0.0), expected(kGrid * kGrid, 0.0);
    Rng rng(13);
    for (int i = 0; i < kSamples; ++i) {
        const Point2 b = SampleUniformTriangle(rng.NextFloat(), rng.NextFloat());
        ASSERT_LE(b.x + b.y, 1.0f + 1e-6f);
        observed[std::min(kGrid - 1, int(b.x * kGrid)) * kGrid +
                 std::min(kGrid - 1, int(b.y * kGrid))] += 1;
    }
    // Area of each cell inside the triangle, by fine midpoint integration.
    constexpr int kFine = 60;
    for (int x = 0; x < kGrid * kFine; ++x)
        for (int y = 0; y < kGrid * kFine; ++y)
            if ((x + 0.5) + (y + 0.5) < kGrid * kFine)
                expected[(x / kFine) * kGrid + y / kFine] += 1;
    double total = 0;
    for (double e : expected) total += e;
    for (double& e : expected) e *= kSamples / total;
    EXPECT_TRUE(testing::ChiSquarePasses(observed, expected));
}

TEST(SamplingTest, DiscreteDistributionFollowsWeightsAndSkipsZeros) {
    const std::vector<double> weights = {1.0, 0.0, 3.0, 0.5, 0.0, 5.5};
    DiscreteDistribution distribution(weights);
    std::vector<double> observed(weights.size(), 0.0), expected(weights.size(), 0.0);
    Rng rng(17);
    for (int i = 0; i < kSamples; ++i) {
        const auto sample = distribution.Draw(rng.NextFloat());
        ASSERT_GT(weights[sample.index], 0.0);
        EXPECT_DOUBLE_EQ(sample.probability, weights[sample.index] / 10.0);
        observed[sample.index] += 1;
    }
    for (size_t i = 0; i < weights.size(); ++i) expected[i] = kSamples * weights[i] / 10.0;
    std::vector<double> nonzero_observed, nonzero_expected;
    for (size_t i = 0; i < weights.size(); ++i)
        if (weights[i] > 0)
            nonzero_observed.push_back(observed[i]), nonzero_expected.push_back(expected[i]);
    EXPECT_TRUE(testing::ChiSquarePasses(nonzero_observed, nonzero_expected));
    EXPECT_EQ(distribution.Draw(0.0f).index, 0u);
    EXPECT_EQ(distribution.Draw(0.99999994f).index, 5u);
}

TEST(SamplingTest, ChiSquareRejectsAWrongDensity) {
    // The test itself must have power: uniform hemisphere samples fail the cosine test.
    constexpr int kBins = 10;
    std::vector<double> observed(kBins, 0.0);
    Rng rng(19);
    for (int i = 0; i < kSamples; ++i) {
        const Vec3 d = SampleUniformSphere(rng.NextFloat(), rng.NextFloat());
        const float z = std::abs(d.z);
        observed[std::min(kBins - 1, static_cast<int>(z * z * kBins))] += 1;
    }
    const std::vector<double> expected(kBins, double(kSamples) / kBins);
    EXPECT_FALSE(testing::ChiSquarePasses(observed, expected));
}

}  // namespace
}  // namespace pf
