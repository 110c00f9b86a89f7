// A metal's Fresnel term (core/shared/conductor.h): the complex index's reflectance against
// the textbook formula in complex arithmetic, its limits (normal incidence, a dielectric's
// k = 0, grazing), Schlick's and the reflectance kind's definitions, the named metals' indices
// against their spectral reflectance, extreme indices, and rough metal's sampling agreeing
// with its evaluation once the term varies with angle.
#include "core/shared/conductor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "core/sampling/rng.h"
#include "core/sampling/sampling.h"
#include "core/scene/scattering.h"
#include "core/scene_io/pbrt/pbrt_parameters.h"

namespace pf {
namespace {

using gpu::ConductorFresnel;
using gpu::FresnelComplex;

// The Fresnel equations in complex arithmetic (Born and Wolf; pbrt-v4's FrComplex), double.
double FresnelReference(double cos_i, double eta, double k) {
    const std::complex<double> n(eta, k);
    const double sin2 = 1 - cos_i * cos_i;
    const std::complex<double> cos_t = std::sqrt(1.0 - sin2 / (n * n));
    const std::complex<double> parallel = (n * cos_i - cos_t) / (n * cos_i + cos_t);
    const std::complex<double> perpendicular = (cos_i - n * cos_t) / (cos_i + n * cos_t);
    return (std::norm(parallel) + std::norm(perpendicular)) / 2;
}

TEST(ConductorTest, ComplexIndexReflectsAsTheFresnelEquations) {
    for (const double eta : {0.05, 0.2, 0.9, 1.0, 1.5, 3.0})
        for (const double k : {0.0, 0.5, 2.6, 7.0, 30.0})
            for (int i = 0; i <= 40; ++i) {
                const double cos_i = std::max(i / 40.0, 1e-4);
                EXPECT_NEAR(FresnelComplex(float(cos_i), float(eta), float(k)),
                            FresnelReference(cos_i, eta, k), 2e-5)
                    << "eta " << eta << ", k " << k << ", cos " << cos_i;
            }
}

TEST(ConductorTest, LimitsAreTheTextbooks) {
    for (const float eta : {0.3f, 1.2f, 2.5f})
        for (const float k : {0.0f, 1.0f, 4.0f}) {
            EXPECT_NEAR(FresnelComplex(1, eta, k),
                        ((eta - 1) * (eta - 1) + k * k) / ((eta + 1) * (eta + 1) + k * k), 1e-6f);
            EXPECT_NEAR(FresnelComplex(0, eta, k), 1.0f, 1e-6f) << "grazing light is all reflected";
        }
    // k = 0 above index 1 is a dielectric seen from outside.
    for (int i = 1; i <= 20; ++i)
        EXPECT_NEAR(FresnelComplex(i / 20.0f, 1.5f, 0), gpu::FresnelDielectric(i / 20.0f, 1 / 1.5f),
                    1e-6f);
}

TEST(ConductorTest, EachKindIsItsDefinition) {
    const Rgb tint(0.9f, 0.5f, 0.2f);
    const gpu::Conductor plain{gpu::kConductorTint, Rgb(1.0f), Rgb(0.0f)};
    const gpu::Conductor schlick{gpu::kConductorSchlick, Rgb(1.0f), Rgb(0.0f)};
    const gpu::Conductor reflectance{gpu::kConductorReflectance, Rgb(1.0f), Rgb(0.0f)};
    const gpu::Conductor complex{gpu::kConductorComplex, Rgb(0.2f, 0.4f, 1.4f),
                                 Rgb(3.0f, 2.7f, 1.8f)};
    for (const float cos_i : {0.0f, 0.3f, 1.0f}) {
        EXPECT_EQ(ConductorFresnel(plain, cos_i, tint, 1), tint);
        const float w = std::pow(1 - cos_i, 5.0f);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(ConductorFresnel(schlick, cos_i, tint, 1)[c], tint[c] + (1 - tint[c]) * w,
                        1e-6f);
            const float k = 2 * std::sqrt(tint[c] / (1 - tint[c]));
            EXPECT_NEAR(ConductorFresnel(reflectance, cos_i, tint, 1)[c],
                        FresnelComplex(cos_i, 1, k), 1e-6f);
            // Tinted, and relative to the medium outside (a coat's index divides it).
            EXPECT_NEAR(ConductorFresnel(complex, cos_i, tint, 1.5f)[c],
                        tint[c] * FresnelComplex(cos_i, complex.eta[c] / 1.5f, complex.k[c] / 1.5f),
                        1e-6f);
        }
    }
    EXPECT_NEAR(ConductorFresnel(reflectance, 1, tint, 1).y, 0.5f, 1e-5f)
        << "a reflectance is what is reflected at normal incidence";
    const float white = ConductorFresnel(reflectance, 1, Rgb(1.0f), 1).x;
    EXPECT_TRUE(white > 0.999f && white <= 1.0f) << "a white reflectance reflects all: " << white;
}

TEST(ConductorTest, NamedMetalsReflectTheirSpectrumsColourHeadOn) {
    for (const char* metal : {"Ag", "Al", "Au", "Cu", "CuZn", "MgO", "TiO2"}) {
        const std::string eta = std::string("metal-") + metal + "-eta";
        const std::optional<pbrt::ComplexIndex> index = pbrt::NamedMetalIndex(eta);
        const std::optional<Rgb> reflectance = pbrt::NamedMetalReflectance(eta);
        ASSERT_TRUE(index && reflectance) << metal;
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(FresnelComplex(1, index->eta[c], index->k[c]),
                        std::min((*reflectance)[c], 0.999f), 1e-4f)
                << metal << " channel " << c;
        EXPECT_EQ(pbrt::NamedMetalIndex(std::string("metal-") + metal + "-k")->k, index->k);
    }
    EXPECT_FALSE(pbrt::NamedMetalIndex("glass-BK7"));
}

TEST(ConductorTest, ExtremeIndicesStayInZeroOne) {
    for (const float eta : {1e-6f, 1e-3f, 1.0f, 1e3f, 9999.0f})
        for (const float k : {0.0f, 1e-6f, 1e3f, 9999.0f})
            for (const float cos_i : {0.0f, 1e-7f, 0.5f, 1.0f}) {
                const float f = FresnelComplex(cos_i, eta, k);
                EXPECT_TRUE(f >= 0 && f <= 1) << eta << " " << k << " " << cos_i << ": " << f;
            }
}

// Gold's rough metal: E[weight] of the sampler per channel equals the integral of its
// evaluation (the Fresnel term taken at the same facet by both).
TEST(ConductorTest, RoughGoldSamplesAsItEvaluates) {
    Material gold;
    gold.type = MaterialType::kRoughConductor;
    gold.roughness = 0.3f;
    gold.conductor = gpu::kConductorComplex;
    gold.conductor_eta = pbrt::NamedMetalIndex("metal-Au-eta")->eta;
    gold.conductor_k = pbrt::NamedMetalIndex("metal-Au-eta")->k;
    const Vec3 n(0, 0, 1);
    for (const float cos_incident : {0.9f, 0.2f}) {
        const Vec3 d(std::sqrt(1 - cos_incident * cos_incident), 0, -cos_incident);
        constexpr int kSamples = 400000;
        Rng rng(11);
        Rgbd sampled(0.0), integrated(0.0);
        for (int i = 0; i < kSamples; ++i) {
            sampled += Rgbd(ScatterNonDiffuse(BsdfOf(gold), d, n, true, Rgb(1.0f), rng.State(),
                                              kCarriesRadiance)
                                .weight);
            Vec3 wi = SampleUniformSphere(rng.NextFloat(), rng.NextFloat());
            wi.z = std::abs(wi.z);
            integrated +=
                Rgbd(EvaluateRoughConductor(BsdfOf(gold), Rgb(1.0f), n, -d, wi).value) * 2 * kPi;
        }
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(sampled[c] / kSamples, integrated[c] / kSamples,
                        0.02 * integrated[c] / kSamples)
                << "cos " << cos_incident << ", channel " << c;
    }
}

}  // namespace
}  // namespace pf
