// Fresnel and specular scattering: known values, Snell's law, and energy conservation.
#include "core/scene/specular.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/sampling/rng.h"
#include "core/sampling/sampling.h"

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
    // Every branch of clear glass carries weight 1, and reflection happens with probability F:
    // reflected + transmitted energy is exactly the incident energy.
    const Material glass = Glass();
    for (float cos_i : {0.1f, 0.5f, 0.9f, 1.0f}) {
        const Vec3 d(std::sqrt(1 - cos_i * cos_i), 0, -cos_i);
        Rng rng(7);
        int reflected = 0;
        constexpr int kTrials = 200000;
        for (int i = 0; i < kTrials; ++i) {
            const SpecularBounce b =
                ScatterSpecular(glass, d, Vec3(0, 0, 1), true, Rgb(1.0f), rng.NextFloat());
            ASSERT_EQ(b.weight, Rgb(1.0f));
            reflected += !b.transmitted;
        }
        const double f = FresnelDielectric(cos_i, 1.0f / 1.5f);
        const double sigma = std::sqrt(f * (1 - f) / kTrials);
        EXPECT_NEAR(double(reflected) / kTrials, f, 5 * sigma + 1e-6);
    }
}

TEST(SpecularTest, LeavingGlassAtGrazingAngleReflectsTotally) {
    const Material glass = Glass();
    const Vec3 d = Normalize(Vec3(0.9f, 0, 0.3f));  // inside, heading out through the back face
    for (float u : {0.0f, 0.5f, 0.999f}) {
        const SpecularBounce b = ScatterSpecular(glass, d, Vec3(0, 0, 1), false, Rgb(1.0f), u);
        EXPECT_FALSE(b.transmitted);
        EXPECT_NEAR(b.direction.z, -0.3f / Length(Vec3(0.9f, 0, 0.3f)), 1e-5f);
    }
}

TEST(SpecularTest, ThinGlassPassesStraightThroughAndConservesEnergy) {
    const Material sheet = Glass(MaterialType::kThinDielectric);
    const Vec3 d = Normalize(Vec3(0.3f, 0.2f, -1.0f));
    Rng rng(9);
    for (int i = 0; i < 1000; ++i) {
        const SpecularBounce b =
            ScatterSpecular(sheet, d, Vec3(0, 0, 1), true, Rgb(1.0f), rng.NextFloat());
        EXPECT_EQ(b.weight, Rgb(1.0f));
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
    const SpecularBounce b = ScatterSpecular(mirror, d, Vec3(0, 0, 1), true, Rgb(0.9f), 0.5f);
    EXPECT_FALSE(b.transmitted);
    EXPECT_NEAR(b.direction.x, d.x, 1e-6f);
    EXPECT_NEAR(b.direction.z, -d.z, 1e-6f);
    EXPECT_EQ(b.weight, Rgb(0.9f));
}

}  // namespace
}  // namespace pf
