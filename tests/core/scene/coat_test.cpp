// Coated surfaces (core/shared/coat.h, scatter.h's ArriveAtCoat and LeaveCoatAt): the walk
// through a smooth coat reflects what the closed form of a layer over a Lambertian base
// gives, a lossless coat over a white base loses nothing, light sampling's transmittance is
// the walk's, the layered surface is reciprocal, and a coated mirror keeps what arrives.
#include <gtest/gtest.h>

#include <cmath>

#include "core/ppm/photon_walk.h"
#include "core/sampling/frame.h"
#include "core/sampling/rng.h"
#include "core/sampling/sampling.h"
#include "core/scene/scattering.h"
#include "tests/core/scene/coat_walk.h"

namespace pf {
namespace {

Material CoatedDiffuse(float albedo, float ior, float alpha, float thickness) {
    Material material;
    material.base_color = Rgb(albedo);
    material.coat_ior = ior;
    material.coat_roughness = alpha;
    material.coat_thickness = thickness;
    return material;
}

TEST(CoatTest, SmoothCoatReflectsTheLayersClosedForm) {
    // A smooth coat of index eta and optical thickness t over a Lambertian base of albedo rho
    // reflects F(mu) + (1 - F(mu)) T(mu_t) rho E / (1 - rho R) of the light arriving at
    // cosine mu: T the crossing's transmittance, E the fraction of the base's (cosine
    // distributed) light that gets out on one try, R the fraction the coat turns back.
    constexpr float kEta = 1.5f, kThickness = 0.05f, kAlbedo = 0.6f;
    const Material material = CoatedDiffuse(kAlbedo, kEta, 0.0f, kThickness);
    const double escape = Integrate([&](double mu) {
        return 2 * mu * std::exp(-kThickness / mu) * (1 - gpu::FresnelDielectric(mu, kEta));
    });
    const double turned_back = Integrate([&](double mu) {
        return 2 * mu * std::exp(-2 * kThickness / mu) * gpu::FresnelDielectric(mu, kEta);
    });
    for (const float mu : {0.95f, 0.6f, 0.25f}) {
        const double fresnel = gpu::FresnelDielectric(mu, 1 / kEta);
        const double mu_t = std::sqrt(1 - (1 - mu * mu) / (kEta * kEta));
        const double expected = fresnel + (1 - fresnel) * std::exp(-kThickness / mu_t) * kAlbedo *
                                              escape / (1 - kAlbedo * turned_back);
        constexpr int kSamples = 400000;
        Rng rng(11);
        double sum = 0, sum_sq = 0;
        Vec3 out;
        for (int i = 0; i < kSamples; ++i) {
            const double w = Walk(material, Incident(mu), rng, out);
            sum += w, sum_sq += w * w;
        }
        const double mean = sum / kSamples;
        const double sigma = std::sqrt((sum_sq / kSamples - mean * mean) / kSamples);
        EXPECT_NEAR(mean, expected, 5 * sigma + 1e-4) << "cos " << mu;
    }
}

TEST(CoatTest, LosslessCoatOverWhiteBaseReflectsEverything) {
    // Exactly so for a smooth coat. A rough one loses light to single-scattering GGX's masking
    // at every crossing, most from inside, near the critical angle (pbrt-v4's LayeredBxDF,
    // built of the same interface, loses the same): never a gain, more the rougher.
    double previous = 1.0 + 1e-6;
    for (const float alpha : {0.0f, 0.1f, 0.4f}) {
        const Material material = CoatedDiffuse(1.0f, 1.5f, alpha, 0.0f);
        constexpr int kSamples = 100000;
        Rng rng(5);
        double sum = 0;
        Vec3 out;
        for (int i = 0; i < kSamples; ++i) sum += Walk(material, Incident(0.7f), rng, out);
        const double albedo = sum / kSamples;
        if (alpha == 0) {
            EXPECT_NEAR(albedo, 1.0, 1e-3) << "a smooth lossless coat keeps it all";
        }
        EXPECT_LT(albedo, previous) << "alpha " << alpha;
        EXPECT_GT(albedo, 0.5) << "alpha " << alpha;
        previous = albedo;
    }
}

TEST(CoatTest, LightSamplingTransmittanceIsTheWalks) {
    // Direct light at a coated base is weighed by CoatTransmittance; photons reach the base
    // through EnterCoat. Their expectations must agree, rough or smooth.
    for (const float alpha : {0.0f, 0.05f, 0.5f}) {
        for (const float mu : {0.9f, 0.4f, 0.1f}) {
            const Vec3 w(std::sqrt(1 - mu * mu), 0, mu);
            constexpr int kSamples = 200000;
            Rng rng(3);
            double walked = 0, walked_sq = 0, sampled = 0, sampled_sq = 0;
            for (int i = 0; i < kSamples; ++i) {
                const float u[5] = {rng.NextFloat(), rng.NextFloat(), rng.NextFloat(),
                                    rng.NextFloat(), rng.NextFloat()};
                Vec3 wi;
                const gpu::Coat coat{gpu::kCoatLayered, 1.5f, alpha, 0.1f, 1.0f, 10};
                const float entered = gpu::EnterCoat(coat, w, u[0], u[1], u[2], wi).x;
                const double a = wi.z < 0 ? entered : 0.0;
                const double b = gpu::CoatTransmittance(coat, w, u[3], u[4]);
                walked += a, walked_sq += a * a, sampled += b, sampled_sq += b * b;
            }
            walked /= kSamples, sampled /= kSamples;
            const double sigma = std::sqrt((walked_sq / kSamples - walked * walked) / kSamples +
                                           (sampled_sq / kSamples - sampled * sampled) / kSamples);
            EXPECT_NEAR(walked, sampled, 5 * sigma + 1e-6) << "alpha " << alpha << ", cos " << mu;
            if (alpha == 0) {
                const double mu_t = std::sqrt(1 - (1 - mu * mu) / 2.25);
                EXPECT_NEAR(sampled,
                            (1 - gpu::FresnelDielectric(mu, 1 / 1.5f)) * std::exp(-0.1 / mu_t),
                            1e-5);
            }
        }
    }
}

TEST(CoatTest, CoatedDiffuseIsReciprocal) {
    // f(a, b) = f(b, a): the flux a walk from a carries out into a small cone about b, over
    // cos(b), equals the same from b into a cone about a, over cos(a).
    for (const float alpha : {0.0f, 0.3f}) {
        const Material material = CoatedDiffuse(0.8f, 1.5f, alpha, 0.2f);
        const Vec3 a = Normalize(Vec3(0.3f, 0.1f, 0.95f));
        const Vec3 b = Normalize(Vec3(-0.8f, 0.4f, 0.45f));
        const auto [ab, sigma_ab] = IntoCone(material, a, b);
        const auto [ba, sigma_ba] = IntoCone(material, b, a);
        EXPECT_GT(ab, 0);
        EXPECT_NEAR(ab, ba, 5 * std::hypot(sigma_ab, sigma_ba)) << "alpha " << alpha;
    }
}

TEST(CoatTest, CoatedMirrorKeepsWhatArrives) {
    Material mirror;
    mirror.type = MaterialType::kMirror;
    mirror.coat_ior = 1.5f;
    Rng rng(9);
    constexpr int kSamples = 50000;
    double sum = 0;
    for (int i = 0; i < kSamples; ++i) {
        const SpecularBounce bounce =
            ScatterNonDiffuse(BsdfOf(mirror), Incident(0.7f), {0, 0, 1}, true, Rgb(1.0f),
                              rng.State(), kCarriesRadiance);
        sum += Average(bounce.weight);
        ASSERT_GT(bounce.direction.z, 0) << "a coated mirror reflects";
        // Both the coat's and the mirror's reflections are the mirror direction of d.
        EXPECT_NEAR(bounce.direction.x, Incident(0.7f).x, 1e-4);
    }
    EXPECT_GT(sum / kSamples, 0.999) << "a lossless coat over a perfect mirror";
    // A coat over copper tints what gets through to it: less than the bare copper's
    // normal-incidence reflectance comes back only through absorption in the coat.
    Material copper = mirror;
    copper.coat_thickness = 0.5f;
    double tinted = 0;
    for (int i = 0; i < kSamples; ++i)
        tinted += Average(ScatterNonDiffuse(BsdfOf(copper), Incident(1.0f), {0, 0, 1}, true,
                                            Rgb(0.95f, 0.64f, 0.54f), rng.State(), kCarriesRadiance)
                              .weight);
    EXPECT_LT(tinted / kSamples, Average(Rgb(0.95f, 0.64f, 0.54f)));
}

TEST(CoatTest, PhotonsReflectedByACoatKeepTheirFlux) {
    // A smooth coat over a black base (albedo 0): a photon that the coat lets in is absorbed
    // there, so the flux that goes on is what the coat reflects, F(cos) of it, in the mirror
    // direction (the caustics a varnished floor throws), and every photon that enters lands.
    Scene scene;
    scene.positions = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
    scene.triangles = {{{0, 1, 2}, 0, false, {0, 0, 1}}};
    scene.materials = {CoatedDiffuse(0.0f, 1.5f, 0.0f, 0.0f)};
    scene.bounds.Extend({-1, -1, 0}), scene.bounds.Extend({1, 1, 0});
    constexpr float kCos = 0.6f;
    constexpr int kPhotons = 200000;
    Rng rng(21);
    double carried = 0, landed = 0;
    for (int i = 0; i < kPhotons; ++i) {
        Ray ray{{0, 0, 1}, Incident(kCos)};
        Rgb flux(1.0f);
        const RayHit hit{1.0f, 0, 1.0f / 3, 1.0f / 3};
        const PhotonEvent event =
            ScatterPhotonAt<true, false>(scene, hit, ray, flux, rng,
                                         [&](const Vec3&, const Vec3&, const Rgb& power, bool,
                                             float, const Vec3&) { landed += power.x; });
        if (event != PhotonEvent::kNonDiffuse) continue;
        carried += flux.x;
        EXPECT_NEAR(ray.direction.z, kCos, 1e-5f) << "the mirror direction";
    }
    const double fresnel = gpu::FresnelDielectric(kCos, 1 / 1.5f);
    const double sigma = std::sqrt(fresnel * (1 - fresnel) / kPhotons);
    EXPECT_NEAR(carried / kPhotons, fresnel, 5 * sigma);
    EXPECT_NEAR(landed / kPhotons, 1 - fresnel, 5 * sigma) << "flux reaching the base";
}

// pbrt-v4's maxdepth counts crossings of the layer, so its default 10 lets light visit the
// base 5 times, each with a chance to leave: under a smooth coat of index eta and optical
// thickness t over a Lambertian base of albedo rho, light arriving at cosine mu comes back
// F(mu) + (1 - F(mu)) T(mu_t) rho E sum_{k < K} (rho R)^k, K the visits (coat_test.cpp's
// closed form, cut at K). Photons walk so (core/ppm/photon_walk.h), as do camera paths.
TEST(CoatTest, PhotonsVisitTheBaseAsOftenAsTheCoatsDepthAllows) {
    constexpr float kEta = 1.5f, kThickness = 0.01f, kAlbedo = 0.9f;
    const double escape = Integrate([&](double mu) {
        return 2 * mu * std::exp(-kThickness / mu) * (1 - gpu::FresnelDielectric(mu, kEta));
    });
    const double turned_back = Integrate([&](double mu) {
        return 2 * mu * std::exp(-2 * kThickness / mu) * gpu::FresnelDielectric(mu, kEta);
    });
    Scene scene;
    scene.positions = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
    scene.triangles = {{{0, 1, 2}, 0, false, {0, 0, 1}}};
    scene.bounds.Extend({-1, -1, 0}), scene.bounds.Extend({1, 1, 0});
    for (const uint32_t visits : {1u, 2u, 5u}) {
        Material coated;
        coated.base_color = Rgb(kAlbedo);
        coated.coat_ior = kEta;
        coated.coat_thickness = kThickness;
        coated.coat_depth = visits;
        scene.materials = {coated};
        constexpr float kCos = 0.8f;
        const double fresnel = gpu::FresnelDielectric(kCos, 1 / kEta);
        const double mu_t = std::sqrt(1 - (1 - kCos * kCos) / (kEta * kEta));
        double series = 0;
        for (uint32_t k = 0; k < visits; ++k) series += std::pow(kAlbedo * turned_back, k);
        const double expected =
            fresnel + (1 - fresnel) * std::exp(-kThickness / mu_t) * kAlbedo * escape * series;
        Rng rng(13);
        constexpr int kPhotons = 400000;
        double sum = 0, sum_sq = 0;
        for (int i = 0; i < kPhotons; ++i) {
            Ray ray{{0, 0, 1}, Incident(kCos)};
            Rgb flux(1.0f);
            const RayHit hit{1.0f, 0, 1.0f / 3, 1.0f / 3};
            const PhotonEvent event = ScatterPhotonAt<true, false>(
                scene, hit, ray, flux, rng,
                [](const Vec3&, const Vec3&, const Rgb&, bool, float, const Vec3&) {});
            const double out = event == PhotonEvent::kEnded ? 0.0 : double(flux.x);
            sum += out, sum_sq += out * out;
        }
        const double mean = sum / kPhotons;
        const double sigma = std::sqrt((sum_sq / kPhotons - mean * mean) / kPhotons);
        EXPECT_NEAR(mean, expected, 5 * sigma) << visits << " visits";
    }
}

}  // namespace
}  // namespace pf
