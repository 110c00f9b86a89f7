// Environment lights: the maps between images and directions, importance sampling whose pdf
// is the one its lookups report and whose estimates integrate the map, and photons whose flux
// through a surface is the irradiance the environment gives it.
#include "core/scene/environment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/sampling/rng.h"
#include "core/sampling/sampling.h"
#include "core/scene/emitters.h"
#include "core/scene_io/scene_loader.h"
#include "tests/support/chi_square.h"
#include "tests/support/gltf_builder.h"

namespace pf {
namespace {

// A map with texels of every scale, a few of them black.
Environment RandomMap(EnvironmentMapping mapping, int width, int height, uint64_t seed) {
    Environment environment;
    environment.mapping = mapping;
    environment.image.width = width, environment.image.height = height;
    Rng rng(seed);
    for (int i = 0; i < width * height; ++i) {
        const float u = rng.NextFloat();
        environment.image.texels.push_back(u < 0.1f ? Rgb(0.0f)
                                                    : Rgb(u, 2 * rng.NextFloat(), u * u * 10));
    }
    environment.scale = Rgb(1.5f, 1.0f, 0.5f);
    environment.to_map = RotationAboutUp(30);
    return environment;
}

TEST(EnvironmentTest, EqualAreaMapRoundTripsAndCoversTheSphereEvenly) {
    for (float y = 0.01f; y < 1; y += 0.0731f)
        for (float x = 0.005f; x < 1; x += 0.0617f) {
            const Vec3 d = EqualAreaSquareToSphere({x, y});
            EXPECT_NEAR(Length(d), 1.0f, 1e-5f);
            const Point2 back = EqualAreaSphereToSquare(d);
            EXPECT_NEAR(back.x, x, 2e-5f) << x << " " << y;
            EXPECT_NEAR(back.y, y, 2e-5f) << x << " " << y;
        }
    // Uniform points of the square land uniformly on the sphere: z is uniform in [-1, 1], and
    // each octant takes an eighth.
    Rng rng(11);
    constexpr int kPoints = 80000;
    std::vector<double> z_bins(8, 0.0), octants(8, 0.0);
    for (int i = 0; i < kPoints; ++i) {
        const Vec3 d = EqualAreaSquareToSphere({rng.NextFloat(), rng.NextFloat()});
        z_bins[std::min(7, static_cast<int>((d.z + 1) * 4))] += 1;
        octants[(d.x > 0) + 2 * (d.y > 0) + 4 * (d.z > 0)] += 1;
    }
    const std::vector<double> even(8, kPoints / 8.0);
    EXPECT_TRUE(testing::ChiSquarePasses(z_bins, even));
    EXPECT_TRUE(testing::ChiSquarePasses(octants, even));
}

TEST(EnvironmentTest, LatLongMapPutsItsCentreAheadAndItsTopUp) {
    const auto near = [](const Vec3& a, const Vec3& b) { return Length(a - b) < 1e-5f; };
    EXPECT_TRUE(near(LatLongToSphere({0.5f, 0.5f}), Vec3(0, 0, -1)));  // glTF's camera looks -z
    EXPECT_TRUE(near(LatLongToSphere({0.75f, 0.5f}), Vec3(1, 0, 0)));
    EXPECT_TRUE(near(LatLongToSphere({0.25f, 0.5f}), Vec3(-1, 0, 0)));
    EXPECT_TRUE(near(LatLongToSphere({0.3f, 0.0f}), Vec3(0, 1, 0)));
    for (float v = 0.02f; v < 1; v += 0.09f)
        for (float u = 0.01f; u < 1; u += 0.07f) {
            const Point2 back = LatLongFromSphere(LatLongToSphere({u, v}));
            EXPECT_NEAR(back.x, u, 1e-5f);
            EXPECT_NEAR(back.y, v, 1e-5f);
        }
    // --environment-rotate 90 turns the map's centre from -z to -x (counter-clockwise about +y
    // seen from above).
    Environment environment;
    environment.to_map = RotationAboutUp(90);
    EXPECT_TRUE(near(environment.ToWorld(Vec3(0, 0, -1)), Vec3(-1, 0, 0)));
    EXPECT_TRUE(near(environment.ToMap(Vec3(-1, 0, 0)), Vec3(0, 0, -1)));
}

class EnvironmentSampling : public ::testing::TestWithParam<EnvironmentMapping> {
protected:
    Environment Map() const {
        return GetParam() == EnvironmentMapping::kEqualArea
                   ? RandomMap(EnvironmentMapping::kEqualArea, 16, 16, 3)
                   : RandomMap(EnvironmentMapping::kLatLong, 24, 12, 4);
    }
};

TEST_P(EnvironmentSampling, DrawsReportThePdfAndRadianceTheirLookupsGive) {
    const Environment environment = Map();
    const EnvironmentSampler sampler(environment);
    Rng rng(5);
    constexpr int kDraws = 100000;
    int mismatched = 0;
    for (int i = 0; i < kDraws; ++i) {
        const EnvironmentSampler::Sample sample = sampler.Draw(rng.NextFloat(), rng.NextFloat());
        ASSERT_GT(sample.pdf, 0);
        ASSERT_FALSE(IsBlack(sample.radiance)) << "a black texel was drawn";
        EXPECT_NEAR(Length(sample.toward), 1.0f, 1e-5f);
        // Directions on a texel's very edge may look up its neighbour: rare.
        const float pdf = sampler.Pdf(sample.toward);
        const Rgb radiance = environment.Radiance(sample.toward);
        mismatched += std::abs(pdf - sample.pdf) > 1e-4f * sample.pdf ||
                      Length(radiance - sample.radiance) > 1e-4f * Length(sample.radiance);
    }
    EXPECT_LE(mismatched, kDraws / 1000);
}

TEST_P(EnvironmentSampling, EstimatesIntegrateTheMapAndThePdfIntegratesToOne) {
    const Environment environment = Map();
    const EnvironmentSampler sampler(environment);
    const Rgbd integral = environment.RadianceIntegral();
    Rng rng(6);
    constexpr int kDraws = 200000;
    Rgbd sum(0.0), sum_sq(0.0);
    double pdf_sum = 0, pdf_sum_sq = 0;
    for (int i = 0; i < kDraws; ++i) {
        const EnvironmentSampler::Sample sample = sampler.Draw(rng.NextFloat(), rng.NextFloat());
        const Rgbd estimate = Rgbd(sample.radiance) / double(sample.pdf);
        sum += estimate, sum_sq += estimate * estimate;
        // The pdf over the sphere, estimated with uniform directions: E[4 pi pdf] = 1.
        const double p =
            4 * kPiD * sampler.Pdf(SampleUniformSphere(rng.NextFloat(), rng.NextFloat()));
        pdf_sum += p, pdf_sum_sq += p * p;
    }
    for (int c = 0; c < 3; ++c) {
        const double mean = sum[c] / kDraws;
        const double sigma = std::sqrt((sum_sq[c] / kDraws - mean * mean) / kDraws);
        EXPECT_NEAR(mean, integral[c], 5 * sigma + 1e-6 * integral[c]) << "channel " << c;
    }
    const double pdf_mean = pdf_sum / kDraws;
    const double pdf_sigma = std::sqrt((pdf_sum_sq / kDraws - pdf_mean * pdf_mean) / kDraws);
    EXPECT_NEAR(pdf_mean, 1.0, 5 * pdf_sigma);
    // The pdf is the channels' average radiance times solid angle, normalised: the average's
    // estimate is the same for every draw, the integral itself.
    const double average_integral = (integral.x + integral.y + integral.z) / 3;
    for (int i = 0; i < 1000; ++i) {
        const EnvironmentSampler::Sample sample = sampler.Draw(rng.NextFloat(), rng.NextFloat());
        EXPECT_NEAR(Average(sample.radiance) / sample.pdf, average_integral,
                    1e-4 * average_integral);
    }
}

INSTANTIATE_TEST_SUITE_P(Maps, EnvironmentSampling,
                         ::testing::Values(EnvironmentMapping::kEqualArea,
                                           EnvironmentMapping::kLatLong),
                         [](const auto& param_info) {
                             return param_info.param == EnvironmentMapping::kEqualArea
                                        ? std::string("EqualArea")
                                        : std::string("LatLong");
                         });

// A unit quad in the plane z = 0 (LitQuadScene without its light) under `environment`.
Scene QuadUnder(const EnvironmentSettings& environment_settings, const std::string& name) {
    testing::TestScene test_scene = testing::LitQuadScene();
    test_scene.materials[1].emission = Rgb(0.0f);
    SceneLoadOptions options;
    options.environment = environment_settings;
    absl::StatusOr<Scene> scene = LoadScene(testing::WriteGltf(test_scene, name), options);
    EXPECT_TRUE(scene.ok()) << scene.status();
    return scene.ok() ? std::move(*scene) : Scene{};
}

EnvironmentSettings Grey() {
    EnvironmentSettings settings;
    settings.color = Rgb(1.0f);
    return settings;
}

// The flux photons carry through the unit quad at z = 0 from above, per emitted photon (W),
// with its standard error.
struct QuadFlux {
    Rgbd mean, sigma;
};
QuadFlux FluxThroughQuad(const Emitters& emitters, uint64_t seed, int photons) {
    Rng rng(seed);
    Rgbd sum(0.0), sum_sq(0.0);
    for (int i = 0; i < photons; ++i) {
        const EmittedPhoton photon = emitters.Emit(rng);
        const Ray& ray = photon.ray;
        Rgbd through(0.0);
        if (ray.direction.z < 0 && ray.origin.z > 0) {
            const float t = -ray.origin.z / ray.direction.z;
            const Vec3 p = ray.origin + ray.direction * t;
            if (std::abs(p.x) <= 0.5f && std::abs(p.y) <= 0.5f) through = Rgbd(photon.flux);
        }
        sum += through, sum_sq += through * through;
    }
    QuadFlux flux;
    flux.mean = sum / double(photons);
    for (int c = 0; c < 3; ++c)
        flux.sigma[c] = std::sqrt((sum_sq[c] / photons - flux.mean[c] * flux.mean[c]) / photons);
    return flux;
}

TEST(EnvironmentTest, PhotonsFromAUniformEnvironmentGiveAPlaneIrradiancePiL) {
    EnvironmentSettings settings;
    settings.color = Rgb(1.0f, 0.5f, 2.0f);
    settings.scale = 3;
    const Scene scene = QuadUnder(settings, "environment-quad.gltf");
    const Emitters emitters(scene);
    ASSERT_TRUE(emitters.HasEnvironment());
    // Power: pi R^2 x 4 pi L over the scene's bounding sphere.
    const double radius = emitters.SceneRadius();
    EXPECT_NEAR(emitters.TotalPower().y, kPiD * radius * radius * 4 * kPiD * 1.5, 1e-3);
    const QuadFlux flux = FluxThroughQuad(emitters, 7, 3000000);
    for (int c = 0; c < 3; ++c) {
        const double expected = kPiD * (*settings.color)[c] * settings.scale;  // E = pi L, A = 1
        EXPECT_NEAR(flux.mean[c], expected, 5 * flux.sigma[c]) << "channel " << c;
        EXPECT_LT(5 * flux.sigma[c], 0.02 * expected);  // a 2% error would show
    }
}

TEST(EnvironmentTest, PhotonsFromAMapGiveThePlaneTheMapsIrradiance) {
    // The irradiance a map gives the quad's upper side, by quadrature: each texel split into
    // 16 x 16 cells of equal solid angle (uniform in longitude and in cos theta).
    Scene scene = QuadUnder(Grey(), "environment-map-quad.gltf");
    scene.environment = RandomMap(EnvironmentMapping::kLatLong, 12, 6, 8);
    const Environment& environment = *scene.environment;
    Rgbd expected(0.0);
    constexpr int kCells = 16;
    for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 12; ++x) {
            const double cell = environment.TexelSolidAngle(y) / (kCells * kCells);
            const double cos0 = std::cos(kPiD * y / 6), cos1 = std::cos(kPiD * (y + 1) / 6);
            for (int j = 0; j < kCells; ++j)
                for (int i = 0; i < kCells; ++i) {
                    const double cos_theta = cos0 + (j + 0.5) / kCells * (cos1 - cos0);
                    const double sin_theta = std::sqrt(1 - cos_theta * cos_theta);
                    const double phi = 2 * kPiD * ((x + (i + 0.5) / kCells) / 12 - 0.5);
                    const Vec3 map(float(sin_theta * std::sin(phi)), float(cos_theta),
                                   float(-sin_theta * std::cos(phi)));
                    const Vec3 world = environment.ToWorld(map);
                    if (world.z > 0)
                        expected += Rgbd(environment.image.texels[y * 12 + x] * environment.scale) *
                                    (world.z * cell);
                }
        }
    const Emitters emitters(scene);
    const QuadFlux flux = FluxThroughQuad(emitters, 9, 400000);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(flux.mean[c], expected[c], 5 * flux.sigma[c] + 2e-3 * expected[c])
            << "channel " << c;
}

TEST(EnvironmentTest, DirectSamplesAgreeWithWhatAnEscapingRayFinds) {
    Scene scene = QuadUnder(Grey(), "environment-direct-quad.gltf");
    scene.environment = RandomMap(EnvironmentMapping::kEqualArea, 8, 8, 10);
    const Emitters emitters(scene);
    Rng rng(12);
    int taken = 0, mismatched = 0;
    constexpr int kSamples = 100000;
    for (int i = 0; i < kSamples; ++i) {
        LightSample sample;
        if (!emitters.SampleDirect(Vec3(0, 0, 0.1f), Vec3(0, 0, 1), rng, &sample)) continue;
        ++taken;
        EXPECT_TRUE(std::isinf(sample.shadow_ray.t_max));
        const Emitters::Hit escaped = emitters.Escaped(sample.shadow_ray.origin, sample.direction);
        mismatched += std::abs(escaped.pdf - sample.pdf) > 1e-4f * sample.pdf ||
                      Length(escaped.radiance - sample.radiance_over_pdf * sample.pdf) >
                          1e-3f * Length(escaped.radiance);
    }
    EXPECT_GT(taken, kSamples / 4);
    EXPECT_LE(mismatched, kSamples / 1000);
}

// A skylight 1.5 above the quad: a 0.6 x 0.8 portal facing up (pbrt-v4's p03 x p01 is +z).
EnvironmentPortal Skylight() {
    return *EnvironmentPortal::FromCorners({Vec3(-0.4f, -0.3f, 1.5f), Vec3(-0.4f, 0.3f, 1.5f),
                                            Vec3(0.4f, 0.3f, 1.5f), Vec3(0.4f, -0.3f, 1.5f)});
}

// The irradiance at p (normal +z) from what the environment sends through the portal, by
// midpoint quadrature over n x n cells of the portal: L cos_p cos_portal / d^2 dA.
Rgbd IrradianceThroughPortal(const Environment& environment, const Vec3& p, int n) {
    const EnvironmentPortal& portal = *environment.portal;
    const double cell = portal.Area() / (double(n) * n);
    Rgbd sum(0.0);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const Vec3 q =
                portal.corner + portal.edge_u * ((i + 0.5f) / n) + portal.edge_v * ((j + 0.5f) / n);
            const Vec3 d = q - p;
            const double distance_sq = LengthSquared(d);
            const Vec3 w = d / std::sqrt(float(distance_sq));
            sum += Rgbd(environment.Radiance(w)) *
                   (double(w.z) * Dot(w, portal.normal) / distance_sq * cell);
        }
    return sum;
}

TEST(EnvironmentTest, APortalLetsInItsWindowsLightAndOnlyThat) {
    Scene base = QuadUnder(Grey(), "environment-portal-quad.gltf");
    Environment uniform;
    uniform.scale = Rgb(1.0f, 0.5f, 2.0f);
    for (Environment environment : {uniform, RandomMap(EnvironmentMapping::kEqualArea, 8, 8, 4)}) {
        SCOPED_TRACE(environment.mapping == EnvironmentMapping::kUniform ? "uniform" : "map");
        environment.portal = Skylight();
        Scene scene = base;
        scene.environment = environment;
        const Emitters emitters(scene);
        ASSERT_TRUE(emitters.HasEnvironment());
        // Photons: all come in through the portal, and the flux they carry through the unit
        // quad is the irradiance's integral over it (quadrature over 24 x 24 points of it).
        Rgbd expected(0.0);
        constexpr int kPoints = 24;
        for (int j = 0; j < kPoints; ++j)
            for (int i = 0; i < kPoints; ++i)
                expected +=
                    IrradianceThroughPortal(
                        *scene.environment,
                        Vec3((i + 0.5f) / kPoints - 0.5f, (j + 0.5f) / kPoints - 0.5f, 0), 48) *
                    (1.0 / (kPoints * kPoints));
        const QuadFlux flux = FluxThroughQuad(emitters, 11, 4000000);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(flux.mean[c], expected[c], 5 * flux.sigma[c] + 3e-3 * expected[c])
                << "photons, channel " << c;
            EXPECT_LT(5 * flux.sigma[c], 0.02 * expected[c]);
        }
        Rng rng(13);
        for (int i = 0; i < 1000; ++i) {
            const EmittedPhoton photon = emitters.Emit(rng);
            const Vec3 q = photon.ray.origin - scene.environment->portal->corner;
            EXPECT_NEAR(q.z, 0, 1e-3f);
            // Directions drawn from a texel that is partly behind the portal may carry nothing.
            if (!IsBlack(photon.flux)) {
                EXPECT_LT(photon.ray.direction.z, 0);
            }
        }
        // Light samples at a point under it: their mean is the irradiance there, and a ray
        // that escapes toward a sample's direction finds the same radiance and density.
        const Vec3 p(0.1f, -0.2f, 0.0f);
        const Rgbd irradiance = IrradianceThroughPortal(*scene.environment, p, 200);
        Rgbd sum(0.0);
        int mismatched = 0;
        constexpr int kSamples = 200000;
        for (int i = 0; i < kSamples; ++i) {
            LightSample sample;
            if (!emitters.SampleDirect(p, Vec3(0, 0, 1), rng, &sample)) continue;
            sum += Rgbd(sample.radiance_over_pdf) * double(sample.direction.z);
            const Emitters::Hit escaped =
                emitters.Escaped(sample.shadow_ray.origin, sample.direction);
            mismatched += std::abs(escaped.pdf - sample.pdf) > 1e-3f * sample.pdf ||
                          Length(escaped.radiance - sample.radiance_over_pdf * sample.pdf) >
                              1e-3f * Length(escaped.radiance);
        }
        EXPECT_LE(mismatched, kSamples / 1000);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(sum[c] / kSamples, irradiance[c], 5e-3 * irradiance[c])
                << "light samples, channel " << c;
        // A ray that leaves beside the portal, or from outside it, finds nothing; a camera
        // ray through it sees the sky.
        EXPECT_EQ(emitters.Escaped(p, Normalize(Vec3(1, 0, 0.3f))).pdf, 0);
        EXPECT_TRUE(IsBlack(scene.environment->RadianceFrom(p, Normalize(Vec3(1, 0, 0.3f)))));
        EXPECT_TRUE(IsBlack(scene.environment->RadianceFrom(Vec3(0, 0, 2), Vec3(0, 0, 1))));
        EXPECT_FALSE(IsBlack(scene.environment->RadianceFrom(p, Vec3(0, 0, 1))));
    }
}

TEST(EnvironmentTest, APortalMustBeARectangle) {
    EXPECT_FALSE(EnvironmentPortal::FromCorners(
                     {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0.2f), Vec3(0, 1, 0)})
                     .ok());
    EXPECT_FALSE(
        EnvironmentPortal::FromCorners({Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)})
            .ok());
    const absl::StatusOr<EnvironmentPortal> portal = EnvironmentPortal::FromCorners(
        {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 3, 0), Vec3(0, 3, 0)});
    ASSERT_TRUE(portal.ok());
    EXPECT_FLOAT_EQ(portal->Area(), 6);
    EXPECT_NEAR(portal->normal.z, -1, 1e-6f);  // p03 x p01 = y x x
}

TEST(EnvironmentTest, ASceneLitOnlyByItsEnvironmentLoadsAndOneWithoutLightNamesTheWayOut) {
    testing::TestScene test_scene = testing::LitQuadScene();
    test_scene.materials[1].emission = Rgb(0.0f);
    const std::string path = testing::WriteGltf(test_scene, "environment-dark.gltf");
    const absl::StatusOr<Scene> dark = LoadScene(path);
    ASSERT_FALSE(dark.ok());
    EXPECT_NE(dark.status().message().find(path), std::string::npos) << dark.status();
    EXPECT_NE(dark.status().message().find("no light"), std::string::npos) << dark.status();
    EXPECT_NE(dark.status().message().find("--environment"), std::string::npos) << dark.status();
    SceneLoadOptions options;
    options.environment.color = Rgb(0.2f);
    const absl::StatusOr<Scene> lit = LoadScene(path, options);
    ASSERT_TRUE(lit.ok()) << lit.status();
    ASSERT_TRUE(lit->environment.has_value());
    EXPECT_EQ(lit->environment->mapping, EnvironmentMapping::kUniform);
    options.environment.file = "missing.exr";
    options.environment.color.reset();
    const absl::StatusOr<Scene> missing = LoadScene(path, options);
    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.status().message().find("missing.exr"), std::string::npos);
}

}  // namespace
}  // namespace pf
