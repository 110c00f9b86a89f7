// Fresnel and specular scattering: known values, Snell's law, and energy conservation.
#include <gtest/gtest.h>

#include <cmath>

#include "core/sampling/rng.h"
#include "core/sampling/sampling.h"
#include "core/scene/scattering.h"

namespace pf {
namespace {

Material Glass(MaterialType type = MaterialType::kDielectric) {
    Material m;
    m.type = type;
    m.base_color = Rgb(1.0f);
    m.ior = 1.5f;
    return m;
}

TEST(FresnelTest, NormalIncidenceAndGrazingAndTotalInternalReflection) {
    EXPECT_NEAR(FresnelDielectric(1.0f, 1.0f / 1.5f), 0.04f, 1e-6f);  // ((n-1)/(n+1))^2
    EXPECT_NEAR(FresnelDielectric(0.0f, 1.0f / 1.5f), 1.0f, 1e-6f);
    const float critical_cos = std::sqrt(1.0f - 1.0f / (1.5f * 1.5f));
    EXPECT_EQ(FresnelDielectric(critical_cos - 0.01f, 1.5f), 1.0f);
    EXPECT_LT(FresnelDielectric(critical_cos + 0.01f, 1.5f), 1.0f);
}

TEST(FresnelTest, ReflectanceIsTheSameFromBothSides) {
    // Stokes reciprocity: R(theta_i, n1->n2) == R(theta_t, n2->n1).
    for (float cos_i = 0.05f; cos_i <= 1.0f; cos_i += 0.05f) {
        const float eta = 1.0f / 1.5f;
        const float cos_t = std::sqrt(1.0f - eta * eta * (1.0f - cos_i * cos_i));
        EXPECT_NEAR(FresnelDielectric(cos_i, eta), FresnelDielectric(cos_t, 1.0f / eta), 1e-5f);
    }
}

TEST(SpecularTest, RefractionObeysSnellsLaw) {
    const Vec3 n(0, 0, 1);
    Rng rng(3);
    for (int i = 0; i < 1000; ++i) {
        Vec3 d = SampleUniformSphere(rng.NextFloat(), rng.NextFloat());
        if (d.z > -0.01f) d.z = -std::abs(d.z) - 0.01f;
        d = Normalize(d);
        Vec3 t;
        ASSERT_TRUE(Refract(d, n, 1.0f / 1.5f, t));
        const float sin_i = std::sqrt(std::max(0.0f, 1 - d.z * d.z)),
                    sin_t = std::sqrt(std::max(0.0f, 1 - t.z * t.z));
        EXPECT_NEAR(sin_i, 1.5f * sin_t, 1e-4f);
        EXPECT_LT(t.z, 0.0f);
        EXPECT_NEAR(Length(t), 1.0f, 1e-5f);
    }
}

TEST(SpecularTest, ClearGlassConservesEnergyAndReflectsAtTheFresnelRate) {
    // Every branch of clear glass carries flux with weight 1, and reflection happens with
    // probability F: reflected + transmitted energy is exactly the incident energy.
    const Material glass = Glass();
    for (float cos_i : {0.1f, 0.5f, 0.9f, 1.0f}) {
        const Vec3 d(std::sqrt(1 - cos_i * cos_i), 0, -cos_i);
        Rng rng(7);
        int reflected = 0;
        constexpr int kTrials = 200000;
        for (int i = 0; i < kTrials; ++i) {
            const SpecularBounce b = ScatterSpecular(BsdfOf(glass), d, Vec3(0, 0, 1), true,
                                                     Rgb(1.0f), rng.NextFloat(), kCarriesFlux);
            ASSERT_EQ(b.weight, Rgb(1.0f));
            reflected += !b.transmitted;
        }
        const double f = FresnelDielectric(cos_i, 1.0f / 1.5f);
        const double sigma = std::sqrt(f * (1 - f) / kTrials);
        EXPECT_NEAR(double(reflected) / kTrials, f, 5 * sigma + 1e-6);
    }
}

// Radiance refracted into glass of index 1.5 is 1.5^2 times the radiance outside (L / eta^2
// is invariant: Veach 1997, section 5.2), so a camera path entering glass carries 1 / 1.5^2 of
// what it finds inside, and one leaving carries 1.5^2; photons carry flux, which refraction
// does not scale. The reflected branch is never scaled.
TEST(SpecularTest, RefractionScalesRadianceByEtaSquaredAndFluxNot) {
    const Material glass = Glass();
    const Vec3 in = Normalize(Vec3(0.3f, 0, -1));
    const Vec3 out = Normalize(Vec3(0.2f, 0, 1));  // inside, within the critical angle
    constexpr float kUTransmit = 0.999f;           // above every Fresnel reflectance here
    const auto weight = [&](const Vec3& d, bool front, uint32_t carries) {
        const SpecularBounce b =
            ScatterSpecular(BsdfOf(glass), d, Vec3(0, 0, 1), front, Rgb(1.0f), kUTransmit, carries);
        EXPECT_TRUE(b.transmitted);
        return b.weight.x;
    };
    EXPECT_FLOAT_EQ(weight(in, true, kCarriesRadiance), 1.0f / (1.5f * 1.5f));
    EXPECT_FLOAT_EQ(weight(out, false, kCarriesRadiance), 1.5f * 1.5f);
    EXPECT_FLOAT_EQ(weight(in, true, kCarriesFlux), 1.0f);
    EXPECT_FLOAT_EQ(weight(out, false, kCarriesFlux), 1.0f);
    EXPECT_FLOAT_EQ(RefractionOf(BsdfOf(glass), true), 1.0f / (1.5f * 1.5f));
    EXPECT_FLOAT_EQ(RefractionOf(BsdfOf(Glass(MaterialType::kThinDielectric)), true), 1.0f);
    const SpecularBounce reflected =
        ScatterSpecular(BsdfOf(glass), in, Vec3(0, 0, 1), true, Rgb(1.0f), 0.0f, kCarriesRadiance);
    EXPECT_FALSE(reflected.transmitted);
    EXPECT_EQ(reflected.weight, Rgb(1.0f));
}

TEST(SpecularTest, LeavingGlassAtGrazingAngleReflectsTotally) {
    const Material glass = Glass();
    const Vec3 d = Normalize(Vec3(0.9f, 0, 0.3f));  // inside, heading out through the back face
    for (float u : {0.0f, 0.5f, 0.999f}) {
        const SpecularBounce b =
            ScatterSpecular(BsdfOf(glass), d, Vec3(0, 0, 1), false, Rgb(1.0f), u, kCarriesRadiance);
        EXPECT_FALSE(b.transmitted);
        EXPECT_NEAR(b.direction.z, -0.3f / Length(Vec3(0.9f, 0, 0.3f)), 1e-5f);
    }
}

TEST(SpecularTest, ThinGlassPassesStraightThroughAndConservesEnergy) {
    const Material sheet = Glass(MaterialType::kThinDielectric);
    const Vec3 d = Normalize(Vec3(0.3f, 0.2f, -1.0f));
    Rng rng(9);
    for (int i = 0; i < 1000; ++i) {
        const SpecularBounce b = ScatterSpecular(BsdfOf(sheet), d, Vec3(0, 0, 1), true, Rgb(1.0f),
                                                 rng.NextFloat(), kCarriesRadiance);
        EXPECT_EQ(b.weight, Rgb(1.0f));  // out on the side it came from: no change of index
        if (b.transmitted)
            EXPECT_EQ(b.direction, d);
        else
            EXPECT_NEAR(b.direction.z, -d.z, 1e-6f);
    }
}

TEST(SpecularTest, MirrorReflectsWithItsTint) {
    Material mirror;
    mirror.type = MaterialType::kMirror;
    const Vec3 d = Normalize(Vec3(1, 0, -1));
    const SpecularBounce b =
        ScatterSpecular(BsdfOf(mirror), d, Vec3(0, 0, 1), true, Rgb(0.9f), 0.5f, kCarriesRadiance);
    EXPECT_FALSE(b.transmitted);
    EXPECT_NEAR(b.direction.x, d.x, 1e-6f);
    EXPECT_NEAR(b.direction.z, -d.z, 1e-6f);
    EXPECT_EQ(b.weight, Rgb(0.9f));
}

}  // namespace
}  // namespace pf
