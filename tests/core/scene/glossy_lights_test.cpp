// What glossy surfaces reflect of punctual lights (core/shared/glossy_lights.h) is what their
// sampling draws: integrated over every direction of light, f |cos wi| gives the albedo the
// sampling's weights average to, at fixed angles, for the coat's reflection, rough glass and a
// coated conductor.
#include "core/shared/glossy_lights.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>

#include "core/sampling/rng.h"
#include "core/sampling/sampling.h"
#include "core/scene/scattering.h"
#include "tests/core/scene/coat_walk.h"

namespace pf {
namespace {

struct Estimate {
    double mean = 0, sigma = 0;
};

// The mean of `draw` over n draws, with its standard error.
Estimate Average(int n, const std::function<double()>& draw) {
    double sum = 0, sum_sq = 0;
    for (int i = 0; i < n; ++i) {
        const double x = draw();
        sum += x, sum_sq += x * x;
    }
    const double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sum_sq / n - mean * mean) / n)};
}

Vec3 Outgoing(float cos_theta) { return {std::sqrt(1 - cos_theta * cos_theta), 0, cos_theta}; }

// The integral of response(wi) over the sphere (or the upper hemisphere), wi drawn uniformly.
Estimate IntegrateDirections(int n, bool sphere, Rng& rng,
                             const std::function<double(const Vec3&)>& response) {
    return Average(n, [&] {
        Vec3 wi = SampleUniformSphere(rng.NextFloat(), rng.NextFloat());
        if (!sphere) wi.z = std::abs(wi.z);
        return response(wi) * (sphere ? 4 : 2) * kPi;
    });
}

void ExpectSame(const Estimate& evaluated, const Estimate& sampled, const std::string& what) {
    std::printf("%s: evaluated %.5f +- %.5f, sampled %.5f +- %.5f\n", what.c_str(), evaluated.mean,
                evaluated.sigma, sampled.mean, sampled.sigma);
    EXPECT_NEAR(evaluated.mean, sampled.mean, 5 * std::hypot(evaluated.sigma, sampled.sigma))
        << what;
    EXPECT_GT(evaluated.mean, 0.01) << what << ": something to compare";
}

TEST(GlossyLights, CoatReflectionIsWhatEnterCoatReflects) {
    gpu::Coat layered{gpu::kCoatLayered, 1.5f, 0.3f, 0.1f, 1.0f, 5, Vec3(0.0f), 0.5f};
    gpu::Coat mix = layered;
    mix.kind = gpu::kCoatFresnelMix;
    mix.weight = 0.8f;
    gpu::Coat sheen = layered;
    sheen.kind = gpu::kCoatNone;
    sheen.sheen = Vec3(0.6f, 0.5f, 0.4f);
    gpu::Coat sheen_over_coat = layered;
    sheen_over_coat.sheen = Vec3(0.3f);
    const std::pair<const char*, gpu::Coat> coats[] = {
        {"rough coat", layered},
        {"rough Fresnel mix", mix},
        {"sheen", sheen},
        {"sheen over a rough coat", sheen_over_coat}};
    for (const auto& [name, coat] : coats) {
        for (const float mu : {0.9f, 0.5f, 0.2f}) {
            const Vec3 wo = Outgoing(mu);
            Rng rng(3);
            const Estimate evaluated = IntegrateDirections(400000, false, rng, [&](const Vec3& wi) {
                return double(gpu::CoatReflection(coat, wo, wi).x);
            });
            const Estimate sampled = Average(400000, [&] {
                Vec3 wi;
                const float u[3] = {rng.NextFloat(), rng.NextFloat(), rng.NextFloat()};
                const Vec3 weight = gpu::EnterCoat(coat, wo, u[0], u[1], u[2], wi);
                return wi.z > 0 ? double(weight.x) : 0.0;
            });
            ExpectSame(evaluated, sampled, std::string(name) + ", cos " + std::to_string(mu));
        }
    }
}

TEST(GlossyLights, RoughGlassResponseIsWhatItsSamplingCarries) {
    Material glass;
    glass.type = MaterialType::kRoughDielectric;
    glass.ior = 1.5f;
    glass.roughness = 0.3f;
    const Rgb tint(0.9f, 0.7f, 0.5f);
    for (const bool front : {true, false}) {
        const float eta = front ? 1 / glass.ior : glass.ior;
        for (const float mu : {0.9f, 0.5f}) {
            const Vec3 wo = Outgoing(mu);
            Rng rng(5);
            for (int channel : {0, 2}) {
                const Estimate evaluated =
                    IntegrateDirections(800000, true, rng, [&](const Vec3& wi) {
                        return double(gpu::RoughDielectricResponse(eta, glass.roughness, tint, wo,
                                                                   wi)[channel]);
                    });
                // The camera path arrives along -wo at the side the normal faces (front: from
                // outside) or at its back (from inside the glass, the normal turned away).
                const Vec3 normal(0, 0, front ? 1.0f : -1.0f);
                const Vec3 d = -wo;
                const Estimate sampled = Average(800000, [&] {
                    return double(ScatterNonDiffuse(BsdfOf(glass), d, normal, front, tint,
                                                    rng.State(), kCarriesRadiance)
                                      .weight[channel]);
                });
                ExpectSame(evaluated, sampled,
                           std::string(front ? "into" : "out of") + " rough glass, cos " +
                               std::to_string(mu) + ", channel " + std::to_string(channel));
            }
        }
    }
}

TEST(GlossyLights, CoatedConductorResponseIsWhatItsWalkCarries) {
    const gpu::Conductor copper{gpu::kConductorComplex, Vec3(0.27f, 0.68f, 1.22f),
                                Vec3(3.6f, 2.6f, 2.3f)};
    struct Case {
        const char* name;
        float coat_alpha, base_alpha;
    };
    for (const Case& c : {Case{"rough coat over a mirror", 0.3f, 0.0f},
                          Case{"smooth coat over rough metal", 0.0f, 0.3f},
                          Case{"rough coat over rough metal", 0.2f, 0.4f}}) {
        const gpu::Coat coat{gpu::kCoatLayered, 1.5f, c.coat_alpha, 0.1f, 1.0f, 5,
                             Vec3(0.0f),        0.5f};
        for (const float mu : {0.9f, 0.4f}) {
            const Vec3 wo = Outgoing(mu);
            gpu::Pcg32 state = gpu::Pcg32Seeded(7);
            Rng rng(11);
            Estimate evaluated = IntegrateDirections(150000, false, rng, [&](const Vec3& wi) {
                return double(gpu::CoatedConductorResponse(coat, copper, Vec3(1.0f), c.base_alpha,
                                                           wo, wi, 1, state)
                                  .y);
            });
            // A smooth coat's own reflection is a delta the response leaves out (no punctual
            // light meets it) and the walk takes: F(mu) of the light.
            if (c.coat_alpha == 0) evaluated.mean += gpu::FresnelDielectric(mu, 1 / coat.ior);
            const Estimate sampled = Average(150000, [&] {
                Vec3 wi;
                return double(gpu::ScatterCoatedConductor(coat, copper, wo, Vec3(1.0f),
                                                          c.base_alpha, state, wi)
                                  .y);
            });
            ExpectSame(evaluated, sampled, std::string(c.name) + ", cos " + std::to_string(mu));
        }
    }
}

}  // namespace
}  // namespace pf
