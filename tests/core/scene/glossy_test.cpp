// The rough materials: sampling rough metal agrees with its evaluation (what the path tracer's
// light sampling weighs against), the sampled density integrates to at most one, and rough
// glass loses energy only to masking.
#include <gtest/gtest.h>

#include <cmath>

#include "core/sampling/frame.h"
#include "core/sampling/rng.h"
#include "core/sampling/sampling.h"
#include "core/scene/scattering.h"

namespace pf {
namespace {

struct Lobe {
    float alpha;
    float cos_incident;
};

class RoughMetalTest : public ::testing::TestWithParam<Lobe> {};

TEST_P(RoughMetalTest, SamplingAgreesWithEvaluation) {
    const Lobe lobe = GetParam();
    Material metal;
    metal.type = MaterialType::kRoughConductor;
    metal.roughness = lobe.alpha;
    const Vec3 n(0, 0, 1);
    const float sin_incident = std::sqrt(1 - lobe.cos_incident * lobe.cos_incident);
    const Vec3 d(sin_incident, 0, -lobe.cos_incident);  // arriving at the surface
    const Vec3 wo = -d;
    constexpr int kSamples = 400000;
    // E[f cos / pdf] by the sampler, against the integral of f cos over the hemisphere by
    // uniform directions; and the integral of the density, which is at most 1 (directions
    // reflected below the surface are lost).
    Rng rng(7);
    double sampled = 0, integrated = 0, density = 0;
    for (int i = 0; i < kSamples; ++i) {
        const SpecularBounce bounce =
            ScatterNonDiffuse(BsdfOf(metal), d, n, true, Rgb(1.0f), rng.State(), kCarriesRadiance);
        sampled += Average(bounce.weight);
        const float u1 = rng.NextFloat();
        const float u2 = rng.NextFloat();
        Vec3 wi = SampleUniformSphere(u1, u2);
        wi.z = std::abs(wi.z);
        const RoughReflection f = EvaluateRoughConductor(BsdfOf(metal), Rgb(1.0f), n, wo, wi);
        integrated += Average(f.value) * 2 * kPi;
        density += f.pdf * 2 * kPi;
    }
    sampled /= kSamples, integrated /= kSamples, density /= kSamples;
    EXPECT_NEAR(sampled, integrated, 0.02 * integrated)
        << "alpha " << lobe.alpha << ", cos " << lobe.cos_incident;
    EXPECT_LE(sampled, 1.0) << "a rough mirror of tint 1 reflects at most what arrives";
    EXPECT_LE(density, 1.03) << "the sampled density integrates to at most 1";
    if (lobe.alpha <= 0.4f) {  // single-scattering GGX loses much more when very rough
        EXPECT_GT(sampled, 0.75) << "a moderately rough mirror loses little to masking";
        EXPECT_GT(density, 0.8);
    }
}

INSTANTIATE_TEST_SUITE_P(Lobes, RoughMetalTest,
                         ::testing::Values(Lobe{0.1f, 1.0f}, Lobe{0.1f, 0.5f}, Lobe{0.4f, 0.9f},
                                           Lobe{0.8f, 0.7f}),
                         [](const auto& param_info) {
                             return "alpha" + std::to_string(int(param_info.param.alpha * 100)) +
                                    "_cos" +
                                    std::to_string(int(param_info.param.cos_incident * 100));
                         });

TEST(RoughGlassTest, LosesEnergyOnlyToMaskingAndRefractsMostLight) {
    Material glass;
    glass.type = MaterialType::kRoughDielectric;
    glass.roughness = 0.2f;
    glass.ior = 1.5f;
    Rng rng(3);
    constexpr int kSamples = 200000;
    double carried = 0;
    int transmitted = 0;
    for (int i = 0; i < kSamples; ++i) {
        const SpecularBounce bounce =
            ScatterNonDiffuse(BsdfOf(glass), Normalize(Vec3(0.3f, 0, -1)), {0, 0, 1}, true,
                              Rgb(1.0f), rng.State(), kCarriesFlux);
        ASSERT_LE(MaxComponent(bounce.weight), 1.0f + 1e-5f);
        carried += Average(bounce.weight);
        if (bounce.transmitted) {
            ++transmitted;
            ASSERT_LT(bounce.direction.z, 0) << "a refracted direction goes into the glass";
        }
    }
    EXPECT_GT(carried / kSamples, 0.9);
    EXPECT_NEAR(double(transmitted) / kSamples, 0.95, 0.03)
        << "about 4% of light is reflected at near-normal incidence";
}

// A camera path through rough glass carries radiance, which a refraction scales by
// (eta_i / eta_t)^2 as at smooth glass (specular_test.cpp); the same numbers give the same
// microfacet and branch, so the two weights differ by that factor alone on every refraction.
TEST(RoughGlassTest, RefractedRadianceScalesByEtaSquared) {
    Material glass;
    glass.type = MaterialType::kRoughDielectric;
    glass.roughness = 0.3f;
    glass.ior = 1.33f;
    int refracted = 0;
    for (const bool front : {true, false}) {
        const Vec3 d = Normalize(Vec3(0.2f, 0.1f, front ? -1.0f : 1.0f));
        const float expected = front ? 1 / (1.33f * 1.33f) : 1.33f * 1.33f;
        for (uint64_t seed = 0; seed < 2000; ++seed) {
            Rng flux_rng(seed), radiance_rng(seed);
            const SpecularBounce flux = ScatterNonDiffuse(
                BsdfOf(glass), d, {0, 0, 1}, front, Rgb(1.0f), flux_rng.State(), kCarriesFlux);
            const SpecularBounce radiance =
                ScatterNonDiffuse(BsdfOf(glass), d, {0, 0, 1}, front, Rgb(1.0f),
                                  radiance_rng.State(), kCarriesRadiance);
            ASSERT_EQ(flux.transmitted, radiance.transmitted);
            if (!flux.transmitted || IsBlack(flux.weight)) {
                ASSERT_EQ(flux.weight, radiance.weight);
                continue;
            }
            ++refracted;
            ASSERT_NEAR(radiance.weight.x, flux.weight.x * expected, 1e-5f * expected);
        }
    }
    EXPECT_GT(refracted, 2000) << "most of the samples refract";
}

}  // namespace
}  // namespace pf
