// Emitters: photons leave each light in proportion to its power, carry the scene's total
// power on average, and direct-light samples integrate to the known irradiance.
#include "core/scene/emitters.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/scene_io/scene_loader.h"
#include "tests/support/chi_square.h"
#include "tests/support/gltf_builder.h"

namespace pf {
namespace {

TEST(EmittersTest, AreaLightPowerIsPiTimesAreaTimesRadiance) {
    const absl::StatusOr<Scene> scene =
        LoadScene(testing::WriteGltf(testing::LitQuadScene(), "emit-quad.gltf"));
    ASSERT_TRUE(scene.ok()) << scene.status();
    const Emitters emitters(*scene);
    // A 0.4 x 0.4 quad of radiance 10: pi * 0.16 * 10.
    EXPECT_NEAR(emitters.TotalPower().x, kPiD * 0.16 * 10.0, 1e-4);
}

TEST(EmittersTest, PhotonsLeaveLightsInProportionToPowerAndCarryTheTotal) {
    testing::TestScene test_scene = testing::LitQuadScene();
    // Intensities in candela, 683 to the watt: 1 and 3 W/sr.
    test_scene.lights = {R"({"type":"point","intensity":683})",
                         R"({"type":"point","intensity":2049})"};
    const absl::StatusOr<Scene> scene =
        LoadScene(testing::WriteGltf(test_scene, "emit-mixed.gltf"));
    ASSERT_TRUE(scene.ok()) << scene.status();
    const Emitters emitters(*scene);
    // Emitters: 2 area triangles (power pi*0.08*10 each), point lights 4 pi and 12 pi.
    const double powers[] = {kPiD * 0.8, kPiD * 0.8, 4 * kPiD, 12 * kPiD};
    const double total = powers[0] + powers[1] + powers[2] + powers[3];
    EXPECT_NEAR(emitters.TotalPower().x, total, 1e-3);
    Rng rng(1);
    constexpr int kPhotons = 200000;
    std::vector<double> observed(2, 0.0);  // from the area light, from the point lights
    double flux_sum = 0;
    for (int i = 0; i < kPhotons; ++i) {
        const EmittedPhoton photon = emitters.Emit(rng);
        flux_sum += photon.flux.x;
        observed[std::abs(photon.ray.origin.z - 1.0f) < 1e-3f ? 0 : 1] += 1;
    }
    const std::vector<double> expected = {kPhotons * (powers[0] + powers[1]) / total,
                                          kPhotons * (powers[2] + powers[3]) / total};
    EXPECT_TRUE(testing::ChiSquarePasses(observed, expected));
    // Each photon carries its light's power over its selection probability: the total on average.
    EXPECT_NEAR(flux_sum / kPhotons, total, 1e-3 * total);
}

TEST(EmittersTest, DirectSamplesIntegrateToThePointLightIrradiance) {
    testing::TestScene test_scene = testing::LitQuadScene();
    test_scene.materials[1].emission = Rgb(0.0f);
    test_scene.lights = {R"({"type":"point","intensity":1366})"};  // 2 W/sr
    const absl::StatusOr<Scene> scene =
        LoadScene(testing::WriteGltf(test_scene, "emit-point.gltf"));
    ASSERT_TRUE(scene.ok()) << scene.status();
    const Emitters emitters(*scene);
    Rng rng(2);
    LightSample sample;
    // A receiver at distance 2 below the light, facing it: E = I cos / d^2 = 2 / 4.
    ASSERT_TRUE(emitters.SampleDirect(Vec3(0, 0, -2), Vec3(0, 0, 1), rng, &sample));
    EXPECT_NEAR(sample.radiance_over_pdf.x * Dot(sample.direction, Vec3(0, 0, 1)), 0.5f, 1e-4f);
    // Facing away: no light.
    EXPECT_FALSE(emitters.SampleDirect(Vec3(0, 0, -2), Vec3(0, 0, -1), rng, &sample));
}

TEST(EmittersTest, AreaLightDirectSamplesConvergeToTheAnalyticIrradiance) {
    const absl::StatusOr<Scene> scene =
        LoadScene(testing::WriteGltf(testing::LitQuadScene(), "emit-area.gltf"));
    ASSERT_TRUE(scene.ok()) << scene.status();
    const Emitters emitters(*scene);
    // Irradiance at the centre below a square of half-side a at height h with radiance L:
    // E = 4 L [ a / sqrt(a^2 + h^2) atan(a / sqrt(a^2 + h^2)) ] (four corner rectangles).
    const double a = 0.2, h = 1.0, radiance = 10.0;
    const double s = a / std::sqrt(a * a + h * h);
    const double expected = 4 * radiance * s * std::atan(s);
    Rng rng(3);
    double sum = 0, sum_sq = 0;
    constexpr int kSamples = 200000;
    LightSample sample;
    for (int i = 0; i < kSamples; ++i) {
        double value = 0;
        if (emitters.SampleDirect(Vec3(0, 0, 0), Vec3(0, 0, 1), rng, &sample))
            value = sample.radiance_over_pdf.x * Dot(sample.direction, Vec3(0, 0, 1));
        sum += value;
        sum_sq += value * value;
    }
    const double mean = sum / kSamples;
    const double standard_error = std::sqrt((sum_sq / kSamples - mean * mean) / kSamples);
    EXPECT_NEAR(mean, expected, 5 * standard_error + 1e-4 * expected);
}

// A unit square at z = 1 emitting Le downward, (u, v) = (x, y), with `texture` as its
// emission texture (none where it has no texels), over nothing.
Scene SquareLight(Rgb radiance, const Texture& texture) {
    Scene scene;
    scene.positions = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
    scene.uvs = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
    scene.normals.assign(4, Vec3(0.0f));
    scene.triangles = {{{0, 3, 1}, 0, false, {0, 0, -1}}, {{0, 2, 3}, 0, false, {0, 0, -1}}};
    Material material;
    material.emission = radiance;
    if (!texture.texels.empty()) {
        material.emission_texture = 0;
        scene.textures.push_back(std::make_shared<const Texture>(texture));
    }
    scene.materials = {material};
    for (const Vec3& p : scene.positions) scene.bounds.Extend(p);
    scene.bounds.Extend({0, 0, 0});
    return scene;
}

TEST(EmittersTest, ASingleTexelTextureEmitsAsItsColourDoesUntextured) {
    // Emission (2, 4, 1) x a texture of one texel (0.5, 0.25, 1) is emission (1, 1, 1): the
    // same power, photons, light samples and hits, value for value.
    const Texture texel{1, 1, {Rgb(0.5f, 0.25f, 1.0f)}};
    const Scene textured = SquareLight(Rgb(2.0f, 4.0f, 1.0f), texel);
    const Scene plain = SquareLight(Rgb(1.0f), Texture{});
    const Emitters a(textured), b(plain);
    EXPECT_EQ(a.TotalPower().x, b.TotalPower().x);
    EXPECT_EQ(a.TotalPower().y, b.TotalPower().y);
    EXPECT_EQ(a.TotalPower().z, b.TotalPower().z);
    Rng rng_a(7), rng_b(7);
    for (int i = 0; i < 1000; ++i) {
        const EmittedPhoton pa = a.Emit(rng_a), pb = b.Emit(rng_b);
        ASSERT_EQ(pa.flux, pb.flux);
        ASSERT_EQ(pa.ray.origin, pb.ray.origin);
        LightSample sa, sb;
        const Vec3 receiver(0.3f, 0.6f, 0.0f);
        ASSERT_EQ(a.SampleDirect(receiver, {0, 0, 1}, rng_a, &sa),
                  b.SampleDirect(receiver, {0, 0, 1}, rng_b, &sb));
        ASSERT_EQ(sa.radiance_over_pdf, sb.radiance_over_pdf);
        ASSERT_EQ(sa.pdf, sb.pdf);
    }
    RayHit hit;
    hit.triangle = 1, hit.b1 = 0.2f, hit.b2 = 0.3f;
    const Emitters::Hit ha = a.HitEmitter(hit, {0.5f, 0.5f, 0}, {0.3f, 0.5f, 1});
    const Emitters::Hit hb = b.HitEmitter(hit, {0.5f, 0.5f, 0}, {0.3f, 0.5f, 1});
    EXPECT_EQ(ha.radiance, hb.radiance);
    EXPECT_EQ(ha.pdf, hb.pdf);
}

TEST(EmittersTest, ATexturedLightEmitsItsTexturesPowerAndNoneFromItsBlackTexels) {
    // An 8 x 1 texture, texels 0-3 white and 4-7 black, repeated over u: bilinear lookups
    // are 1 for u in [1/16, 7/16], 0 for u in [9/16, 15/16], and average 1/2. Photons carry
    // pi A Le / 2 on average (their flux is the texel where they leave over the pick's
    // probability), none leaves the black texels with any flux, and light samples of points
    // there carry nothing.
    Texture texture{8, 1, {}};
    for (int x = 0; x < 8; ++x) texture.texels.push_back(Rgb(x < 4 ? 1.0f : 0.0f));
    const Scene scene = SquareLight(Rgb(3.0f), texture);
    const Emitters emitters(scene);
    const double expected = kPiD * 3.0 * 0.5;
    // The pick's estimate of the power: within the quadrature's error.
    EXPECT_NEAR(emitters.TotalPower().x, expected, 0.05 * expected);
    Rng rng(11);
    constexpr int kPhotons = 400000;
    double sum = 0, sum_sq = 0;
    int from_black = 0;
    for (int i = 0; i < kPhotons; ++i) {
        const EmittedPhoton photon = emitters.Emit(rng);
        const double flux = photon.flux.x;
        sum += flux, sum_sq += flux * flux;
        const float u = photon.ray.origin.x;
        if (u > 9.0f / 16 && u < 15.0f / 16) {
            ++from_black;
            ASSERT_EQ(photon.flux.x, 0.0f) << "u " << u;
        }
    }
    EXPECT_GT(from_black, 0);
    const double mean = sum / kPhotons;
    const double standard_error = std::sqrt((sum_sq / kPhotons - mean * mean) / kPhotons);
    EXPECT_NEAR(mean, expected, 5 * standard_error);
    EXPECT_LT(5 * standard_error, 0.01 * expected);
    LightSample sample;
    for (int i = 0; i < 1000; ++i)
        if (emitters.SampleDirect({0.5f, 0.5f, 0}, {0, 0, 1}, rng, &sample)) {
            const float u = 0.5f + sample.direction.x / sample.direction.z;  // where it aims
            if (u > 9.0f / 16 && u < 15.0f / 16) ADD_FAILURE() << "a light sample at u " << u;
        }
}

TEST(EmittersTest, EachTexturedEmitterRecordsItsOwnTexturesLargestTexel) {
    // Two unit squares of light, each of two triangles, over two textures whose largest
    // components are 5 (blue, texel 2) and 2 (red, texel 0): each record's peak is its own
    // texture's, however many triangles share it.
    Scene scene =
        SquareLight(Rgb(1.0f), Texture{2, 2, {Rgb(0.5f), Rgb(1.0f), Rgb(0, 0, 5), Rgb(0.25f)}});
    const auto square = static_cast<uint32_t>(scene.positions.size());
    for (uint32_t v = 0; v < 4; ++v) {
        scene.positions.push_back(scene.positions[v] + Vec3(2, 0, 0));
        scene.uvs.push_back(scene.uvs[v]);
        scene.normals.push_back(Vec3(0.0f));
    }
    scene.triangles.push_back({{square, square + 3, square + 1}, 1, false, {0, 0, -1}});
    scene.triangles.push_back({{square, square + 2, square + 3}, 1, false, {0, 0, -1}});
    Material second = scene.materials[0];
    second.emission_texture = 1;
    scene.materials.push_back(second);
    scene.textures.push_back(
        std::make_shared<const Texture>(Texture{1, 2, {Rgb(2.0f, 0.5f, 0.5f), Rgb(1.0f)}}));
    for (const Vec3& p : scene.positions) scene.bounds.Extend(p);
    const Emitters emitters(scene);
    const std::vector<Emitters::Record> records = emitters.Records();
    ASSERT_EQ(records.size(), 4u);
    for (const Emitters::Record& record : records) {
        ASSERT_NE(record.texture, kNoTexture);
        EXPECT_EQ(record.peak, record.texture == 0 ? 5.0f : 2.0f) << "texture " << record.texture;
    }
}

// A scene of one floor triangle far below and one light.
Scene LightOnly(const PunctualLight& light) {
    Scene scene;
    scene.positions = {{-10, -10, -5}, {10, -10, -5}, {0, 10, -5}};
    scene.normals.assign(3, Vec3(0.0f));
    scene.uvs.assign(3, Point2{});
    scene.triangles = {{{0, 1, 2}, 0, false, {0, 0, 1}}};
    scene.materials = {Material{}};
    scene.lights = {light};
    for (const Vec3& p : scene.positions) scene.bounds.Extend(p);
    return scene;
}

struct FluxMean {
    double mean = 0, standard_error = 0;
};
// The mean and its standard error of the photons' first-channel flux; each photon checked.
template <typename Check>
FluxMean MeanFlux(const Emitters& emitters, int photons, Check check) {
    Rng rng(17);
    double sum = 0, sum_sq = 0;
    for (int i = 0; i < photons; ++i) {
        const EmittedPhoton photon = emitters.Emit(rng);
        check(photon);
        sum += photon.flux.x, sum_sq += double(photon.flux.x) * photon.flux.x;
    }
    const double mean = sum / photons;
    return {mean, std::sqrt(std::max(0.0, sum_sq / photons - mean * mean) / photons)};
}

TEST(EmittersTest, AGoniometricLightOfAConstantImageIsAPointLight) {
    // I = 2 x a 4 x 4 image of 0.5 everywhere: a point light of intensity 1, power 4 pi.
    PunctualLight light;
    light.type = LightType::kGoniometric;
    light.intensity = Rgb(2.0f);
    light.image = std::make_shared<const Texture>(Texture{4, 4, std::vector<Rgb>(16, Rgb(0.5f))});
    const Scene scene = LightOnly(light);
    const Emitters emitters(scene);
    EXPECT_NEAR(emitters.TotalPower().x, 4 * kPiD, 1e-4);
    const FluxMean flux = MeanFlux(emitters, 1000, [](const EmittedPhoton& photon) {
        EXPECT_NEAR(photon.flux.x, 4 * kPi, 1e-3f);
    });
    EXPECT_NEAR(flux.mean, 4 * kPiD, 1e-3);
    Rng rng(3);
    LightSample sample;
    ASSERT_TRUE(emitters.SampleDirect({0, 0, -2}, {0, 0, 1}, rng, &sample));
    EXPECT_NEAR(sample.radiance_over_pdf.x, 0.25f, 1e-5f);  // I / d^2
}

TEST(EmittersTest, AGoniometricLightEmitsWhereItsImageIsBright) {
    // A 32 x 32 map bright (1) where its texels' centres lie in the light frame's upper
    // hemisphere, dark below: photons carry the bright texels' solid angle on average (4 pi /
    // 1024 each), none goes where the map is dark, and light samples there carry nothing.
    Texture map{32, 32, {}};
    int bright = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            const bool up = EqualAreaSquareToSphere({(x + 0.5f) / 32, (y + 0.5f) / 32}).z > 0;
            map.texels.push_back(Rgb(up ? 1.0f : 0.0f));
            bright += up;
        }
    PunctualLight light;
    light.type = LightType::kGoniometric;
    light.image = std::make_shared<const Texture>(map);
    const Scene scene = LightOnly(light);
    const Emitters emitters(scene);
    const FluxMean flux = MeanFlux(emitters, 200000, [&](const EmittedPhoton& photon) {
        if (photon.flux.x > 0) {
            EXPECT_GT(light.ImageFactor(photon.ray.direction).x, 0.0f);
        }
    });
    EXPECT_NEAR(flux.mean, 4 * kPiD * bright / 1024, 5 * flux.standard_error + 1e-3);
    Rng rng(5);
    LightSample sample;
    EXPECT_FALSE(emitters.SampleDirect({0, 0, -2}, {0, 0, 1}, rng, &sample));  // below: dark
    ASSERT_TRUE(emitters.SampleDirect({0, 0, 2}, {0, 0, -1}, rng, &sample));   // above: bright
    EXPECT_NEAR(sample.radiance_over_pdf.x, 0.25f, 1e-5f);
}

TEST(EmittersTest, AProjectionLightFillsItsFrustumWithItsImage) {
    // A 2 x 1 image of 1s through a 90 degree frustum: x/z in [-2, 2], y/z in [-1, 1], a
    // pyramid of solid angle 4 asin(ab / sqrt((a^2 + 1)(b^2 + 1))) for half-sides a = 2, b = 1.
    // Photons carry I times it on average and stay inside; a receiver ahead gets I / d^2, one
    // outside nothing.
    PunctualLight light;
    light.type = LightType::kProjection;
    light.intensity = Rgb(3.0f);
    light.tan_half_fov = 1;
    light.image = std::make_shared<const Texture>(Texture{2, 1, {Rgb(1.0f), Rgb(1.0f)}});
    const Scene scene = LightOnly(light);
    const Emitters emitters(scene);
    const double solid_angle = 4 * std::asin(2.0 / std::sqrt(5.0 * 2.0));
    const FluxMean flux = MeanFlux(emitters, 200000, [](const EmittedPhoton& photon) {
        const Vec3& d = photon.ray.direction;
        EXPECT_GT(d.z, 0.0f);
        EXPECT_LE(std::abs(d.x / d.z), 2.0f + 1e-4f);
        EXPECT_LE(std::abs(d.y / d.z), 1.0f + 1e-4f);
    });
    EXPECT_NEAR(flux.mean, 3 * solid_angle, 5 * flux.standard_error);
    EXPECT_LT(5 * flux.standard_error, 0.01 * 3 * solid_angle);
    Rng rng(7);
    LightSample sample;
    ASSERT_TRUE(emitters.SampleDirect({0.5f, 0.2f, 2}, {0, 0, -1}, rng, &sample));
    EXPECT_NEAR(sample.radiance_over_pdf.x, 3 / (0.25f + 0.04f + 4), 1e-4f);
    EXPECT_FALSE(emitters.SampleDirect({0, 3, 1}, {0, -1, 0}, rng, &sample));  // y/z = 3
}

TEST(EmittersTest, AProjectionImagesTopRowLightsTheLightFramesMinusY) {
    // pbrt-v4 flips the projection's y: its image's top row goes toward the frame's -y.
    PunctualLight light;
    light.type = LightType::kProjection;
    light.image = std::make_shared<const Texture>(Texture{1, 2, {Rgb(5.0f), Rgb(7.0f)}});
    EXPECT_EQ(light.ImageFactor(Normalize(Vec3(0, -0.5f, 1))), Rgb(5.0f));
    EXPECT_EQ(light.ImageFactor(Normalize(Vec3(0, 0.5f, 1))), Rgb(7.0f));
    EXPECT_EQ(light.ImageFactor(Normalize(Vec3(0, 0.5f, -1))), Rgb(0.0f));  // behind
}

}  // namespace
}  // namespace pf
