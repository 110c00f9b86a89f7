// A sheen over a surface (core/shared/coat.h's sheen, glTF's KHR_materials_sheen): a white sheen
// over a white base reflects all the light, over a black one its own albedo; the surface is
// reciprocal; light sampling, the camera pass's split and photons see the same surface; over a
// metal the walk gives the closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "tests/core/scene/coat_walk.h"

namespace pf {
namespace {

// A diffuse surface of albedo `albedo` under a sheen of colour `sheen` and roughness r, over no
// coat (kCoatNone) or glTF's dielectric layer (a smooth Fresnel mix of index 1.5).
Material Sheened(float albedo, const Rgb& sheen, float roughness, bool fresnel_mix) {
    Material material;
    material.base_color = Rgb(albedo);
    material.coat_kind = fresnel_mix ? gpu::kCoatFresnelMix : gpu::kCoatNone;
    material.coat_ior = fresnel_mix ? 1.5f : 1.0f;
    material.sheen_color = sheen;
    material.sheen_roughness = roughness;
    return material;
}

struct Estimate {
    double mean, sigma;
};

Estimate MeanWalk(const Material& material, float cos_theta, int samples) {
    Rng rng(11);
    double sum = 0, sum_sq = 0;
    Vec3 out;
    for (int i = 0; i < samples; ++i) {
        const double w = Walk(material, Incident(cos_theta), rng, out);
        sum += w, sum_sq += w * w;
    }
    const double mean = sum / samples;
    return {mean, std::sqrt((sum_sq / samples - mean * mean) / samples)};
}

// The tables' error where E is at most 1 (sheen_test.cpp bounds it).
double TableTolerance(double albedo) { return 0.015 * albedo + 2e-3; }

TEST(SheenLayerTest, WhiteSheenOverAWhiteBaseReflectsEverything) {
    // E(mu) from the sheen, (1 - E(mu)) from the Lambertian base, whose lobe is normalised by
    // 1 - E_avg.
    for (const float roughness : {0.5f, 1.0f}) {
        const Material material = Sheened(1.0f, Rgb(1.0f), roughness, false);
        for (const float mu : {0.95f, 0.5f, 0.15f}) {
            const Estimate walked = MeanWalk(material, mu, 200000);
            EXPECT_NEAR(walked.mean, 1.0,
                        5 * walked.sigma + TableTolerance(gpu::SheenAlbedo(mu, roughness)))
                << "roughness " << roughness << ", cos " << mu;
        }
    }
}

TEST(SheenLayerTest, OverGltfsDielectricTheSheenScalesItsLayers) {
    // Over a smooth Fresnel mix on a white base, light at cosine mu is reflected by the sheen
    // (E), or by the specular layer (F, scaled by 1 - P as glTF scales it), or by the base
    // through both: E + (1 - P) F + (1 - P) (1 - F) / ((1 - F_avg) (1 - P_avg)) integral (1 -
    // F) (1 - P) 2 mu.
    for (const float roughness : {0.3f, 1.0f}) {
        const Material material = Sheened(1.0f, Rgb(1.0f), roughness, true);
        const gpu::Coat coat = CoatOf(material);
        const double through = Integrate([&](double x) {
            return (1 - gpu::MixFresnel(coat, float(x))) *
                   (1 - gpu::SheenProbability(coat, float(x))) * 2 * x;
        });
        for (const float mu : {0.95f, 0.5f, 0.15f}) {
            const double e = gpu::SheenAlbedo(mu, roughness);
            const double p = gpu::SheenProbability(coat, mu), fresnel = gpu::MixFresnel(coat, mu);
            const double expected = e + (1 - p) * fresnel +
                                    (1 - p) * (1 - fresnel) * gpu::SheenInside(coat) /
                                        (1 - gpu::MixFresnelAverage(coat)) * through;
            const Estimate walked = MeanWalk(material, mu, 200000);
            EXPECT_NEAR(walked.mean, expected, 5 * walked.sigma + TableTolerance(e))
                << "roughness " << roughness << ", cos " << mu;
        }
    }
}

TEST(SheenLayerTest, OverABlackBaseTheSheenReflectsItsAlbedo) {
    for (const float roughness : {0.07f, 0.3f, 1.0f}) {
        for (const float mu : {0.9f, 0.4f, 0.1f}) {
            const Estimate walked =
                MeanWalk(Sheened(0.0f, Rgb(0.6f), roughness, false), mu, 400000);
            const double albedo = 0.6 * gpu::SheenAlbedo(mu, roughness);
            EXPECT_NEAR(walked.mean, albedo, 5 * walked.sigma + 0.6 * TableTolerance(albedo))
                << "roughness " << roughness << ", cos " << mu;
        }
    }
}

TEST(SheenLayerTest, IsReciprocal) {
    // f(a, b) = f(b, a) for the sheen, the rough layer's reflection and the base alike.
    // Over a black base too, so that the layer's reflection is most of what leaves, between
    // directions the sheen treats differently (P 0.36 at the first, 0.23 at the second), broad
    // lobes, so that the cones' averages stand for their centres.
    for (const float albedo : {0.0f, 0.7f}) {
        Material material = Sheened(albedo, Rgb(1.0f, 0.7f, 0.5f), 1.0f, true);
        material.coat_roughness = 0.5f;
        material.coat_ior = 4.0f;  // F0 0.36: a strong reflection
        const Vec3 a = Normalize(Vec3(-0.87f, 0.05f, 0.5f)), b = Normalize(Vec3(0.6f, 0.0f, 0.8f));
        const auto [forward, forward_sigma] = IntoCone(material, a, b);
        const auto [backward, backward_sigma] = IntoCone(material, b, a);
        EXPECT_NEAR(forward, backward, 5 * std::hypot(forward_sigma, backward_sigma))
            << "base albedo " << albedo;
    }
}

TEST(SheenLayerTest, LightSamplingAndTheCameraSplitSeeWhatPhotonsSee) {
    // Photons choose with EnterCoat, light sampling weighs by CoatTransmittance, the camera
    // pass splits with SplitAtCoat: the same expectations of what reaches the base and what is
    // reflected, per channel of a coloured sheen.
    for (const uint32_t kind : {gpu::kCoatNone, gpu::kCoatFresnelMix, gpu::kCoatLayered}) {
        const gpu::Coat coat{
            kind, kind == gpu::kCoatNone ? 1.0f : 1.5f, 0.3f, 0, 1, 10, Rgb(0.9f, 0.6f, 0.2f),
            0.4f};
        for (const float mu : {0.9f, 0.3f, 0.08f}) {
            const Vec3 w(std::sqrt(1 - mu * mu), 0, mu);
            constexpr int kSamples = 400000;
            Rng rng(3);
            // Per sample: photons' base weight, their reflected red and blue, light sampling's,
            // the split's base weight and reflected red and blue.
            double sums[7] = {}, squares[7] = {};
            for (int i = 0; i < kSamples; ++i) {
                float u[8];
                for (float& x : u) x = rng.NextFloat();
                Vec3 wi;
                const Rgb weight = gpu::EnterCoat(coat, w, u[0], u[1], u[2], wi);
                const bool in = wi.z < 0;
                Rgb split;
                const double entered = gpu::SplitAtCoat(coat, w, u[5], u[6], u[7], wi, split);
                const double values[7] = {in ? weight.x : 0.0,
                                          in ? 0.0 : weight.x,
                                          in ? 0.0 : weight.z,
                                          gpu::CoatTransmittance(coat, w, u[3], u[4]),
                                          entered,
                                          split.x,
                                          split.z};
                for (int k = 0; k < 7; ++k)
                    sums[k] += values[k], squares[k] += values[k] * values[k];
            }
            double mean[7], sigma[7];
            for (int k = 0; k < 7; ++k) {
                mean[k] = sums[k] / kSamples;
                sigma[k] =
                    std::sqrt(std::max(0.0, squares[k] / kSamples - mean[k] * mean[k]) / kSamples);
            }
            const std::string where =
                "kind " + std::to_string(kind) + ", cos " + std::to_string(mu);
            const auto agree = [&](int a, int b) {
                EXPECT_NEAR(mean[a], mean[b], 5 * std::hypot(sigma[a], sigma[b]) + 1e-6)
                    << where << ": " << a << " against " << b;
            };
            agree(0, 3), agree(0, 4), agree(1, 5), agree(2, 6);
        }
    }
}

TEST(SheenLayerTest, OverAMirrorTheWalkGivesTheClosedForm) {
    // A white sheen over a white mirror (no coat below it): the sheen reflects E(mu); the rest
    // reaches the mirror and leaves at the same cosine, weighed by (1 - E(mu)) / (1 - E_avg).
    Material mirror;
    mirror.type = MaterialType::kMirror;
    mirror.base_color = Rgb(1.0f);
    mirror.coat_kind = gpu::kCoatNone;
    mirror.coat_ior = 1.0f;
    mirror.sheen_color = Rgb(1.0f);
    mirror.sheen_roughness = 0.6f;
    for (const float mu : {0.9f, 0.4f, 0.12f}) {
        Rng rng(5);
        constexpr int kSamples = 200000;
        double sum = 0, sum_sq = 0;
        for (int i = 0; i < kSamples; ++i) {
            const SpecularBounce bounce =
                ScatterNonDiffuse(BsdfOf(mirror), Incident(mu), Vec3(0, 0, 1), true, Rgb(1.0f),
                                  rng.State(), kCarriesRadiance);
            const double w = bounce.weight.x;
            sum += w, sum_sq += w * w;
        }
        const double mean = sum / kSamples;
        const double sigma = std::sqrt((sum_sq / kSamples - mean * mean) / kSamples);
        const double e = gpu::SheenAlbedo(mu, 0.6f), average = gpu::SheenAverageAlbedo(0.6f);
        EXPECT_NEAR(mean, e + (1 - e) * (1 - e) / (1 - average), 5 * sigma + TableTolerance(e))
            << "cos " << mu;
    }
}

}  // namespace
}  // namespace pf
