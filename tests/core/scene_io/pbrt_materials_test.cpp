// The pbrt-v4 importer's materials and what shapes bring to them: each material's parameters
// against pbrt-v4's definitions (coats, conductors, glass), shapes' alpha cut-outs and float
// textures, and the errors bad values get.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "core/scene/scattering.h"
#include "core/scene_io/pbrt/pbrt_parameters.h"
#include "core/scene_io/scene_files.h"
#include "tests/core/scene_io/pbrt_test_support.h"
#include "tests/support/test_env.h"

namespace pf {
namespace {

using namespace pbrt_test;

TEST(PbrtMaterialsTest, MaterialsMapOntoPhotonfarms) {
    const std::string world =
        std::string(
            "MakeNamedMaterial \"gold\" \"string type\" \"conductor\" \"spectrum eta\" "
            "\"metal-Au-eta\" \"spectrum k\" \"metal-Au-k\"\n") +
        "NamedMaterial \"gold\"\n" + kQuad + "Material \"dielectric\" \"float eta\" 1.33\n" +
        kQuad + "Material \"dielectric\" \"spectrum eta\" \"glass-BK7\"\n" + kQuad +
        "Material \"coateddiffuse\" \"rgb reflectance\" [0.2 0.4 0.6] \"float roughness\" 0.1\n" +
        kQuad + "Material \"conductor\" \"rgb reflectance\" [0.9 0.9 0.9]\n" + kQuad +
        "Material \"thindielectric\"\n" + kQuad;
    std::vector<std::string> warnings;
    const absl::StatusOr<Scene> scene = Load(Bundle(world), &warnings);
    ASSERT_TRUE(scene.ok()) << scene.status();
    ASSERT_EQ(scene->materials.size(), 6u);
    // Gold: its complex index, whose normal-incidence reflectance is the spectrum's (red high,
    // blue low), reflected as the Fresnel term of that index (core/shared/conductor.h).
    const Material& gold = scene->materials[0];
    EXPECT_EQ(gold.type, MaterialType::kMirror);
    EXPECT_EQ(gold.conductor, gpu::kConductorComplex);
    EXPECT_EQ(gold.base_color, Rgb(1.0f));
    EXPECT_NEAR(gpu::FresnelComplex(1, gold.conductor_eta.x, gold.conductor_k.x), 0.999f, 1e-4f);
    EXPECT_NEAR(gpu::FresnelComplex(1, gold.conductor_eta.z, gold.conductor_k.z), 0.336f, 1e-4f);
    EXPECT_NEAR(gold.conductor_eta.z, 1.3816f, 1e-4f);  // pbrt-v4's eta at 464 nm
    EXPECT_EQ(scene->materials[1].type, MaterialType::kDielectric);
    EXPECT_NEAR(scene->materials[1].ior, 1.33f, 1e-6f);
    EXPECT_NEAR(scene->materials[2].ior, 1.5185f, 1e-4f);
    EXPECT_EQ(scene->materials[3].type, MaterialType::kDiffuse);
    EXPECT_NEAR(scene->materials[3].base_color.z, 0.6f, 1e-6f);
    EXPECT_TRUE(scene->materials[3].HasCoat());
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    // A reflectance r is the index 1 + i 2 sqrt(r / (1 - r)), reflecting r at normal incidence.
    const Material& reflector = scene->materials[4];
    EXPECT_EQ(reflector.conductor, gpu::kConductorComplex);
    EXPECT_EQ(reflector.conductor_eta, Rgb(1.0f));
    EXPECT_NEAR(reflector.conductor_k.y, 2 * std::sqrt(0.9f / 0.1f), 1e-4f);
    EXPECT_NEAR(gpu::FresnelComplex(1, 1, reflector.conductor_k.y), 0.9f, 1e-5f);
    EXPECT_EQ(scene->materials[5].type, MaterialType::kThinDielectric);
}

TEST(PbrtMaterialsTest, ADielectricsEtaMayBeBelowOneButNotZero) {
    // pbrt-v4 takes any positive eta: below 1, the front side is the denser one
    // (bitterli/glass-of-water's 0.763, water against glass).
    const absl::StatusOr<Scene> scene =
        Load(Bundle(std::string("Material \"dielectric\" \"float eta\" 0.763\n") + kQuad +
                    "Material \"dielectric\" \"float eta\" 0.5 \"float roughness\" 0.2\n" + kQuad));
    ASSERT_TRUE(scene.ok()) << scene.status();
    ASSERT_EQ(scene->materials.size(), 2u);
    EXPECT_EQ(scene->materials[0].type, MaterialType::kDielectric);
    EXPECT_EQ(scene->materials[0].ior, 0.763f);
    EXPECT_EQ(scene->materials[1].type, MaterialType::kRoughDielectric);
    EXPECT_EQ(scene->materials[1].ior, 0.5f);
    for (const char* eta : {"0", "-1.5"})
        ExpectError(
            Load(Bundle(absl::StrCat("Material \"dielectric\" \"float eta\" ", eta, "\n") + kQuad)),
            "scenes/scene.pbrt:6:1: Material \"dielectric\": \"eta\" must be positive and finite");
}

TEST(PbrtMaterialsTest, ConductorsTakeAReflectanceOrAComplexIndex) {
    const std::string world =
        std::string(
            "Texture \"tint\" \"spectrum\" \"imagemap\" \"string filename\" \"tint.png\" "
            "\"string wrap\" \"clamp\"\n"
            "Material \"conductor\" \"texture reflectance\" \"tint\"\n") +
        kQuad + "Material \"conductor\" \"rgb eta\" [0.2 0.9 1.1] \"float k\" 3\n" + kQuad +
        "Material \"conductor\" \"spectrum k\" \"metal-Ag-k\"\n" + kQuad;
    const std::string png = TwoTexelPng({250, 200, 40, 60, 120, 250}, "photonfarm-pbrt-tint.png");
    ASSERT_FALSE(png.empty());
    const absl::StatusOr<Scene> scene = Load(Bundle(world, {{"tint.png", png}}));
    ASSERT_TRUE(scene.ok()) << scene.status();
    ASSERT_EQ(scene->materials.size(), 3u);
    // A textured reflectance: each texel's index, found where light meets it.
    EXPECT_EQ(scene->materials[0].conductor, gpu::kConductorReflectance);
    ASSERT_NE(scene->materials[0].base_color_texture, kNoTexture);
    EXPECT_EQ(scene->textures[scene->materials[0].base_color_texture]->wrap_v, gpu::kWrapClamp);
    EXPECT_EQ(scene->materials[1].conductor_eta, Rgb(0.2f, 0.9f, 1.1f));
    EXPECT_EQ(scene->materials[1].conductor_k, Rgb(3.0f));
    // eta not given is copper's, as pbrt-v4's default; k silver's, as named.
    EXPECT_EQ(scene->materials[2].conductor_eta, pbrt::NamedMetalIndex("metal-Cu-eta")->eta);
    EXPECT_EQ(scene->materials[2].conductor_k, pbrt::NamedMetalIndex("metal-Ag-k")->k);

    ExpectError(Load(Bundle(std::string("Material \"conductor\" \"rgb reflectance\" [0.5 0.5 "
                                        "0.5] \"float k\" 3\n") +
                            kQuad)),
                "Material \"conductor\": give \"reflectance\" or \"eta\" and \"k\", not both");
    ExpectError(Load(Bundle(std::string("Material \"conductor\" \"rgb eta\" [0 1 1]\n") + kQuad)),
                "\"eta\" must lie in (0, 1e4) and \"k\" in [0, 1e4)");
}

// pbrt-v4's checkerboard and bilerp textures at (s, t) = (uscale u + udelta, vscale v + vdelta).
TEST(PbrtMaterialsTest, CheckerboardAndBilerpAreBakedAsPbrtEvaluatesThem) {
    const std::string world =
        std::string(
            "Texture \"checks\" \"spectrum\" \"checkerboard\" \"rgb tex1\" [0.9 0.1 0.1] "
            "\"rgb tex2\" [0.1 0.1 0.9] \"float uscale\" 4 \"float vscale\" 4\n"
            "Texture \"ramp\" \"float\" \"bilerp\" \"float v00\" 0.1 \"float v01\" 0.3 "
            "\"float v10\" 0.5 \"float v11\" 0.9\n"
            "Material \"diffuse\" \"texture reflectance\" \"checks\"\n") +
        "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 1 1 0] \"integer indices\" [0 1 2] "
        "\"point2 uv\" [0 0 1 0 1 1]\n"
        "Material \"conductor\" \"texture roughness\" \"ramp\" \"bool remaproughness\" false\n"
        "Shape \"trianglemesh\" \"point3 P\" [0 0 1 1 0 1 1 1 1] \"integer indices\" [0 1 2] "
        "\"point2 uv\" [0 0 1 0 1 1]\n";
    const absl::StatusOr<Scene> scene = Load(Bundle(world));
    ASSERT_TRUE(scene.ok()) << scene.status();
    // Each surface point's texture value, at the barycentre of a small triangle around (u, v).
    const auto value_at = [&](uint32_t triangle, int32_t texture, float u, float v) {
        const uint32_t* corner = scene->triangles[triangle].vertex;
        // The triangle's uvs are (0,0), (1,0), (1,1), mapped by the texture's transform:
        // barycentrics b1 = u - v, b2 = v reach (u, v).
        const Point2 a = scene->uvs[corner[0]], b = scene->uvs[corner[1]],
                     c = scene->uvs[corner[2]];
        const float b1 = u - v, b2 = v;
        const Point2 at{a.x + b1 * (b.x - a.x) + b2 * (c.x - a.x),
                        a.y + b1 * (b.y - a.y) + b2 * (c.y - a.y)};
        return scene->textures[texture]->Sample(at.x, at.y);
    };
    const Material& checked = scene->materials[scene->triangles[0].material];
    ASSERT_NE(checked.base_color_texture, kNoTexture);
    for (const auto& [u, v] : {std::pair{0.1f, 0.05f}, std::pair{0.3f, 0.05f},
                               std::pair{0.9f, 0.6f}, std::pair{0.6f, 0.35f}}) {
        const bool even = (int(std::floor(4 * u)) + int(std::floor(4 * v))) % 2 == 0;
        const Rgb expected = even ? Rgb(0.9f, 0.1f, 0.1f) : Rgb(0.1f, 0.1f, 0.9f);
        const Rgb got = value_at(0, checked.base_color_texture, u, v) * checked.base_color;
        EXPECT_NEAR(got.x, expected.x, 1e-5f) << u << ", " << v;
        EXPECT_NEAR(got.z, expected.z, 1e-5f) << u << ", " << v;
    }
    EXPECT_EQ(scene->textures[checked.base_color_texture]->wrap_u, gpu::kWrapRepeat);
    const Material& ramped = scene->materials[scene->triangles[1].material];
    ASSERT_NE(ramped.roughness_texture, kNoTexture);
    for (const auto& [u, v] : {std::pair{0.5f, 0.25f}, std::pair{0.8f, 0.3f}}) {
        const float bilerp =
            0.1f * (1 - u) * (1 - v) + 0.3f * (1 - u) * v + 0.5f * u * (1 - v) + 0.9f * u * v;
        EXPECT_NEAR(value_at(1, ramped.roughness_texture, u, v).x * ramped.roughness, bilerp,
                    1e-5f);
    }
}

// A medium is read at the surfaces that bound it: MediumInterface's inside behind a shape, its
// outside in front (a liquid around the glass that holds it), one name for both sides.
TEST(PbrtMaterialsTest, MediaAbsorbOnTheSidesOfTheSurfacesThatBoundThem) {
    const std::string world =
        std::string(
            "MakeNamedMedium \"ink\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [0.1 0.2 "
            "0.3] \"float scale\" 10\n"
            "MakeNamedMedium \"tea\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [0.5 0.25 "
            "0.125] \"rgb sigma_s\" [0 0 0]\n"
            "MakeNamedMedium \"smoke\" \"string type\" \"uniformgrid\"\n"
            "AttributeBegin\nMediumInterface \"ink\" \"\"\nMaterial \"dielectric\"\n") +
        kQuad + "Material \"diffuse\"\n" + kQuad + "AttributeEnd\n" + "Material \"dielectric\"\n" +
        kQuad + "MediumInterface \"smoke\"\n" + kQuad + "MediumInterface \"\" \"tea\"\n" + kQuad +
        "MediumInterface \"tea\"\n" + kQuad +
        "AttributeBegin\nMaterial \"interface\"\nMediumInterface \"ink\" \"\"\n" + kQuad +
        "AttributeEnd\n";
    std::vector<std::string> warnings;
    const absl::StatusOr<Scene> scene = Load(Bundle(world), &warnings);
    ASSERT_TRUE(scene.ok()) << scene.status();
    const auto material_of = [&](size_t quad) {
        return scene->materials[scene->triangles[2 * quad].material];
    };
    // sigma_a x scale inside the glass; pbrt-v4's default sigma_s (1) is scattering, noted.
    EXPECT_EQ(material_of(0).absorption, Rgb(1.0f, 2.0f, 3.0f));
    EXPECT_EQ(material_of(0).outside_absorption, Rgb(0.0f));
    EXPECT_EQ(material_of(1).absorption, Rgb(1.0f, 2.0f, 3.0f)) << "any surface bounds a medium";
    EXPECT_FALSE(material_of(2).HasVolume()) << "AttributeEnd restores no medium";
    EXPECT_FALSE(material_of(3).HasVolume()) << "a grid medium is left out";
    EXPECT_EQ(material_of(4).absorption, Rgb(0.0f));
    EXPECT_EQ(material_of(4).outside_absorption, Rgb(0.5f, 0.25f, 0.125f)) << "tea outside";
    EXPECT_EQ(material_of(5).absorption, Rgb(0.5f, 0.25f, 0.125f)) << "one name: both sides";
    EXPECT_EQ(material_of(5).outside_absorption, Rgb(0.5f, 0.25f, 0.125f));
    EXPECT_EQ(scene->triangles.size(), 12u) << "the interface shape is left out";
    EXPECT_TRUE(Contains(warnings, "scattering (sigma_s) is left out; the medium absorbs only"));
    EXPECT_TRUE(Contains(warnings, "\"uniformgrid\" media are not rendered"));
    EXPECT_TRUE(Contains(warnings, "the medium \"ink\" of \"interface\" shapes (no surface)"));
    EXPECT_TRUE(Contains(warnings, "light sampled from it is not attenuated by the medium"))
        << "the diffuse quad in ink";
    for (const std::string& warning : warnings)
        EXPECT_FALSE(absl::StartsWith(warning, ":1:1:")) << warning << ": a location of none";

    ExpectError(Load(Bundle(std::string("MediumInterface \"fog\" \"\"\n") + kQuad)),
                "MediumInterface: no medium named \"fog\"");
    ExpectError(Load(Bundle(std::string("MediumInterface \"\" \"fog\"\n") + kQuad)),
                "MediumInterface: no medium named \"fog\"");
    ExpectError(Load(Bundle(std::string("MakeNamedMedium \"ink\" \"string type\" "
                                        "\"homogeneous\" \"rgb sigma_a\" [-1 0 0]\n") +
                            kQuad)),
                "sigma_a, sigma_s and scale must be finite and not negative");
}

// pbrt-v4 refuses a sampler it does not know; so does photonfarm, naming pbrt-v4's.
TEST(PbrtMaterialsTest, AnUnknownSamplerIsAnError) {
    SceneBundle bundle = Bundle(kQuad);
    bundle.files["scene.pbrt"] = "Sampler \"zsobl\"\n" + bundle.files["scene.pbrt"];
    ExpectError(Load(bundle), "scenes/scene.pbrt:1:1: Sampler \"zsobl\" is not one of pbrt-v4's");
}

TEST(PbrtMaterialsTest, ATexturedCoatThicknessIsNamedAndTheDefaultUsed) {
    // pbrt-v4 takes a float texture for a coat's thickness (kroken's moka pot); photonfarm's
    // coat has one thickness: pbrt-v4's default 0.01, with a warning naming the texture.
    const std::string world =
        std::string("Texture \"t\" \"float\" \"constant\" \"float value\" 0.3\n") +
        "Material \"coatedconductor\" \"texture thickness\" \"t\"\n" + kQuad;
    std::vector<std::string> warnings;
    const absl::StatusOr<Scene> scene = Load(Bundle(world), &warnings);
    ASSERT_TRUE(scene.ok()) << scene.status();
    ASSERT_EQ(scene->materials.size(), 1u);
    EXPECT_EQ(scene->materials[0].coat_thickness, 0.01f);
    EXPECT_TRUE(Contains(warnings,
                         "Material \"coatedconductor\": \"thickness\" from texture \"t\" "
                         "is not read; the default 0.01 is used"));
}

TEST(PbrtMaterialsTest, CoatsTakePbrtsParameters) {
    const std::string world =
        std::string("Material \"coateddiffuse\"\n") + kQuad +
        "Material \"coateddiffuse\" \"rgb reflectance\" [0.1 0.2 0.3] \"float eta\" 1.33 "
        "\"float roughness\" 0.04 \"float thickness\" 0.2 \"integer maxdepth\" 5 "
        "\"integer nsamples\" 4 \"rgb albedo\" [0.5 0.5 0.5] \"float g\" 0.3\n" +
        kQuad +
        "Material \"coatedconductor\" \"float interface.roughness\" 0.01 \"float "
        "conductor.roughness\" 0.09 \"rgb reflectance\" [0.9 0.5 0.2]\n" +
        kQuad + "Material \"coatedconductor\" \"float interface.eta\" 1\n" + kQuad;
    std::vector<std::string> warnings;
    const absl::StatusOr<Scene> scene = Load(Bundle(world), &warnings);
    ASSERT_TRUE(scene.ok()) << scene.status();
    ASSERT_EQ(scene->materials.size(), 4u);
    // pbrt-v4's defaults: reflectance 0.5, eta 1.5, smooth, thickness 0.01, maxdepth 10.
    const Material& plain = scene->materials[0];
    EXPECT_EQ(plain.type, MaterialType::kDiffuse);
    EXPECT_EQ(plain.base_color, Rgb(0.5f));
    EXPECT_EQ(plain.coat_ior, 1.5f);
    EXPECT_EQ(plain.coat_roughness, 0.0f);
    EXPECT_NEAR(plain.coat_thickness, 0.01f, 1e-7f);
    EXPECT_EQ(plain.coat_depth, 5u);  // visits to the base: maxdepth / 2
    const Material& given = scene->materials[1];
    EXPECT_NEAR(given.coat_ior, 1.33f, 1e-6f);
    EXPECT_NEAR(given.coat_roughness, 0.2f, 1e-6f);  // sqrt(0.04): pbrt remaps roughness
    EXPECT_NEAR(given.coat_thickness, 0.2f, 1e-6f);
    EXPECT_EQ(given.coat_depth, 2u);
    EXPECT_EQ(given.coat_samples, 4u);
    EXPECT_EQ(plain.coat_samples, 1u);
    EXPECT_TRUE(Contains(warnings, "scattering inside the coat (\"albedo\") is left out"));
    // A coated conductor: the metal under the coat, its index kept in vacuum (the coat divides
    // it by its own where light meets the base), reflecting r at normal incidence in air.
    const Material& metal = scene->materials[2];
    EXPECT_EQ(metal.type, MaterialType::kRoughConductor);
    EXPECT_NEAR(metal.roughness, 0.3f, 1e-6f);
    EXPECT_NEAR(metal.coat_roughness, 0.1f, 1e-6f);
    EXPECT_EQ(metal.conductor, gpu::kConductorComplex);
    for (int c = 0; c < 3; ++c) {
        const float r = std::array{0.9f, 0.5f, 0.2f}[c];
        EXPECT_NEAR(metal.conductor_k[c], 2 * std::sqrt(r / (1 - r)), 1e-4f);
        EXPECT_NEAR(metal.conductor_eta[c], 1.0f, 1e-6f);
    }
    // Index 1: the coat bends nothing, and the copper default shows through unchanged.
    const Material& copper = scene->materials[3];
    EXPECT_EQ(copper.type, MaterialType::kMirror);
    EXPECT_EQ(copper.coat_ior, 1.0f);
    EXPECT_NEAR(
        gpu::ConductorFresnel(ConductorOf(copper), 1.0f, copper.base_color, copper.coat_ior).x,
        0.955f, 1e-3f);

    ExpectError(Load(Bundle(std::string("Material \"coateddiffuse\" \"float eta\" 0.5\n") + kQuad)),
                "scenes/scene.pbrt:6:1: Material \"coateddiffuse\": \"eta\" must be at least 1");
    ExpectError(
        Load(Bundle(std::string("Material \"coateddiffuse\" \"float thickness\" -1\n") + kQuad)),
        "\"thickness\" must lie in [0, 1e6]");
    ExpectError(
        Load(Bundle(std::string("Material \"coatedconductor\" \"integer maxdepth\" 0\n") + kQuad)),
        "\"maxdepth\" must lie in [1, 1024]");
    ExpectError(
        Load(Bundle(std::string("Material \"coatedconductor\" \"float conductor.roughness\" -2\n") +
                    kQuad)),
        "conductor.roughness must lie in [0, 1000]");
}

TEST(PbrtMaterialsTest, ShapesTakeAlphaAsANumberOrAFloatTexture) {
    // A 2x1 RGB PNG: a float texture reads its channels' average (pbrt-v4's float imagemap).
    const std::string png = TwoTexelPng({0, 0, 0, 255, 255, 255}, "photonfarm-pbrt-alpha.png");
    ASSERT_FALSE(png.empty());
    const std::string world =
        std::string("Texture \"leaf\" \"float\" \"imagemap\" \"string filename\" \"leaf.png\"\n") +
        "Texture \"back\" \"float\" \"imagemap\" \"string filename\" \"leaf.png\" "
        "\"bool invert\" true\n"
        "Texture \"faint\" \"float\" \"scale\" \"texture tex\" \"leaf\" \"float scale\" 0.5\n"
        "Material \"diffuse\"\nShape \"bilinearmesh\" \"point3 P\" [0 0 0  1 0 0  0 1 0  1 1 0] "
        "\"float alpha\" 0.25\n"
        "Shape \"bilinearmesh\" \"point3 P\" [0 0 1  1 0 1  0 1 1  1 1 1] \"texture alpha\" "
        "\"leaf\"\n"
        "Shape \"bilinearmesh\" \"point3 P\" [0 0 2  1 0 2  0 1 2  1 1 2] \"texture alpha\" "
        "\"back\"\n"
        "Shape \"bilinearmesh\" \"point3 P\" [0 0 3  1 0 3  0 1 3  1 1 3] \"texture alpha\" "
        "\"faint\"\n" +
        kQuad;
    const absl::StatusOr<Scene> scene = Load(Bundle(world, {{"leaf.png", png}}));
    ASSERT_TRUE(scene.ok()) << scene.status();
    // One scene material per (material, alpha): the quad at the end is opaque.
    const auto material_of = [&](size_t shape) {
        return scene->materials[scene->triangles[2 * shape].material];
    };
    EXPECT_EQ(material_of(0).alpha, 0.25f);
    EXPECT_EQ(material_of(0).alpha_texture, kNoTexture);
    EXPECT_EQ(material_of(0).alpha_cutoff, 0.0f) << "pbrt-v4's alpha test is stochastic";
    ASSERT_NE(material_of(1).alpha_texture, kNoTexture);
    const Texture& leaf = *scene->textures[material_of(1).alpha_texture];
    EXPECT_EQ(leaf.texels[0], Rgb(0.0f));
    EXPECT_EQ(leaf.texels[1], Rgb(1.0f));
    const Texture& back = *scene->textures[material_of(2).alpha_texture];
    EXPECT_EQ(back.texels[0], Rgb(1.0f)) << "inverted";
    EXPECT_EQ(material_of(3).alpha, 0.5f);
    EXPECT_EQ(material_of(3).alpha_texture, material_of(1).alpha_texture) << "decoded once";
    EXPECT_FALSE(material_of(4).HasCutOuts());
    // The alpha texture is read at the shape's (u, v): the bilinear patch spans the unit square.
    EXPECT_NEAR(scene->Alpha(2, 0.0f, 0.0f) + scene->Alpha(3, 0.0f, 0.0f), 1.0f, 1e-6f);

    ExpectError(Load(Bundle(std::string("Shape \"sphere\" \"float alpha\" 2\n") + kQuad)),
                "scenes/scene.pbrt:6:1: Shape: \"alpha\" must lie in [0, 1]");
    ExpectError(Load(Bundle(std::string("Shape \"sphere\" \"texture alpha\" \"none\"\n") + kQuad)),
                "Shape: \"alpha\" names no float texture \"none\"");
}

TEST(PbrtMaterialsTest, AMixIsOneOfItsMaterialsAtEachPoint) {
    const std::string world =
        std::string(
            "MakeNamedMaterial \"red\" \"string type\" \"diffuse\" \"rgb reflectance\" [1 0 0]\n") +
        "MakeNamedMaterial \"glass\" \"string type\" \"dielectric\"\n"
        "MakeNamedMaterial \"half\" \"string type\" \"mix\" \"string materials\" [\"red\" "
        "\"glass\"] "
        "\"float amount\" 0.25\n"
        "Material \"mix\" \"string materials\" [\"half\" \"red\"]\n" +
        kQuad;
    const absl::StatusOr<Scene> scene = Load(Bundle(world));
    ASSERT_TRUE(scene.ok()) << scene.status();
    const uint32_t outer = scene->triangles[0].material;
    const Material& mix = scene->materials[outer];
    ASSERT_EQ(mix.type, MaterialType::kMix);
    EXPECT_EQ(mix.mix_amount, 0.5f) << "pbrt's default amount";
    ASSERT_LT(mix.mix_first, outer);
    ASSERT_LT(mix.mix_second, outer);
    EXPECT_EQ(scene->materials[mix.mix_first].type, MaterialType::kMix);
    EXPECT_EQ(scene->materials[mix.mix_first].mix_amount, 0.25f);
    // Over many points: red with probability 1/2 + 1/2 x 3/4, glass 1/2 x 1/4 (nested mixes
    // choose independently).
    constexpr int kPoints = 40000;
    int glass = 0;
    for (int i = 0; i < kPoints; ++i) {
        const Vec3 p(0.001f * float(i % 200), 0.001f * float(i / 200), 0.0f);
        const uint32_t m = scene->ResolveMaterial(outer, p, 0);
        ASSERT_NE(scene->materials[m].type, MaterialType::kMix);
        glass += scene->materials[m].type == MaterialType::kDielectric;
        EXPECT_EQ(scene->ResolveMaterial(outer, p, 0), m) << "the same point, the same material";
    }
    EXPECT_NEAR(double(glass) / kPoints, 0.125, 5 * std::sqrt(0.125 * 0.875 / kPoints));

    ExpectError(
        Load(Bundle(std::string("Material \"mix\" \"string materials\" \"red\"\n") + kQuad)),
        "Material \"mix\" needs \"string materials\" naming two materials");
    ExpectError(
        Load(Bundle(std::string("Material \"mix\" \"string materials\" [\"a\" \"b\"]\n") + kQuad)),
        "Material \"mix\": no material named \"a\"");
    ExpectError(
        Load(Bundle(std::string("MakeNamedMaterial \"a\" \"string type\" \"diffuse\"\n") +
                    "Material \"mix\" \"string materials\" [\"a\" \"a\"] \"float amount\" 2\n" +
                    kQuad)),
        "\"amount\" must lie in [0, 1]");
}

TEST(PbrtMaterialsTest, RoughnessAndMixAmountTakeFloatTextures) {
    // Grey texels 0 and 1 (8-bit sRGB: decoded to linear 0 and 1) and grey 128.
    const std::string png = TwoTexelPng({128, 128, 128, 255, 255, 255}, "photonfarm-rough.png");
    ASSERT_FALSE(png.empty());
    const std::string world =
        std::string("Texture \"r\" \"float\" \"imagemap\" \"string filename\" \"r.png\"\n") +
        "Material \"conductor\" \"texture roughness\" \"r\"\n"
        "Shape \"bilinearmesh\" \"point3 P\" [0 0 0  1 0 0  0 1 0  1 1 0]\n"
        "Material \"conductor\" \"texture roughness\" \"r\" \"bool remaproughness\" false\n"
        "Shape \"bilinearmesh\" \"point3 P\" [0 0 1  1 0 1  0 1 1  1 1 1]\n"
        "Material \"coateddiffuse\" \"texture roughness\" \"r\"\n"
        "Shape \"bilinearmesh\" \"point3 P\" [0 0 2  1 0 2  0 1 2  1 1 2]\n"
        "MakeNamedMaterial \"a\" \"string type\" \"diffuse\"\n"
        "MakeNamedMaterial \"b\" \"string type\" \"conductor\"\n"
        "Material \"mix\" \"string materials\" [\"a\" \"b\"] \"texture amount\" \"r\"\n"
        "Shape \"bilinearmesh\" \"point3 P\" [0 0 3  1 0 3  0 1 3  1 1 3]\n" +
        kQuad;
    const absl::StatusOr<Scene> scene = Load(Bundle(world, {{"r.png", png}}));
    ASSERT_TRUE(scene.ok()) << scene.status();
    const auto material_of = [&](size_t shape) {
        return scene->materials[scene->triangles[2 * shape].material];
    };
    const float grey = SrgbToLinear(128 / 255.0f);
    // Remapped as pbrt-v4's RoughnessToAlpha: alpha = sqrt(roughness), texel by texel.
    const Material& remapped = material_of(0);
    EXPECT_EQ(remapped.type, MaterialType::kRoughConductor);
    EXPECT_FLOAT_EQ(remapped.roughness, 1.0f);
    ASSERT_NE(remapped.roughness_texture, kNoTexture);
    EXPECT_NEAR(scene->textures[remapped.roughness_texture]->texels[0].x, std::sqrt(grey), 1e-6);
    const Material& raw = material_of(1);
    ASSERT_NE(raw.roughness_texture, kNoTexture);
    EXPECT_NEAR(scene->textures[raw.roughness_texture]->texels[0].x, grey, 1e-6);
    // A coat's roughness texture scales the coat's alpha.
    const Material& coated = material_of(2);
    EXPECT_FLOAT_EQ(coated.coat_roughness, 1.0f);
    EXPECT_EQ(coated.roughness_texture, remapped.roughness_texture) << "decoded once";
    SurfacePoint point;
    point.material = scene->triangles[4].material;
    point.uv = {0.25f, 0.5f};
    std::optional<Material> scratch;
    EXPECT_NEAR(scene->ShadingMaterial(point, scratch).coat_roughness, std::sqrt(grey), 1e-3);
    // A mix's amount, texel by texel.
    const Material& mix = material_of(3);
    ASSERT_EQ(mix.type, MaterialType::kMix);
    EXPECT_FLOAT_EQ(mix.mix_amount, 1.0f);
    ASSERT_NE(mix.mix_texture, kNoTexture);
    EXPECT_NEAR(scene->textures[mix.mix_texture]->texels[0].x, grey, 1e-6);
    ExpectError(Load(Bundle(std::string("Material \"conductor\" \"texture roughness\" \"none\"\n") +
                            kQuad)),
                "Material \"conductor\": \"roughness\" names no float texture \"none\"");
}

TEST(PbrtMaterialsTest, DiffuseTransmissionTakesPbrtsParameters) {
    // Texels sRGB 128 and 255 grey: linear 0.216 and 1, mean 0.608.
    const std::string png = TwoTexelPng({128, 128, 128, 255, 255, 255}, "photonfarm-paper.png");
    ASSERT_FALSE(png.empty());
    const std::string world =
        std::string("Material \"diffusetransmission\"\n") + kQuad +
        "Material \"diffusetransmission\" \"rgb reflectance\" [0.2 0.4 0.6] \"rgb "
        "transmittance\" [0.1 0.2 0.3] \"float scale\" 2\n" +
        kQuad +
        "Texture \"paper\" \"spectrum\" \"imagemap\" \"string filename\" \"paper.png\"\n"
        "Material \"diffusetransmission\" \"texture reflectance\" \"paper\" "
        "\"texture transmittance\" \"paper\" \"float scale\" 0.5\n" +
        kQuad;
    std::vector<std::string> warnings;
    const absl::StatusOr<Scene> scene = Load(Bundle(world, {{"paper.png", png}}), &warnings);
    ASSERT_TRUE(scene.ok()) << scene.status();
    ASSERT_EQ(scene->materials.size(), 3u);
    // pbrt-v4's defaults: 0.25 each.
    const Material& plain = scene->materials[0];
    EXPECT_EQ(plain.type, MaterialType::kDiffuse);
    EXPECT_EQ(plain.base_color, Rgb(0.25f));
    EXPECT_EQ(plain.transmittance, Rgb(0.25f));
    EXPECT_TRUE(plain.IsTranslucent());
    // Both times the scale.
    const Material& scaled = scene->materials[1];
    EXPECT_FLOAT_EQ(scaled.base_color.z, 1.0f) << "1.2 clamped to 1, as pbrt-v4";
    EXPECT_FLOAT_EQ(scaled.base_color.x, 0.4f);
    EXPECT_FLOAT_EQ(scaled.transmittance.y, 0.4f);
    // A reflectance texture as any base colour's; a transmittance texture read at the point too.
    const Material& textured = scene->materials[2];
    ASSERT_NE(textured.base_color_texture, kNoTexture);
    EXPECT_FLOAT_EQ(textured.base_color.x, 0.5f);
    ASSERT_NE(textured.transmittance_texture, kNoTexture);
    EXPECT_FLOAT_EQ(textured.transmittance.y, 0.5f);
    for (const std::string& warning : warnings)
        EXPECT_EQ(warning.find("mean colour"), std::string::npos) << warning;
    SurfacePoint surface;
    surface.material = 2;
    surface.uv = {0.25f, 0.5f};  // the first texel
    std::optional<Material> scratch;
    EXPECT_NEAR(scene->ShadingMaterial(surface, scratch).transmittance.y,
                0.5f * SrgbToLinear(128 / 255.0f), 1e-4f);
    // Under another mapping than the reflectance's: its mean colour, noted.
    const absl::StatusOr<Scene> planar = Load(
        Bundle(std::string("Texture \"paper\" \"spectrum\" \"imagemap\" \"string filename\" "
                           "\"paper.png\"\nTexture \"flat\" \"spectrum\" \"imagemap\" \"string "
                           "filename\" \"paper.png\" \"string mapping\" \"planar\"\n"
                           "Material \"diffusetransmission\" \"texture reflectance\" \"paper\" "
                           "\"texture transmittance\" \"flat\"\n") +
                   kQuad,
               {{"paper.png", png}}),
        &warnings);
    ASSERT_TRUE(planar.ok()) << planar.status();
    const float mean = (SrgbToLinear(128 / 255.0f) + 1.0f) / 2;
    EXPECT_NEAR(planar->materials[0].transmittance.y, mean, 1e-5f);
    bool noted = false;
    for (const std::string& warning : warnings)
        noted |= warning.find("is taken as its mean colour") != std::string::npos;
    EXPECT_TRUE(noted);
    ExpectError(
        Load(Bundle(std::string("Material \"diffusetransmission\" \"float scale\" -1\n") + kQuad)),
        "Material \"diffusetransmission\": \"scale\" must be finite and non-negative");
}

TEST(PbrtMaterialsTest, SubsurfaceAndHairTakeTheirNearestSurfaces) {
    const std::string world =
        std::string(
            "Material \"subsurface\" \"rgb reflectance\" [0.8 0.5 0.3] \"float "
            "roughness\" 0.04 \"rgb mfp\" [1 1 1]\n") +
        kQuad + "Material \"subsurface\"\n" + kQuad +
        "Material \"subsurface\" \"rgb sigma_a\" [0 1 1] \"rgb sigma_s\" [1 0 1] \"float eta\" "
        "1.5\n" +
        kQuad + "Material \"hair\" \"rgb color\" [0.6 0.4 0.2]\n" + kQuad +
        "Material \"hair\" \"float eumelanin\" 0\n" + kQuad +
        "Material \"hair\" \"rgb sigma_a\" [0.1 0.2 0.3] \"float beta_n\" 0.5\n" + kQuad +
        "Material \"hair\"\n" + kQuad + "Material \"measured\" \"string filename\" \"x.bsdf\"\n" +
        kQuad;
    std::vector<std::string> warnings;
    const absl::StatusOr<Scene> scene = Load(Bundle(world), &warnings);
    ASSERT_TRUE(scene.ok()) << scene.status();
    const auto material = [&](int shape) {
        return scene->materials[scene->triangles[2 * shape].material];
    };
    // A coated diffuse: pbrt-v4's interface (index 1.33 by default) over its albedo.
    const Material& given = material(0);
    EXPECT_EQ(given.type, MaterialType::kDiffuse);
    EXPECT_EQ(given.base_color, Rgb(0.8f, 0.5f, 0.3f));
    EXPECT_FLOAT_EQ(given.coat_ior, 1.33f);
    EXPECT_NEAR(given.coat_roughness, 0.2f, 1e-6f);
    EXPECT_EQ(given.coat_thickness, 0.0f);
    // pbrt-v4's default coefficients: nearly white, red the palest (blue absorbs most).
    const Rgb skin = material(1).base_color;
    EXPECT_GT(skin.z, 0.6f);
    EXPECT_GT(skin.x, skin.y);
    EXPECT_GT(skin.y, skin.z);
    EXPECT_LT(skin.x, 1.0f);
    // A medium that absorbs nothing reflects all (albedo 1), one that scatters nothing none.
    const Material& limits = material(2);
    EXPECT_NEAR(limits.base_color.x, 1.0f, 1e-6f);
    EXPECT_NEAR(limits.base_color.y, 0.0f, 1e-6f);
    EXPECT_FLOAT_EQ(limits.coat_ior, 1.5f);
    // Hair: its colour, or the colour pbrt-v4 relates to its absorption:
    // sigma_a = (ln c / s(beta_n))^2, c = exp(-sqrt(sigma_a) s).
    EXPECT_EQ(material(3).base_color, Rgb(0.6f, 0.4f, 0.2f));
    EXPECT_EQ(material(4).base_color, Rgb(1.0f)) << "no melanin absorbs nothing";
    const double b = 0.5;
    const double s = 5.969 - 0.215 * b + 2.532 * b * b - 10.73 * std::pow(b, 3) +
                     5.574 * std::pow(b, 4) + 0.245 * std::pow(b, 5);
    EXPECT_NEAR(std::pow(std::log(material(5).base_color.z) / s, 2), 0.3, 1e-5);
    const Rgb dark = material(6).base_color;  // eumelanin 1.3: brown, red the lightest
    EXPECT_GT(dark.x, dark.z);
    EXPECT_LT(dark.x, 0.5f);
    EXPECT_EQ(material(7).base_color, Rgb(0.5f));
    EXPECT_TRUE(Contains(warnings, "nearest surface, a coated diffuse"));
    EXPECT_TRUE(Contains(warnings, "shaded as a diffuse surface of its colour"));
    EXPECT_TRUE(Contains(warnings, "Material \"measured\" (a measured BSDF file) is not read"));
}

TEST(PbrtMaterialsTest, HairTakesItsColourInPbrtsOrder) {
    // pbrt-v4's HairMaterial::Create: sigma_a over reflectance (or "color") over the melanins.
    const std::string world =
        std::string("Material \"hair\" \"rgb reflectance\" [0.3 0.5 0.7]\n") + kQuad +
        "Material \"hair\" \"rgb reflectance\" [0.3 0.5 0.7] \"rgb sigma_a\" [0.1 0.2 0.3]\n" +
        kQuad + "Material \"hair\" \"rgb reflectance\" [0.3 0.5 0.7] \"float eumelanin\" 2\n" +
        kQuad;
    std::vector<std::string> warnings;
    const absl::StatusOr<Scene> scene = Load(Bundle(world), &warnings);
    ASSERT_TRUE(scene.ok()) << scene.status();
    const auto colour = [&](int shape) {
        return scene->materials[scene->triangles[2 * shape].material].base_color;
    };
    EXPECT_EQ(colour(0), Rgb(0.3f, 0.5f, 0.7f));
    // beta_n 0.3 (pbrt-v4's default): c = exp(-sqrt(sigma_a) s(0.3)).
    const double b = 0.3;
    const double s = 5.969 - 0.215 * b + 2.532 * b * b - 10.73 * std::pow(b, 3) +
                     5.574 * std::pow(b, 4) + 0.245 * std::pow(b, 5);
    EXPECT_NEAR(colour(1).y, std::exp(-std::sqrt(0.2) * s), 1e-6);
    EXPECT_EQ(colour(2), Rgb(0.3f, 0.5f, 0.7f));
    EXPECT_TRUE(Contains(warnings,
                         "Material \"hair\" is shaded as a diffuse surface of its "
                         "colour (0.3 0.5 0.7)"));
}

}  // namespace
}  // namespace pf
