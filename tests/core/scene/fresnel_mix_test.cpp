// The Fresnel mix (core/shared/coat.h's kCoatFresnelMix, glTF's dielectric BRDF): over a white
// base it reflects all the light under a smooth layer and never more under a rough one, it
// reflects F + (1 - F) rho in closed form, it is reciprocal, and light sampling, the camera
// pass's split and photons see the same surface.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "tests/core/scene/coat_walk.h"

namespace pf {
namespace {

Material Plastic(float albedo, float ior, float alpha, float weight = 1.0f) {
    Material material;
    material.base_color = Rgb(albedo);
    material.coat_kind = gpu::kCoatFresnelMix;
    material.coat_ior = ior;
    material.coat_roughness = alpha;
    material.coat_weight = weight;
    return material;
}

struct WalkEstimate {
    double mean, sigma;
};

WalkEstimate MeanWalk(const Material& material, float cos_theta, int samples, uint64_t seed) {
    Rng rng(seed);
    double sum = 0, sum_sq = 0;
    Vec3 out;
    for (int i = 0; i < samples; ++i) {
        const double w = Walk(material, Incident(cos_theta), rng, out);
        sum += w, sum_sq += w * w;
    }
    const double mean = sum / samples;
    return {mean, std::sqrt((sum_sq / samples - mean * mean) / samples)};
}

TEST(FresnelMixTest, SmoothLayerReflectsFresnelPlusTheRestOfTheBase) {
    // Under a smooth layer the surface reflects F(mu) specularly and (1 - F(mu)) rho from the
    // base, the base's lobe normalised by 1 - F_avg: a white base reflects everything.
    for (const auto& [ior, weight] : {std::pair{1.5f, 1.0f}, std::pair{2.2f, 0.6f}}) {
        for (const float albedo : {1.0f, 0.6f}) {
            const Material material = Plastic(albedo, ior, 0.0f, weight);
            for (const float mu : {0.95f, 0.5f, 0.15f}) {
                const double fresnel =
                    gpu::MixFresnel(gpu::Coat{gpu::kCoatFresnelMix, ior, 0, 0, weight, 0}, mu);
                const WalkEstimate walked = MeanWalk(material, mu, 200000, 7);
                EXPECT_NEAR(walked.mean, fresnel + (1 - fresnel) * albedo, 5 * walked.sigma + 1e-4)
                    << "ior " << ior << ", weight " << weight << ", albedo " << albedo << ", cos "
                    << mu;
            }
        }
    }
    // The normalisation is the cosine-weighted mean of F, 1/21 of (1 - F0) above F0.
    const gpu::Coat coat{gpu::kCoatFresnelMix, 1.5f, 0, 0, 1, 0};
    EXPECT_NEAR(gpu::MixFresnelAverage(coat),
                Integrate([&](double mu) { return 2 * mu * gpu::MixFresnel(coat, float(mu)); }),
                1e-6);
}

TEST(FresnelMixTest, RoughLayerOverAWhiteBaseNeverReflectsMoreThanArrives) {
    // A rough layer loses a little to single-scattering GGX's masking, as glTF's BRDF does:
    // most at grazing angles on the roughest layers.
    for (const float alpha : {0.1f, 0.5f, 1.0f}) {
        for (const float mu : {0.9f, 0.5f, 0.2f}) {
            const WalkEstimate walked = MeanWalk(Plastic(1.0f, 1.5f, alpha), mu, 200000, 13);
            EXPECT_LT(walked.mean, 1.0 + 5 * walked.sigma) << "alpha " << alpha << ", cos " << mu;
            // What gets lost is some of what the layer reflects, never what it lets through.
            const gpu::Coat coat{gpu::kCoatFresnelMix, 1.5f, alpha, 0, 1, 0};
            Rng rng(5);
            double through = 0;
            for (int i = 0; i < 100000; ++i)
                through +=
                    gpu::CoatTransmittance(coat, -Incident(mu), rng.NextFloat(), rng.NextFloat());
            EXPECT_GT(walked.mean, through / 100000 - 5 * walked.sigma - 2e-3)
                << "alpha " << alpha << ", cos " << mu;
        }
    }
}

TEST(FresnelMixTest, IsReciprocal) {
    // f(a, b) = f(b, a): the flux a walk from a carries out into a small cone about b, over
    // cos(b), equals the same from b into a cone about a, over cos(a).
    for (const float alpha : {0.0f, 0.3f}) {
        const Material material = Plastic(0.8f, 1.5f, alpha);
        const Vec3 a = Normalize(Vec3(0.3f, 0.1f, 0.95f));
        const Vec3 b = Normalize(Vec3(-0.8f, 0.4f, 0.45f));
        const auto [ab, sigma_ab] = IntoCone(material, a, b);
        const auto [ba, sigma_ba] = IntoCone(material, b, a);
        EXPECT_GT(ab, 0);
        EXPECT_NEAR(ab, ba, 5 * std::hypot(sigma_ab, sigma_ba)) << "alpha " << alpha;
    }
}

TEST(FresnelMixTest, LightSamplingAndTheCameraSplitSeeWhatPhotonsSee) {
    // Direct light at the base is weighed by CoatTransmittance, the camera pass splits with
    // SplitAtCoat, photons choose with EnterCoat: the same expectations of what reaches the
    // base and what the layer reflects.
    for (const float alpha : {0.0f, 0.4f}) {
        const gpu::Coat coat{gpu::kCoatFresnelMix, 1.5f, alpha, 0, 0.8f, 0};
        for (const float mu : {0.9f, 0.3f}) {
            const Vec3 w(std::sqrt(1 - mu * mu), 0, mu);
            constexpr int kSamples = 400000;
            Rng rng(3);
            // Per sample: photons' base and reflected weights, light sampling's, the split's.
            double sums[5] = {}, squares[5] = {};
            for (int i = 0; i < kSamples; ++i) {
                float u[7];
                for (float& x : u) x = rng.NextFloat();
                Vec3 wi;
                const float weight = gpu::EnterCoat(coat, w, u[0], u[1], u[2], wi).x;
                Rgb split_reflected;
                const double values[5] = {
                    wi.z < 0 ? weight : 0.0, wi.z > 0 ? weight : 0.0,
                    gpu::CoatTransmittance(coat, w, u[3], u[4]),
                    gpu::SplitAtCoat(coat, w, 1.0f, u[5], u[6], wi, split_reflected),
                    split_reflected.x};
                for (int k = 0; k < 5; ++k)
                    sums[k] += values[k], squares[k] += values[k] * values[k];
            }
            double mean[5], sigma[5];
            for (int k = 0; k < 5; ++k) {
                mean[k] = sums[k] / kSamples;
                sigma[k] =
                    std::sqrt(std::max(0.0, squares[k] / kSamples - mean[k] * mean[k]) / kSamples);
            }
            const std::string where =
                "alpha " + std::to_string(alpha) + ", cos " + std::to_string(mu);
            EXPECT_NEAR(mean[0], mean[2], 5 * std::hypot(sigma[0], sigma[2]) + 1e-6) << where;
            EXPECT_NEAR(mean[0], mean[3], 5 * std::hypot(sigma[0], sigma[3]) + 1e-6) << where;
            EXPECT_NEAR(mean[1], mean[4], 5 * std::hypot(sigma[1], sigma[4]) + 1e-6) << where;
            if (alpha == 0) {
                EXPECT_NEAR(mean[2], 1 - gpu::MixFresnel(coat, mu), 1e-6) << where;
            }
        }
    }
}

TEST(FresnelMixTest, TheNormalisationIsTheMeanOfWhatTheLayerReflects) {
    // F_avg, the base's normalisation, is the cosine-weighted mean over w of E_m[F(w.m)] over
    // w's visible microfacets; MixFresnelAverage's fit of it must hold at every roughness.
    for (const float alpha : {0.05f, 0.2f, 0.5f, 0.8f, 1.0f}) {
        const gpu::Coat coat{gpu::kCoatFresnelMix, 1.5f, alpha, 0, 1, 0};
        constexpr int kMicrofacets = 2000;
        const double mean = Integrate([&](double mu) {
            const Vec3 w(std::sqrt(1 - mu * mu), 0, float(mu));
            double sum = 0;
            for (int j = 0; j < kMicrofacets; ++j) {
                const float u1 = (j + 0.5f) / kMicrofacets;
                const float u2 = std::fmod(j * 0.618034f + 0.3f, 1.0f);
                sum += gpu::MixFresnel(coat, Dot(w, gpu::CoatMicrofacet(coat, w, u1, u2)));
            }
            return 2 * mu * sum / kMicrofacets;
        });
        EXPECT_NEAR(gpu::MixFresnelAverage(coat), mean, 1e-3) << "alpha " << alpha;
    }
}

}  // namespace
}  // namespace pf
