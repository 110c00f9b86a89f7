// The Vulkan backend's images against the CPU backend's: two CPU renders and one Vulkan
// render of a scene, each with its own photon stream, must be draws of one estimator, channel
// by channel and block by block, with budgets that let a 2% bias in any channel fail
// (tests/support/image_agreement.cpp derives the checks; image_agreement_test.cpp shows them
// failing on biased, tinted and channel-swapped images).
//
// Budgets: each case's photons are the fewest, in steps of two, whose comparison caught a bias
// of about 1% or less on one 2-core run (ExpectSameEstimator fails any run whose comparison
// could not catch 2%, so a budget too small fails the test rather than passing it). Most of a
// case's time past that is fixed: the Vulkan context's pipelines compiled by lavapipe and
// checked by the validation layer.
//
// Not paired: a Vulkan render and a CPU render of the same photon stream draw the same numbers
// in the same order, yet their images are nearly independent draws (measured at 32x32 on the
// sheen, coats, sky and two-sided-light cases: the spread of mean(V_s - C_s) was 0.6 to 1.6
// times a single render's, where independent renders give 1.4; 18-56% of the pixels agreed
// to 1e-3). Paths part at float rounding, and each progressive radius then follows
// its own photon counts. A paired statistic would need two Vulkan renders for no less noise.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "absl/strings/escaping.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_replace.h"
#include "core/film/exr_io.h"
#include "core/scene_io/scene_files.h"
#include "embedded/local_render.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/image_agreement.h"
#include "tests/support/numerics_cases.h"
#include "tests/support/png_fixture.h"
#include "tests/support/small_render.h"
#include "tests/support/test_env.h"
#include "tests/support/vulkan_validation.h"

namespace pf {
namespace {

// A Vulkan render of the scene (stream 3) against two CPU renders (streams 1 and 2), with no
// validation error on the way.
void ExpectVulkanAgreesWithTheCpu(const std::string& scene_path, uint64_t photons = 1'000'000,
                                  PhotonTracing tracing = PhotonTracing::kUniform) {
    const unsigned long long errors_before = testing::VulkanValidationErrors();
    testing::ExpectSameEstimator(testing::RenderSmall(scene_path, "vulkan", 3, photons, 0, tracing),
                                 testing::RenderSmall(scene_path, "cpu", 1, photons, 0, tracing),
                                 testing::RenderSmall(scene_path, "cpu", 2, photons, 0, tracing));
    EXPECT_EQ(testing::VulkanValidationErrors(), errors_before);
}

class BackendAgreement : public ::testing::TestWithParam<std::string> {};

TEST_P(BackendAgreement, VulkanImageMatchesTheCpuImagesWithinTheirNoise) {
    testing::SkipWithoutVulkan();
    if (IsSkipped() || HasFatalFailure()) return;
    ExpectVulkanAgreesWithTheCpu(std::string(PF_SOURCE_DIR) + "/scenes/" + GetParam(), 250'000);
}

// The lit quad with a wall of `wall` beside it: at x = 1, from z = 0 to 1, facing -x (toward
// the floor and the light), its corners at texture coordinates `low` and `high`.
testing::TestScene LitQuadWithWall(const testing::TestMaterial& wall, float low, float high) {
    testing::TestScene scene = testing::LitQuadScene();
    scene.materials.push_back(wall);
    scene.meshes.push_back({{{1, -1, 0}, {1, 1, 1}, {1, 1, 0}, {1, -1, 0}, {1, -1, 1}, {1, 1, 1}},
                            static_cast<int>(scene.materials.size()) - 1,
                            {low, low, high, high, high, low, low, low, low, high, high, high}});
    return scene;
}

// A wall of factor (1, 1, 0.5) times a base colour texture (a PNG, base64).
testing::TestMaterial TexturedWall(const std::string& png_base64) {
    testing::TestMaterial wall;
    wall.base_color = Rgb(1.0f, 1.0f, 0.5f);
    wall.texture_png_base64 = png_base64;
    return wall;
}

TEST(BackendAgreementTextures, LightOffATexturedWallMatchesTheCpus) {
    // The lit quad with a textured wall beside it (2x1 texels: sRGB red, sRGB grey 128; factor
    // (1, 1, 0.5)): the floor's indirect light comes off the wall, so photons must take the
    // texture's albedo at their bounce there (direct light needs no texture on the device:
    // hit points carry their BSDF weight). Same checks as the Cornell scenes.
    testing::SkipWithoutVulkan();
    if (::testing::Test::IsSkipped() || ::testing::Test::HasFatalFailure()) return;
    const testing::TestMaterial wall = TexturedWall(
        "iVBORw0KGgoAAAANSUhEUgAAAAIAAAABCAIAAAB7QOjdAAAAD0lEQVR4nGP4z8DQ0NAAAAkBAoCZxGkyAAAAAElFTk"
        "SuQmCC");
    ExpectVulkanAgreesWithTheCpu(
        testing::WriteGltf(LitQuadWithWall(wall, 0, 1), "textured-wall.gltf"), 500'000);
}

TEST(BackendAgreementTextures, WrapModesMatchTheCpus) {
    // The textured wall again, its coordinates running from -1 to 2 so that most of it lies
    // beyond the image: clamped in u, mirrored in v (a glTF sampler), photons reading the
    // texels the wrap modes pick on the device as on the CPU.
    testing::SkipWithoutVulkan();
    if (::testing::Test::IsSkipped() || ::testing::Test::HasFatalFailure()) return;
    testing::TestMaterial wall = TexturedWall(
        absl::Base64Escape(testing::TwoTexelPng({250, 30, 30, 30, 30, 250}, "wrap.png")));
    wall.texture_sampler = R"({"wrapS":33071,"wrapT":33648})";
    ExpectVulkanAgreesWithTheCpu(
        testing::WriteGltf(LitQuadWithWall(wall, -1, 2), "wrapped-wall.gltf"), 500'000);
}

// A wall of `wall` in the lit quad scene at x = 0.4, from z = 0 to 1.2, facing -x (toward the
// floor), beside the light, its texture coordinates across it.
void AddWallBesideTheLight(testing::TestScene& scene, const testing::TestMaterial& wall) {
    scene.materials.push_back(wall);
    scene.meshes.push_back({{{0.4f, -1, 0},
                             {0.4f, 1, 1.2f},
                             {0.4f, 1, 0},
                             {0.4f, -1, 0},
                             {0.4f, -1, 1.2f},
                             {0.4f, 1, 1.2f}},
                            static_cast<int>(scene.materials.size()) - 1,
                            {0, 0, 3, 1, 3, 0, 0, 0, 0, 1, 3, 1}});
}

TEST(BackendAgreementGltfMaterials, MetallicRoughnessMatchesTheCpus) {
    // glTF's BRDF, seen on a wall beside the light, metal or plastic per texel of its
    // metallic-roughness texture (stripes: metal of roughness 0.55, rough plastic), over a floor
    // of rough plastic: photons reflected by the metal as the texture's roughness says, by the
    // plastic's specular layer or let through to its base; hit points under the layer, on the
    // device as on the CPU.
    testing::SkipWithoutVulkan();
    if (::testing::Test::IsSkipped() || ::testing::Test::HasFatalFailure()) return;
    testing::TestScene scene = testing::LitQuadScene();
    scene.materials[0].roughness = 0.7f;
    scene.materials[0].extensions.clear();
    testing::TestMaterial wall{Rgb(0.9f, 0.7f, 0.4f)};
    wall.metallic = wall.roughness = 1;
    wall.extensions.clear();
    wall.texture_png_base64 =
        absl::Base64Escape(testing::TwoTexelPng({0, 140, 255, 0, 255, 0}, "stripes.png"));
    wall.texture_metallic_roughness = true;
    AddWallBesideTheLight(scene, wall);
    // The light, behind the camera, faces the wall: the floor is lit mostly by what the wall
    // reflects.
    scene.meshes[1].positions = {{-1, -0.3f, 0.4f}, {-1, 0.3f, 0.4f}, {-1, 0.3f, 1},
                                 {-1, -0.3f, 0.4f}, {-1, 0.3f, 1},    {-1, -0.3f, 1}};
    scene.camera_position = Vec3(-0.9f, 0, 0.6f);
    scene.camera_extra = R"(,"rotation":[0,-0.7071068,0,0.7071068])";
    ExpectVulkanAgreesWithTheCpu(testing::WriteGltf(scene, "metallic-roughness.gltf"), 500'000);
}

TEST(BackendAgreementTextures, ProceduralTexturesMatchTheCpus) {
    // pbrt-v4's noise textures (core/shared/procedural_texture.h) on the surfaces photons
    // bounce off: a floor whose reflectance is scaled by wrinkled and a marble wall; photons
    // take each texture's value at their bounce, on the device as on the CPU. The noise is
    // coarse and of few octaves, so that the CPU's camera pass, which filters it over its
    // samples' footprint, resolves every octave as the device's point lookups do.
    testing::SkipWithoutVulkan();
    if (::testing::Test::IsSkipped() || ::testing::Test::HasFatalFailure()) return;
    ExpectVulkanAgreesWithTheCpu(testing::WriteTextFile(
        "LookAt 0 -2.5 1.8  0 0.3 0.4  0 0 1\nCamera \"perspective\" \"float fov\" 50\n"
        "WorldBegin\n"
        "AttributeBegin\nScale 5 5 5\n"
        "Texture \"wrinkles\" \"float\" \"wrinkled\" \"integer octaves\" 4\n"
        "Scale 4 4 4\n"
        "Texture \"stone\" \"spectrum\" \"marble\" \"float scale\" 3 \"integer octaves\" 5 "
        "\"float variation\" 2\n"
        "AttributeEnd\n"
        "Texture \"floor\" \"spectrum\" \"scale\" \"rgb tex\" [0.9 0.7 0.5] "
        "\"texture scale\" \"wrinkles\"\n"
        "Material \"diffuse\" \"texture reflectance\" \"floor\"\n"
        "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]\n"
        "Material \"diffuse\" \"texture reflectance\" \"stone\"\n"
        "Shape \"bilinearmesh\" \"point3 P\" [-1 1 0  1 1 0  -1 1 1.5  1 1 1.5]\n"
        "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [6 6 6]\n"
        "Material \"diffuse\" \"rgb reflectance\" [0 0 0]\nTranslate 0 -0.6 1.4\n"
        "Rotate 180 1 0 0\n"
        "Shape \"bilinearmesh\" \"point3 P\" [-0.3 -0.3 0  0.3 -0.3 0  -0.3 0.3 0  0.3 0.3 0]\n"
        "AttributeEnd\n",
        "procedural.pbrt"));
}

TEST(BackendAgreementRange, ARangedLightMatchesTheCpus) {
    // A glTF point light with a range of 1, near a wall (x = 1): the floor's direct light fades
    // by the range's window at the light samples' distance, its light off the wall by the
    // window at the photons' first hit; past the range the floor is lit by the wall alone.
    testing::SkipWithoutVulkan();
    if (::testing::Test::IsSkipped() || ::testing::Test::HasFatalFailure()) return;
    testing::TestScene scene = testing::LitQuadScene();
    scene.meshes.resize(1);  // no area light
    scene.meshes.push_back(
        {{{1, -1, 0}, {1, 1, 1}, {1, 1, 0}, {1, -1, 0}, {1, -1, 1}, {1, 1, 1}}, 0});
    scene.lights = {R"({"type":"point","intensity":6830,"range":1.0})"};
    scene.light_node_fields = {R"(,"translation":[0.6,0,0.4])"};
    ExpectVulkanAgreesWithTheCpu(testing::WriteGltf(scene, "ranged-light.gltf"), 500'000);
}

TEST(BackendAgreementTwoSided, ATwoSidedLightMatchesTheCpus) {
    // A tilted two-sided area light over a floor: photons leave either face with equal chance
    // and light samples take the cosine of the face they see, on the device as on the CPU.
    testing::SkipWithoutVulkan();
    if (::testing::Test::IsSkipped() || ::testing::Test::HasFatalFailure()) return;
    ExpectVulkanAgreesWithTheCpu(
        testing::WriteTextFile(
            "LookAt 0 0.5 3  0 0 0.4  0 1 0\nCamera \"perspective\" \"float fov\" 50\nWorldBegin\n"
            "Material \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]\n"
            "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]\n"
            "Shape \"bilinearmesh\" \"point3 P\" [1 -1 0  1 1 0  1 -1 1  1 1 1]\n"
            "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [4 4 4] \"bool twosided\" true\n"
            "Material \"diffuse\" \"rgb reflectance\" [0 0 0]\nTranslate 0 0 0.6\nRotate 50 1 0 0\n"
            "Shape \"bilinearmesh\" \"point3 P\" [-0.3 -0.3 0  0.3 -0.3 0  -0.3 0.3 0  0.3 0.3 0]\n"
            "AttributeEnd\n",
            "two-sided-light.pbrt"),
        250'000);
}

TEST(BackendAgreementCoats, CoatedSurfacesMatchTheCpus) {
    // A smooth-coated floor, a rough-coated wall and a coated metal panel that throws light
    // onto both: photons enter, are turned back under the coats and reflected by them, and
    // direct light crosses them, on the device as on the CPU.
    testing::SkipWithoutVulkan();
    if (::testing::Test::IsSkipped() || ::testing::Test::HasFatalFailure()) return;
    ExpectVulkanAgreesWithTheCpu(
        testing::WriteTextFile(
            "LookAt 0 -2.5 1.8  0 0.3 0.4  0 0 1\nCamera \"perspective\" \"float fov\" 50\n"
            "WorldBegin\n"
            "Material \"coateddiffuse\" \"rgb reflectance\" [0.7 0.4 0.2] \"float thickness\" 0.1\n"
            "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]\n"
            "Material \"coateddiffuse\" \"rgb reflectance\" [0.2 0.5 0.8] \"float roughness\" "
            "0.05\n"
            "Shape \"bilinearmesh\" \"point3 P\" [-1 1 0  1 1 0  -1 1 1.5  1 1 1.5]\n"
            "Material \"coatedconductor\" \"float conductor.roughness\" 0.02 "
            "\"spectrum conductor.eta\" \"metal-Au-eta\" \"spectrum conductor.k\" \"metal-Au-k\"\n"
            "Shape \"bilinearmesh\" \"point3 P\" [0.9 1 0  0.9 -1 0  0.6 1 1.2  0.6 -1 1.2]\n"
            "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [6 6 6]\n"
            "Material \"diffuse\" \"rgb reflectance\" [0 0 0]\nTranslate -0.3 0 1.2\n"
            "Rotate 180 1 0 0\n"
            "Shape \"bilinearmesh\" \"point3 P\" [-0.3 -0.3 0  0.3 -0.3 0  -0.3 0.3 0  0.3 0.3 0]\n"
            "AttributeEnd\n",
            "coated.pbrt"),
        6'000'000);
}

TEST(BackendAgreementShadingDetail, BumpMapsMatchTheCpus) {
    // A floor bump-mapped by a ramp of displacement (pbrt's bilerp, baked) and a coated wall
    // bump-mapped the other way: hit points and photons shaded by the bumped normals, photons
    // leaving the coat by them with Veach's factors, on the device as on the CPU.
    testing::SkipWithoutVulkan();
    if (::testing::Test::IsSkipped() || ::testing::Test::HasFatalFailure()) return;
    ExpectVulkanAgreesWithTheCpu(
        testing::WriteTextFile(
            "LookAt 0 -2.5 1.8  0 0.3 0.4  0 0 1\nCamera \"perspective\" \"float fov\" 50\n"
            "WorldBegin\n"
            "Texture \"ramp\" \"float\" \"bilerp\" \"float v00\" 0 \"float v01\" 0 "
            "\"float v10\" 0.6 \"float v11\" 0.6\n"
            "Texture \"slope\" \"float\" \"bilerp\" \"float v00\" 0 \"float v01\" 0.5 "
            "\"float v10\" 0 \"float v11\" 0.5\n"
            "Material \"diffuse\" \"rgb reflectance\" [0.7 0.6 0.5] \"texture displacement\" "
            "\"ramp\"\n"
            "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]\n"
            "Material \"coateddiffuse\" \"rgb reflectance\" [0.2 0.5 0.8] \"float roughness\" "
            "0.05 \"texture displacement\" \"slope\"\n"
            "Shape \"bilinearmesh\" \"point3 P\" [-1 1 0  1 1 0  -1 1 1.5  1 1 1.5]\n"
            "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [6 6 6]\n"
            "Material \"diffuse\" \"rgb reflectance\" [0 0 0]\nTranslate -0.3 0 1.2\n"
            "Rotate 180 1 0 0\n"
            "Shape \"bilinearmesh\" \"point3 P\" [-0.3 -0.3 0  0.3 -0.3 0  -0.3 0.3 0  0.3 0.3 0]\n"
            "AttributeEnd\n",
            "bumped.pbrt"),
        500'000);
}

TEST(BackendAgreementConductors, MetalsFresnelTermsMatchTheCpus) {
    // pbrt-v4's conductors, each reflecting the Fresnel term of its complex index
    // (core/shared/conductor.h) onto a grey floor: a rough gold panel lit at grazing, a
    // smooth copper one, and a rough one whose "reflectance" is a texture (the index of each
    // texel's reflectance, per hit); photons take each term at their facet on the device as on
    // the CPU.
    testing::SkipWithoutVulkan();
    if (::testing::Test::IsSkipped() || ::testing::Test::HasFatalFailure()) return;
    std::ofstream(testing::TempPath("stripes.png"), std::ios::binary)
        << testing::TwoTexelPng({250, 200, 40, 60, 120, 250}, "stripes-source.png");
    ExpectVulkanAgreesWithTheCpu(
        testing::WriteTextFile(
            "LookAt 0 -2.5 1.8  0 0.3 0.4  0 0 1\nCamera \"perspective\" \"float fov\" 50\n"
            "WorldBegin\n"
            "Texture \"stripes\" \"spectrum\" \"imagemap\" \"string filename\" \"stripes.png\"\n"
            "Material \"diffuse\" \"rgb reflectance\" [0.6 0.6 0.6]\n"
            "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]\n"
            "Material \"conductor\" \"float roughness\" 0.1 \"spectrum eta\" \"metal-Au-eta\" "
            "\"spectrum k\" \"metal-Au-k\"\n"
            "Shape \"bilinearmesh\" \"point3 P\" [0.9 1 0  0.9 -1 0  0.4 1 1.2  0.4 -1 1.2]\n"
            "Material \"conductor\"\n"
            "Shape \"bilinearmesh\" \"point3 P\" [-0.4 1 1.2  -0.4 -1 1.2  -0.9 1 0  -0.9 -1 0]\n"
            "Material \"conductor\" \"float roughness\" 0.2 \"texture reflectance\" \"stripes\"\n"
            "Shape \"bilinearmesh\" \"point3 P\" [-1 1 0  1 1 0  -1 1 1.5  1 1 1.5]\n"
            "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [6 6 6]\n"
            "Material \"diffuse\" \"rgb reflectance\" [0 0 0]\nTranslate 0 -0.6 1.4\n"
            "Rotate 180 1 0 0\n"
            "Shape \"bilinearmesh\" \"point3 P\" [-0.3 -0.3 0  0.3 -0.3 0  -0.3 0.3 0  0.3 0.3 0]\n"
            "AttributeEnd\n",
            "conductors.pbrt"),
        750'000);
}

TEST(BackendAgreementAbsorption, AbsorbingGlassMatchesTheCpus) {
    // The glass Cornell box with its ball tinted by KHR_materials_volume's attenuation (light
    // crossing 0.1 of it keeps (0.8, 0.5, 0.2)): its caustic is the light that crossed the
    // ball, attenuated by Beer-Lambert along each photon's chords, on the device as on the CPU.
    testing::SkipWithoutVulkan();
    if (::testing::Test::IsSkipped() || ::testing::Test::HasFatalFailure()) return;
    const absl::StatusOr<std::string> glass =
        ReadWholeFile(std::string(PF_SOURCE_DIR) + "/scenes/cornell-glass.gltf");
    ASSERT_TRUE(glass.ok()) << glass.status();
    const std::string tinted = absl::StrReplaceAll(
        *glass, {{R"("thicknessFactor": 1.0)", R"("thicknessFactor": 1.0, "attenuationDistance": )"
                                               R"(0.1, "attenuationColor": [0.8, 0.5, 0.2])"}});
    ASSERT_NE(tinted, *glass);
    ExpectVulkanAgreesWithTheCpu(testing::WriteTextFile(tinted, "tinted-glass.gltf"), 250'000);
}

TEST(BackendAgreementSheen, TexturedSheenMatchesTheCpus) {
    // KHR_materials_sheen over a rough metal wall beside the light (the Khronos SheenChair's
    // fabric), its colour and roughness textured (two texels: a bright, rough sheen and a red,
    // smooth one), seen at a grazing angle, where the sheen shows: photons reflected by the
    // fibres or let through to the metal, on the device as on the CPU.
    testing::SkipWithoutVulkan();
    if (::testing::Test::IsSkipped() || ::testing::Test::HasFatalFailure()) return;
    testing::TestScene scene = testing::LitQuadScene();
    testing::TestMaterial wall{Rgb(0.5f, 0.2f, 0.55f)};
    wall.metallic = 1, wall.roughness = 0.6f;
    wall.texture_png_base64 = absl::Base64Escape(
        testing::TwoTexelRgbaPng({230, 230, 230, 255, 250, 40, 90, 60}, "sheen-stripes.png"));
    wall.extensions =
        R"("KHR_materials_sheen":{"sheenColorFactor":[1,0.8,1],"sheenRoughnessFactor":1,)"
        R"("sheenColorTexture":{"index":0},"sheenRoughnessTexture":{"index":0}})";
    AddWallBesideTheLight(scene, wall);
    scene.camera_position = Vec3(-0.9f, -0.6f, 0.6f);
    scene.camera_extra = R"(,"rotation":[0,-0.6427876,0,0.7660444])";
    ExpectVulkanAgreesWithTheCpu(testing::WriteGltf(scene, "sheen-wall.gltf"), 500'000);
}

TEST(BackendAgreementTranslucency, LightThroughAPaperShadeMatchesTheCpus) {
    // A closed room lit from the ceiling, half through a paper shade (pbrt-v4's
    // diffusetransmission, tinted, its transmittance a texture of two stripes, under half the
    // light and over part of the floor), the camera seeing the floor and the shade from below:
    // the floor under it is lit by the photons it lets through, on the device as on the CPU.
    testing::SkipWithoutVulkan();
    if (::testing::Test::IsSkipped() || ::testing::Test::HasFatalFailure()) return;
    testing::WriteTextFile(testing::TwoTexelPng({200, 160, 120, 80, 140, 230}, "stripes.png"),
                           "shade-stripes.png");
    ExpectVulkanAgreesWithTheCpu(
        testing::WriteTextFile(
            "LookAt 0 -0.95 1.2  0 0 0.5  0 0 1\nCamera \"perspective\" \"float fov\" 70\n"
            "WorldBegin\n"
            "Material \"diffuse\" \"rgb reflectance\" [0.7 0.6 0.5]\n"
            "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]\n"
            "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 2  -1 1 2  1 -1 2  1 1 2]\n"
            "Shape \"bilinearmesh\" \"point3 P\" [-1 1 0  1 1 0  -1 1 2  1 1 2]\n"
            "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 0  -1 -1 2  1 -1 0  1 -1 2]\n"
            "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 0  -1 1 0  -1 -1 2  -1 1 2]\n"
            "Shape \"bilinearmesh\" \"point3 P\" [1 -1 0  1 -1 2  1 1 0  1 1 2]\n"
            "Texture \"stripes\" \"spectrum\" \"imagemap\" \"string filename\" "
            "\"shade-stripes.png\"\n"
            "Material \"diffusetransmission\" \"rgb reflectance\" [0.4 0.3 0.2] "
            "\"texture transmittance\" \"stripes\"\n"
            "Shape \"bilinearmesh\" \"point3 P\" [-0.9 -0.2 1.4  0.1 -0.2 1.4  -0.9 0.9 1.6  0.1 "
            "0.9 "
            "1.6]\n"
            "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [5 5 5]\n"
            "Material \"diffuse\" \"rgb reflectance\" [0 0 0]\nTranslate -0.2 0.3 1.99\n"
            "Rotate 180 1 0 0\n"
            "Shape \"bilinearmesh\" \"point3 P\" [-0.4 -0.4 0  0.4 -0.4 0  -0.4 0.4 0  0.4 0.4 0]\n"
            "AttributeEnd\n",
            "paper-shade.pbrt"),
        1'500'000);
}

TEST(BackendAgreementCutOuts, CutOutsAndMixesMatchTheCpus) {
    // A closed room lit from the ceiling, with a checkered alpha-textured card and a card of
    // alpha 0.5 hanging in it, the camera seeing the floor through both: camera rays, photons
    // and shadow rays pass the cards where alpha says, on the device as on the CPU. The floor
    // is a mix of two materials, each point one of them as on the CPU.
    testing::SkipWithoutVulkan();
    if (::testing::Test::IsSkipped() || ::testing::Test::HasFatalFailure()) return;
    const std::string folder = testing::TempPath("cut-outs");
    std::filesystem::create_directories(folder);
    Image checks(4, 4);
    for (int i = 0; i < 16; ++i) checks.pixels[i] = Rgb(float((i + i / 4) % 2));
    ASSERT_TRUE(WriteExr(folder + "/checks.exr", checks).ok());
    const std::string path = folder + "/cut-outs.pbrt";
    std::ofstream(path)
        << "LookAt 0 -0.95 1.2  0 0 0.5  0 0 1\nCamera \"perspective\" \"float fov\" "
           "70\nWorldBegin\n"
           "Texture \"checks\" \"float\" \"imagemap\" \"string filename\" \"checks.exr\"\n"
           "MakeNamedMaterial \"warm\" \"string type\" \"diffuse\" \"rgb reflectance\" [0.8 0.5 "
           "0.2]\n"
           "MakeNamedMaterial \"cool\" \"string type\" \"diffuse\" \"rgb reflectance\" [0.2 0.4 "
           "0.8]\n"
           "Material \"mix\" \"string materials\" [\"warm\" \"cool\"] \"float amount\" 0.3\n"
           "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]\n"
           "Material \"diffuse\" \"rgb reflectance\" [0.7 0.6 0.5]\n"
           "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 2  -1 1 2  1 -1 2  1 1 2]\n"
           "Shape \"bilinearmesh\" \"point3 P\" [-1 1 0  1 1 0  -1 1 2  1 1 2]\n"
           "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 0  -1 -1 2  1 -1 0  1 -1 2]\n"
           "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 0  -1 1 0  -1 -1 2  -1 1 2]\n"
           "Shape \"bilinearmesh\" \"point3 P\" [1 -1 0  1 -1 2  1 1 0  1 1 2]\n"
           "Material \"diffuse\" \"rgb reflectance\" [0.2 0.7 0.3]\n"
           "Shape \"bilinearmesh\" \"point3 P\" [-0.8 -0.3 0.6  0 -0.3 0.6  -0.8 0.6 0.9  0 0.6 "
           "0.9] "
           "\"texture alpha\" \"checks\"\n"
           "Shape \"bilinearmesh\" \"point3 P\" [0 -0.3 0.6  0.8 -0.3 0.6  0 0.6 0.9  0.8 0.6 0.9] "
           "\"float alpha\" 0.5\n"
           "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [5 5 5]\n"
           "Material \"diffuse\" \"rgb reflectance\" [0 0 0]\nTranslate 0 0 1.99\nRotate 180 1 0 "
           "0\n"
           "Shape \"bilinearmesh\" \"point3 P\" [-0.4 -0.4 0  0.4 -0.4 0  -0.4 0.4 0  0.4 0.4 0]\n"
           "AttributeEnd\n";
    ExpectVulkanAgreesWithTheCpu(path, 750'000);
}

TEST(BackendAgreementTexturedLight, AnImageLightMatchesTheCpus) {
    // A tilted two-sided area light whose image is 2 x 2 texels of four colours over a floor
    // and a wall: photons leave it with the texel where they start, light samples and MIS hits take
    // the texel where they land, on the device as on the CPU.
    testing::SkipWithoutVulkan();
    if (::testing::Test::IsSkipped() || ::testing::Test::HasFatalFailure()) return;
    const std::string folder = testing::TempPath("image-light");
    std::filesystem::create_directories(folder);
    Image image(2, 2);
    image.pixels = {Rgb(3, 1, 1), Rgb(1, 3, 1), Rgb(1, 1, 3), Rgb(0.5f)};
    ASSERT_TRUE(WriteExr(folder + "/glow.exr", image).ok());
    const std::string path = folder + "/image-light.pbrt";
    std::ofstream(path)
        << "LookAt 0 0.5 3  0 0 0.4  0 1 0\nCamera \"perspective\" \"float fov\" 50\nWorldBegin\n"
           "Material \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]\n"
           "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]\n"
           "Shape \"bilinearmesh\" \"point3 P\" [1 -1 0  1 1 0  1 -1 1  1 1 1]\n"
           "AttributeBegin\nAreaLightSource \"diffuse\" \"string filename\" \"glow.exr\" "
           "\"bool twosided\" true\n"
           "Material \"diffuse\" \"rgb reflectance\" [0 0 0]\nTranslate 0 0 0.6\nRotate 50 1 0 0\n"
           "Shape \"bilinearmesh\" \"point3 P\" [-0.3 -0.3 0  0.3 -0.3 0  -0.3 0.3 0  0.3 0.3 0]\n"
           "AttributeEnd\n";
    ExpectVulkanAgreesWithTheCpu(path, 1'000'000);
}

TEST(BackendAgreementEnvironment, SkyLitCourtyardMatchesTheCpus) {
    // Lit by an environment map alone: photons leave the map, light samples draw from it and
    // the cosine ray escapes to it, on the device as on the CPU; the sky seen directly is the
    // same in all three (blocks where the CPU renders agree exactly must match exactly). 2M
    // photons (8 epochs of direct samples): at 1M a bias of 1.24% could be caught.
    testing::SkipWithoutVulkan();
    if (::testing::Test::IsSkipped() || ::testing::Test::HasFatalFailure()) return;
    ExpectVulkanAgreesWithTheCpu(std::string(PF_SOURCE_DIR) + "/scenes/pbrt/sky-courtyard.pbrt",
                                 2'000'000);
}

TEST(BackendAgreementAdaptive, AdaptivePhotonChainsMatchTheCpus) {
    // Adaptive photon tracing on both: the device runs a chain a thread, 64 steps long, where
    // the CPU runs eight a chunk, so their photons differ but their estimate is the same. On
    // cornell-box nearly every chain starts at once, so the two spread alike too; where few
    // photons count (light-gap) most short chains never start, and the device's image, the
    // same in the mean (+2.6% within +-4.0% at 1M photons), is the noisier one.
    testing::SkipWithoutVulkan();
    if (::testing::Test::IsSkipped() || ::testing::Test::HasFatalFailure()) return;
    ExpectVulkanAgreesWithTheCpu(std::string(PF_SOURCE_DIR) + "/scenes/cornell-box.gltf", 250'000,
                                 PhotonTracing::kAdaptive);
}

TEST(BackendAgreementImageLights, AProjectorAndAGoniometricLampMatchTheCpus) {
    // A floor and a wall, which fills the view, lit by a projection light casting a 2 x 2
    // picture of four colours across the wall, then by a tilted goniometric lamp of four
    // intensities: photons leave each in proportion to its image and light samples read the
    // texel toward the receiver, on the device as on the CPU.
    testing::SkipWithoutVulkan();
    if (::testing::Test::IsSkipped() || ::testing::Test::HasFatalFailure()) return;
    const std::string folder = testing::TempPath("image-lights");
    std::filesystem::create_directories(folder);
    Image slide(2, 2), lamp(2, 2);
    slide.pixels = {Rgb(3, 1, 1), Rgb(1, 3, 1), Rgb(1, 1, 3), Rgb(0.5f)};
    lamp.pixels = {Rgb(0.5f), Rgb(2.0f), Rgb(1.0f), Rgb(3.0f)};
    ASSERT_TRUE(WriteExr(folder + "/slide.exr", slide).ok());
    ASSERT_TRUE(WriteExr(folder + "/lamp.exr", lamp).ok());
    const std::string room =
        "LookAt -1.2 0 0.6  1 0 0.45  0 0 1\nCamera \"perspective\" \"float fov\" 50\n"
        "WorldBegin\nMaterial \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]\n"
        "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]\n"
        "Shape \"bilinearmesh\" \"point3 P\" [1 -1 0  1 1 0  1 -1 1  1 1 1]\n";
    for (const char* light :
         {"ConcatTransform [0 1 0 0  0 0 1 0  1 0 0 0  -0.5 0 0.5 1]\n"
          "LightSource \"projection\" \"string filename\" \"slide.exr\" \"float fov\" 60\n",
          "Translate 0 0 0.8\nRotate 30 1 0 0\n"
          "LightSource \"goniometric\" \"string filename\" \"lamp.exr\" \"rgb I\" [1 0.8 0.6]\n"}) {
        SCOPED_TRACE(light);
        const std::string path = folder + "/image-light.pbrt";
        std::ofstream(path) << room << "AttributeBegin\n" << light << "AttributeEnd\n";
        ExpectVulkanAgreesWithTheCpu(path, 1'000'000);
    }
}

TEST(BackendAgreementPortal, ARoomLitThroughAPortalMatchesTheCpus) {
    // A closed room whose only opening is a window with a portal on it, under a uniform sky:
    // photons come in through the window and light samples aim at it, on the device as on the
    // CPU.
    testing::SkipWithoutVulkan();
    if (::testing::Test::IsSkipped() || ::testing::Test::HasFatalFailure()) return;
    std::string room =
        "LookAt 1.5 2.6 -1.7  -1 0.3 1  0 1 0\nCamera \"perspective\" \"float fov\" 70\n"
        "WorldBegin\nMaterial \"diffuse\" \"rgb reflectance\" [0.6 0.6 0.6]\n"
        "LightSource \"infinite\" \"rgb L\" [1 0.8 0.6] "
        "\"point3 portal\" [2 1 -0.5  2 1 0.5  2 2 0.5  2 2 -0.5]\n";
    // x in [-2, 2], y in [0, 3], z in [-2, 2]; the wall x = 2 open for y in [1, 2], z in
    // [-0.5, 0.5]. Each patch: x0 y0 z0, then its two edges' ends.
    const float patches[][9] = {{-2, 0, -2, 2, 0, -2, -2, 0, 2},  {-2, 3, -2, -2, 3, 2, 2, 3, -2},
                                {-2, 0, -2, -2, 0, 2, -2, 3, -2}, {-2, 0, -2, -2, 3, -2, 2, 0, -2},
                                {-2, 0, 2, 2, 0, 2, -2, 3, 2},    {2, 0, -2, 2, 1, -2, 2, 0, 2},
                                {2, 2, -2, 2, 3, -2, 2, 2, 2},    {2, 1, -2, 2, 2, -2, 2, 1, -0.5f},
                                {2, 1, 0.5f, 2, 2, 0.5f, 2, 1, 2}};
    for (const float* q : patches) {
        const Vec3 p0(q[0], q[1], q[2]), a(q[3], q[4], q[5]), b(q[6], q[7], q[8]);
        const Vec3 p11 = a + b - p0;
        room += absl::StrFormat(
            "Shape \"bilinearmesh\" \"point3 P\" [%g %g %g  %g %g %g  %g %g %g  %g %g %g]\n", p0.x,
            p0.y, p0.z, a.x, a.y, a.z, b.x, b.y, b.z, p11.x, p11.y, p11.z);
    }
    ExpectVulkanAgreesWithTheCpu(testing::WriteTextFile(room, "portal-room.pbrt"), 1'000'000);
}

TEST(BackendAgreementDepth, PhotonsOnTheDeviceStopAtTheMaximumDepth) {
    // The furnace (albedo 0.5, Le = 1) with --max-depth 2: Le (1 + rho + rho^2) = 1.75 where
    // the unlimited furnace gives 2; photons reaching a third surface would add 0.125.
    testing::SkipWithoutVulkan();
    if (::testing::Test::IsSkipped() || ::testing::Test::HasFatalFailure()) return;
    RenderSettings settings;
    settings.scene_path = std::string(PF_SOURCE_DIR) + "/scenes/furnace.gltf";
    settings.backend = "vulkan";
    settings.threads = 2;
    settings.job.width = settings.job.height = 32;
    settings.job.samples_per_pixel = 16;
    settings.job.photon_budget = 4'000'000;
    settings.job.layout = {1u << 18, 8};
    settings.job.max_depth = 2;
    const absl::StatusOr<RenderOutcome> outcome = RenderLocally(settings);
    ASSERT_TRUE(outcome.ok()) << outcome.status();
    const testing::BoxInterior interior =
        testing::BoxInteriorPixels(settings.scene_path, 32, 32, outcome->initial_radius);
    const double sigma = testing::FurnaceMeanSigma(
        0.5, static_cast<double>(outcome->progress.photons), interior.area_fraction,
        static_cast<double>(interior.count) * 16 * static_cast<double>(outcome->progress.epochs));
    const testing::FurnaceCheck check =
        testing::CheckFurnace(outcome->image, interior, 1.75, sigma);
    EXPECT_TRUE(check.Passed()) << check.Describe();
    EXPECT_FALSE(testing::CheckFurnace(outcome->image, interior, 1.75, sigma, Rgbd(1.03)).Passed());
}

INSTANTIATE_TEST_SUITE_P(Scenes, BackendAgreement,
                         // cornell-bumpy: normal-mapped tiles, Veach's adjoint factors.
                         // cornell-velvet: sheen over rough metal and over rough plastic.
                         ::testing::Values("cornell-box.gltf", "cornell-glass.gltf",
                                           "cornell-bumpy.gltf", "cornell-velvet.gltf"),
                         [](const ::testing::TestParamInfo<std::string>& scene) {
                             std::string name = scene.param.substr(0, scene.param.find('.'));
                             for (char& c : name)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });

}  // namespace
}  // namespace pf
