// The photon maps' searches and density estimates: the kd-tree and the grid find exactly the
// nearest photons brute force finds, every filter estimates a uniform density without bias,
// and maps that will not fit are refused naming the flags.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "core/pm/density_estimate.h"
#include "core/pm/photon_grid.h"
#include "core/pm/photon_kdtree.h"
#include "core/pm/photon_map.h"

namespace pf {
namespace {

// Photons spread uniformly over the unit square at z = 0 and the unit square at x = 0 (two
// walls meeting at an edge), arriving from +z and +x, each of power `power`.
std::vector<StoredPhoton> WallPhotons(size_t count, uint32_t seed, float power = 1.0f) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<StoredPhoton> photons;
    for (size_t i = 0; i < count; ++i) {
        const float a = u(random), b = u(random);
        if (i % 2 == 0)
            photons.push_back({{a, b, 0.0f}, {0, 0, -1}, Rgb(power)});
        else
            photons.push_back({{0.0f, a, b}, {-1, 0, 0}, Rgb(power)});
    }
    return photons;
}

std::vector<float> NearestDistances(const PhotonLookup& lookup, const Vec3& p, uint32_t k,
                                    float max_sq) {
    NearestPhotons nearest;
    lookup.Nearest(p, k, max_sq, nearest);
    std::vector<float> distances;
    for (const auto& entry : nearest.entries) distances.push_back(entry.distance_sq);
    std::sort(distances.begin(), distances.end());
    return distances;
}

TEST(PhotonLookupTest, KdTreeAndGridFindWhatBruteForceFinds) {
    const std::vector<StoredPhoton> photons = WallPhotons(20000, 1);
    const PhotonKdTree tree(photons);
    const PhotonGrid grid(photons, GridCellSize(photons.size(), 2.0, 16, 0.2f));
    std::mt19937 random(2);
    std::uniform_real_distribution<float> u(-0.1f, 1.1f);
    for (int q = 0; q < 300; ++q) {
        const Vec3 p(u(random) * 0.3f, u(random), u(random));
        const uint32_t k = q % 3 == 0 ? 1 : 16;
        const float max_sq = q % 5 == 0 ? 1e-4f : 0.04f;  // some searches end at the limit
        std::vector<float> expected;
        for (const StoredPhoton& photon : photons) {
            const float d = LengthSquared(photon.position - p);
            if (d < max_sq) expected.push_back(d);
        }
        std::sort(expected.begin(), expected.end());
        if (expected.size() > k) expected.resize(k);
        EXPECT_EQ(NearestDistances(tree, p, k, max_sq), expected) << "kd-tree, query " << q;
        EXPECT_EQ(NearestDistances(grid, p, k, max_sq), expected) << "grid, query " << q;
    }
}

TEST(PhotonLookupTest, TheDiscReachesTheKthPhotonOrTheLimit) {
    const PhotonKdTree tree(WallPhotons(1000, 3));
    NearestPhotons nearest;
    tree.Nearest({0.5f, 0.5f, 0.0f}, 8, 1.0f, nearest);
    ASSERT_EQ(nearest.entries.size(), 8u);
    const float farthest =
        std::max_element(nearest.entries.begin(), nearest.entries.end())->distance_sq;
    EXPECT_EQ(nearest.RadiusSq(), farthest);
    tree.Nearest({5.0f, 5.0f, 5.0f}, 8, 0.01f, nearest);
    EXPECT_TRUE(nearest.entries.empty());
    EXPECT_EQ(nearest.RadiusSq(), 0.01f)
        << "too few photons: the estimate's disc is the search's limit";
}

class FilterTest : public ::testing::TestWithParam<DensityFilter> {};

TEST_P(FilterTest, EstimatesAUniformDensityWithoutBias) {
    // 400k photons of power 1/400k each on a unit square at z = 0: irradiance 1 W/m^2 (the
    // other wall's photons arrive from behind a point on this one and must be left out), so a
    // diffuse surface of albedo 0.6 reflects L = 0.6 / pi.
    constexpr size_t kPhotons = 800000;
    const PhotonKdTree tree(WallPhotons(kPhotons, 4, 2.0f / kPhotons));
    std::mt19937 random(5);
    std::uniform_real_distribution<float> u(0.2f, 0.8f);
    NearestPhotons scratch;
    double sum = 0;
    constexpr int kQueries = 2000;
    for (int q = 0; q < kQueries; ++q) {
        const Vec3 p(u(random), u(random), 0.0f);
        sum += Average(EstimateDiffuseRadiance(tree, p, {0, 0, 1}, Rgb(0.6f), 64, 0.01f, GetParam(),
                                               false, scratch));
    }
    // k = 64 photons give each estimate about 1/8 relative noise; 2000 of them, partly
    // sharing photons, average it to well under 1%.
    EXPECT_NEAR(sum / kQueries, 0.6 / kPiD, 0.015 * 0.6 / kPiD) << DensityFilterName(GetParam());
}

INSTANTIATE_TEST_SUITE_P(Filters, FilterTest,
                         ::testing::Values(DensityFilter::kBox, DensityFilter::kCone,
                                           DensityFilter::kGaussian),
                         [](const auto& param_info) {
                             return std::string(DensityFilterName(param_info.param));
                         });

TEST(PhotonMapMemoryTest, MapsThatWillNotFitAreRefusedNamingTheFlags) {
    PhotonMapSettings settings;
    settings.global_photons = 1'000'000'000;
    const PhotonMapForecast forecast{2.5, 0.1, uint64_t{100} << 30};
    const absl::Status status = CheckPhotonMapsFit(forecast, settings, uint64_t{16} << 30);
    EXPECT_EQ(status.code(), absl::StatusCode::kResourceExhausted);
    EXPECT_NE(status.message().find("--pm-photons"), std::string::npos) << status.message();
    EXPECT_NE(status.message().find("ppm, sppm"), std::string::npos)
        << "it names the way out: " << status.message();
    EXPECT_TRUE(
        CheckPhotonMapsFit({2.5, 0.1, uint64_t{1} << 30}, settings, uint64_t{16} << 30).ok());
    EXPECT_GT(AvailableMemoryBytes(), uint64_t{1} << 26);
}

}  // namespace
}  // namespace pf
