// Initial radii from a pilot photon map: in the white furnace the photons that scattered before
// cover the walls evenly, so every hit point's R0 is the one the map's density gives in closed
// form, sqrt(c / (pi rho M)); where photons are denser R0 is smaller by the square root; every
// R0 keeps to its bounds, and a slot without a footprint keeps the fallback.
#include "core/pm/density_radii.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/camera/camera_pass.h"
#include "core/pm/photon_map.h"
#include "tests/support/lit_scene.h"

namespace pf {
namespace {

// Points on the floor (y = -1) of the furnace, away from its edges, facing up.
std::vector<HitPoint> FloorPoints() {
    std::vector<HitPoint> points;
    for (int i = 0; i < 16; ++i)
        for (int j = 0; j < 16; ++j)
            points.push_back({Vec3(-0.75f + 0.1f * i, -1, -0.75f + 0.1f * j), Vec3(0, 1, 0),
                              Rgb(0.5f / std::numbers::pi_v<float>), 0});
    return points;
}

double Median(std::vector<float> values) {
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    return values[values.size() / 2];
}

// The furnace tests' settings: 2^22 photons a first epoch, seed 5, the bounds out of the way.
DensityRadiiSettings UnboundedSettings() {
    DensityRadiiSettings settings;
    settings.first_epoch_photons = 1u << 22;
    settings.seed = 5;
    settings.most_footprints = 1000;
    settings.least_footprints = 0.001;
    settings.most_diagonal = 1;
    return settings;
}

TEST(DensityRadiiTest, FurnaceRadiiFollowThePhotonDensityInClosedForm) {
    const std::unique_ptr<const testing::LitScene> lit = testing::LoadLitScene("furnace.gltf");
    ASSERT_NE(lit, nullptr);
    const testing::LitScene& furnace = *lit;
    const std::vector<HitPoint> points = FloorPoints();
    const std::vector<float> footprint(points.size(), 0.01f);
    DensityRadiiSettings settings = UnboundedSettings();
    // The pilot's global map, as DensityInitialRadii builds it: its photons per unit area and
    // photon emitted over the furnace's 24 m^2 of walls (the furnace has no caustics).
    PhotonMapSettings pilot;
    pilot.global_photons = pilot.caustic_photons = settings.pilot_photons;
    const PhotonMaps maps = BuildPhotonMaps(furnace.scene, *furnace.emitters, *furnace.tracer,
                                            furnace.features, pilot, settings.seed);
    ASSERT_GT(maps.global->Photons().size(), 10000u);
    const double density =
        double(maps.global->Photons().size()) / (double(maps.global_emitted) * 24.0);
    const double expected = std::sqrt(settings.first_epoch_photons_found /
                                      (std::numbers::pi * density * settings.first_epoch_photons));
    const std::vector<float> radii =
        DensityInitialRadii(furnace.scene, *furnace.emitters, *furnace.tracer, furnace.features,
                            points, footprint, 0.5f, settings);
    // k-nearest densities scatter by about 1 / sqrt(k) a point; their median is within a few
    // percent of the density (k = 16: the median disc holds k - 1/3 photons).
    EXPECT_NEAR(Median(radii) / expected, 1.0, 0.05) << "expected R0 " << expected;
    // Four times the photons an epoch: half the radius.
    settings.first_epoch_photons *= 4;
    const std::vector<float> quarter =
        DensityInitialRadii(furnace.scene, *furnace.emitters, *furnace.tracer, furnace.features,
                            points, footprint, 0.5f, settings);
    for (size_t i = 0; i < radii.size(); ++i) EXPECT_NEAR(quarter[i] / radii[i], 0.5, 1e-5);
}

// The radii rpm asks for every epoch, from photons counted per grid cell rather than the k
// nearest: on the furnace's floor (a surface along the axes, where a cell's face is its area)
// the same closed form, within the cells' counting noise (some 20 photons a cell: 1/sqrt(20)
// a point, a few percent for the median); and each of its hit points gathering every photon
// (rpm's gather hits), the global map holds the photons' first landings too, twice the photons
// at albedo 1/2 (1 / (1 - rho) landings a photon rather than rho / (1 - rho)): radii 1/sqrt(2)
// of ppm's.
TEST(DensityRadiiTest, CellRadiiFollowThePhotonDensityAsTheNearestDo) {
    const std::unique_ptr<const testing::LitScene> lit = testing::LoadLitScene("furnace.gltf");
    ASSERT_NE(lit, nullptr);
    const testing::LitScene& furnace = *lit;
    std::vector<HitPoint> points = FloorPoints();
    const std::vector<float> footprint(points.size(), 0.01f);
    DensityRadiiSettings settings = UnboundedSettings();
    const DensityRadii scattered(furnace.scene, *furnace.emitters, *furnace.tracer,
                                 furnace.features, /*everything=*/false, settings, /*cells=*/true);
    const double nearest = Median(scattered.Radii(points, footprint, 0.5f));
    const double cells = Median(scattered.CellRadii(points, footprint, 0.5f));
    EXPECT_NEAR(cells / nearest, 1.0, 0.08);
    for (HitPoint& point : points) point.gathers = kAllPhotons;
    const DensityRadii everything(furnace.scene, *furnace.emitters, *furnace.tracer,
                                  furnace.features, /*everything=*/true, settings, /*cells=*/true);
    EXPECT_NEAR(Median(everything.CellRadii(points, footprint, 0.5f)) / cells, std::sqrt(0.5),
                0.06);
    // Caustics alone where there are none: no radius.
    for (HitPoint& point : points) point.gathers = kCausticPhoton;
    for (const float radius : everything.CellRadii(points, footprint, 0.5f)) EXPECT_EQ(radius, 0);
}

TEST(DensityRadiiTest, RadiiKeepToTheirBoundsAndEmptySlotsKeepTheFallback) {
    const std::unique_ptr<const testing::LitScene> lit = testing::LoadLitScene("furnace.gltf");
    ASSERT_NE(lit, nullptr);
    const testing::LitScene& furnace = *lit;
    std::vector<HitPoint> points = FloorPoints();
    std::vector<float> footprint(points.size());
    for (size_t i = 0; i < footprint.size(); ++i) footprint[i] = 1e-4f * float(1 + i % 7);
    footprint[3] = 0;  // a stochastic pass's empty slot
    DensityRadiiSettings settings;
    settings.seed = 5;
    for (const uint64_t photons : {uint64_t{1} << 10, uint64_t{1} << 50}) {
        settings.first_epoch_photons = photons;  // R0 pushed to the top, then the bottom
        const std::vector<float> radii =
            DensityInitialRadii(furnace.scene, *furnace.emitters, *furnace.tracer, furnace.features,
                                points, footprint, 0.25f, settings);
        for (size_t i = 0; i < radii.size(); ++i) {
            if (footprint[i] == 0) {
                EXPECT_EQ(radii[i], 0.25f);
                continue;
            }
            const float bound = photons < (uint64_t{1} << 20) ? 8 * footprint[i]  // most
                                                              : 0.25f * footprint[i];
            EXPECT_FLOAT_EQ(radii[i], bound) << i;
        }
        EXPECT_GT(MedianRadius(radii, footprint), 0);
    }
}

}  // namespace
}  // namespace pf
