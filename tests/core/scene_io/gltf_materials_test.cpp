// glTF's metallic-roughness materials (core/scene_io/gltf/gltf_materials.h): the dielectric as
// specular over diffuse, metallic as a mix by factor or texture, roughness squared (and its
// texture's green channel squared) as GGX alpha, KHR_materials_specular, _ior, _clearcoat and
// _sheen, and a clear error for values out of range.
#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include "absl/strings/escaping.h"
#include "core/scene/emitters.h"
#include "core/scene_io/scene_loader.h"
#include "core/shared/coat.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/png_fixture.h"

namespace pf {
namespace {

// The quad's material (the lit quad scene's first) as glTF material `material` makes it.
absl::StatusOr<Scene> QuadWith(const testing::TestMaterial& material, const std::string& name) {
    testing::TestScene scene = testing::LitQuadScene();
    scene.materials[0] = material;
    scene.meshes[0].uvs = {0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1};
    return LoadScene(testing::WriteGltf(scene, name));
}

const Material& QuadMaterial(const Scene& scene) {
    return scene.materials[scene.triangles[0].material];
}

testing::TestMaterial Gltf(float metallic, float roughness, const std::string& extensions = "") {
    testing::TestMaterial material{Rgb(0.7f), Rgb(0.0f)};
    material.metallic = metallic, material.roughness = roughness;
    material.extensions = extensions;
    return material;
}

TEST(GltfMaterialsTest, TheDielectricIsSpecularOverDiffuse) {
    const absl::StatusOr<Scene> scene = QuadWith(Gltf(0, 0.5f), "plastic.gltf");
    ASSERT_TRUE(scene.ok()) << scene.status();
    const Material& plastic = QuadMaterial(*scene);
    EXPECT_EQ(plastic.type, MaterialType::kDiffuse);
    EXPECT_EQ(plastic.coat_kind, gpu::kCoatFresnelMix);
    EXPECT_FLOAT_EQ(plastic.coat_ior, 1.5f) << "glTF's default index";
    EXPECT_FLOAT_EQ(plastic.coat_roughness, 0.25f) << "roughness squared";
    EXPECT_FLOAT_EQ(plastic.coat_weight, 1.0f);
    EXPECT_EQ(plastic.base_color, Rgb(0.7f));
    // Without its specular layer it is Lambertian, and pays for no coat.
    const absl::StatusOr<Scene> lambertian = QuadWith(
        Gltf(0, 0.5f, R"("KHR_materials_specular":{"specularFactor":0})"), "lambertian.gltf");
    ASSERT_TRUE(lambertian.ok()) << lambertian.status();
    EXPECT_EQ(QuadMaterial(*lambertian).type, MaterialType::kDiffuse);
    EXPECT_FALSE(QuadMaterial(*lambertian).HasCoat());
    // KHR_materials_ior and KHR_materials_specular set the layer: its weight, and F0 scaled by
    // the specular colour's mean, as an index.
    const absl::StatusOr<Scene> specular =
        QuadWith(Gltf(0, 0,
                      R"("KHR_materials_ior":{"ior":2},"KHR_materials_specular":)"
                      R"({"specularFactor":0.5,"specularColorFactor":[0.5,0.5,0.5]})"),
                 "specular.gltf");
    ASSERT_TRUE(specular.ok()) << specular.status();
    const Material& layer = QuadMaterial(*specular);
    EXPECT_FLOAT_EQ(layer.coat_weight, 0.5f);
    EXPECT_EQ(layer.coat_roughness, 0.0f) << "roughness 0: a smooth layer";
    const double f0 = (1.0 / 9.0) * 0.5, r = std::sqrt(f0);
    EXPECT_NEAR(layer.coat_ior, (1 + r) / (1 - r), 1e-5);
}

TEST(GltfMaterialsTest, MetallicChoosesTheMetalWithItsProbability) {
    const absl::StatusOr<Scene> mirror = QuadWith(Gltf(1, 0), "mirror.gltf");
    ASSERT_TRUE(mirror.ok()) << mirror.status();
    EXPECT_EQ(QuadMaterial(*mirror).type, MaterialType::kMirror);
    const absl::StatusOr<Scene> metal = QuadWith(Gltf(1, 1), "metal.gltf");
    ASSERT_TRUE(metal.ok()) << metal.status();
    EXPECT_EQ(QuadMaterial(*metal).type, MaterialType::kRoughConductor)
        << "glTF's defaults: rough metal";
    EXPECT_FLOAT_EQ(QuadMaterial(*metal).roughness, 1.0f);
    const absl::StatusOr<Scene> half = QuadWith(Gltf(0.3f, 0.6f), "half.gltf");
    ASSERT_TRUE(half.ok()) << half.status();
    const Material& mix = QuadMaterial(*half);
    ASSERT_EQ(mix.type, MaterialType::kMix);
    EXPECT_FLOAT_EQ(mix.mix_amount, 0.3f);
    EXPECT_EQ(mix.mix_texture, kNoTexture);
    const Material& dielectric = half->materials[mix.mix_first];
    const Material& conductor = half->materials[mix.mix_second];
    EXPECT_EQ(dielectric.coat_kind, gpu::kCoatFresnelMix);
    EXPECT_EQ(conductor.type, MaterialType::kRoughConductor);
    EXPECT_NEAR(conductor.roughness, 0.36f, 1e-6);
    EXPECT_NEAR(dielectric.coat_roughness, 0.36f, 1e-6);
}

TEST(GltfMaterialsTest, TheMetallicRoughnessTextureSetsBothPerTexel) {
    // Two texels: green 0.5 (roughness), blue 1 (metal); green 1, blue 0.
    testing::TestMaterial material = Gltf(1, 1);
    material.texture_png_base64 =
        absl::Base64Escape(testing::TwoTexelPng({0, 128, 255, 0, 255, 0}, "mr.png"));
    material.texture_metallic_roughness = true;
    const absl::StatusOr<Scene> scene = QuadWith(material, "textured-metal.gltf");
    ASSERT_TRUE(scene.ok()) << scene.status();
    const Material& mix = QuadMaterial(*scene);
    ASSERT_EQ(mix.type, MaterialType::kMix) << "a metallic texture: a mix per texel";
    ASSERT_NE(mix.mix_texture, kNoTexture);
    const Texture& metallic = *scene->textures[mix.mix_texture];
    EXPECT_FLOAT_EQ(metallic.texels[0].x, 1.0f) << "blue, linear";
    EXPECT_FLOAT_EQ(metallic.texels[1].x, 0.0f);
    const Material& conductor = scene->materials[mix.mix_second];
    ASSERT_NE(conductor.roughness_texture, kNoTexture);
    EXPECT_EQ(scene->materials[mix.mix_first].roughness_texture, conductor.roughness_texture);
    const Texture& roughness = *scene->textures[conductor.roughness_texture];
    EXPECT_NEAR(roughness.texels[0].x, (128 / 255.0) * (128 / 255.0), 1e-6)
        << "green, linear, squared";
    EXPECT_FLOAT_EQ(roughness.texels[1].x, 1.0f);
    // A surface point's material carries its texel's alpha: roughness 0.5 is alpha 0.25.
    SurfacePoint point;
    point.material = mix.mix_second;
    point.uv = {0.25f, 0.5f};  // the first texel's centre
    std::optional<Material> scratch;
    EXPECT_NEAR(scene->ShadingMaterial(point, scratch).roughness, 0.25f, 0.01f);
    point.uv = {0.75f, 0.5f};
    EXPECT_NEAR(scene->ShadingMaterial(point, scratch).roughness, 1.0f, 1e-6f);
}

TEST(GltfMaterialsTest, ClearcoatIsALayeredCoatMixedByItsFactor) {
    const absl::StatusOr<Scene> full = QuadWith(
        Gltf(1, 0.5f,
             R"("KHR_materials_clearcoat":{"clearcoatFactor":1,"clearcoatRoughnessFactor":0.2})"),
        "clearcoat.gltf");
    ASSERT_TRUE(full.ok()) << full.status();
    const Material& coated = QuadMaterial(*full);
    EXPECT_EQ(coated.type, MaterialType::kRoughConductor);
    EXPECT_EQ(coated.coat_kind, gpu::kCoatLayered);
    EXPECT_FLOAT_EQ(coated.coat_ior, 1.5f);
    EXPECT_NEAR(coated.coat_roughness, 0.04f, 1e-6);
    const absl::StatusOr<Scene> half = QuadWith(
        Gltf(0, 0.5f, R"("KHR_materials_clearcoat":{"clearcoatFactor":0.25})"), "half-coat.gltf");
    ASSERT_TRUE(half.ok()) << half.status();
    const Material& mix = QuadMaterial(*half);
    ASSERT_EQ(mix.type, MaterialType::kMix);
    EXPECT_FLOAT_EQ(mix.mix_amount, 0.25f);
    EXPECT_EQ(half->materials[mix.mix_first].coat_kind, gpu::kCoatFresnelMix);
    EXPECT_EQ(half->materials[mix.mix_second].coat_kind, gpu::kCoatLayered);
    EXPECT_EQ(half->materials[mix.mix_second].coat_roughness, 0.0f);
}

TEST(GltfMaterialsTest, ClearcoatTexturesScaleItsFactorAndRoughnessTexelByTexel) {
    // One 2x1 image as the base colour, clearcoatTexture (its red channel, linear, scaling the
    // factor: the mix's amount) and clearcoatRoughnessTexture (green, linear, squared as the
    // factor is: the coated plastic's roughness texture, which scales its coat's alpha).
    testing::TestMaterial material =
        Gltf(0, 0.5f,
             R"("KHR_materials_clearcoat":{"clearcoatFactor":0.8,"clearcoatRoughnessFactor":0.5,)"
             R"("clearcoatTexture":{"index":0},"clearcoatRoughnessTexture":{"index":0}})");
    material.texture_png_base64 =
        absl::Base64Escape(testing::TwoTexelPng({200, 100, 50, 20, 240, 60}, "coat.png"));
    const absl::StatusOr<Scene> scene = QuadWith(material, "clearcoat-textures.gltf");
    ASSERT_TRUE(scene.ok()) << scene.status();
    const Material& mix = QuadMaterial(*scene);
    ASSERT_EQ(mix.type, MaterialType::kMix) << "a textured factor: a mix per texel";
    EXPECT_FLOAT_EQ(mix.mix_amount, 0.8f);
    ASSERT_NE(mix.mix_texture, kNoTexture);
    const Texture& factor = *scene->textures[mix.mix_texture];
    EXPECT_NEAR(factor.texels[0].x, 200 / 255.0, 1e-6) << "red, linear";
    EXPECT_NEAR(factor.texels[1].x, 20 / 255.0, 1e-6);
    const Material& coated = scene->materials[mix.mix_second];
    EXPECT_EQ(coated.coat_kind, gpu::kCoatLayered);
    EXPECT_FLOAT_EQ(coated.coat_roughness, 0.25f);
    ASSERT_NE(coated.roughness_texture, kNoTexture);
    const Texture& roughness = *scene->textures[coated.roughness_texture];
    EXPECT_NEAR(roughness.texels[1].x, (240 / 255.0) * (240 / 255.0), 1e-6) << "green, squared";
    SurfacePoint point;
    point.material = mix.mix_second;
    point.uv = {0.25f, 0.5f};  // the first texel's centre: roughness 0.5 x 100/255
    std::optional<Material> scratch;
    EXPECT_NEAR(scene->ShadingMaterial(point, scratch).coat_roughness,
                0.25 * (100 / 255.0) * (100 / 255.0), 1e-4);
    EXPECT_EQ(scene->materials[mix.mix_first].roughness_texture, kNoTexture)
        << "the uncoated plastic keeps its own (none)";
}

TEST(GltfMaterialsTest, SpecularTextureWeighsTheLayerTexelByTexel) {
    // specularTexture's alpha (linear) scales specularFactor: a mix of the Lambertian base and
    // the surface with its specular layer, the texel the amount.
    testing::TestMaterial material =
        Gltf(0, 0.5f,
             R"("KHR_materials_specular":{"specularFactor":0.7,"specularTexture":{"index":0}})");
    material.texture_png_base64 = absl::Base64Escape(
        testing::TwoTexelRgbaPng({200, 100, 50, 255, 20, 240, 60, 51}, "specular.png"));
    const absl::StatusOr<Scene> scene = QuadWith(material, "specular-texture.gltf");
    ASSERT_TRUE(scene.ok()) << scene.status();
    const Material& mix = QuadMaterial(*scene);
    ASSERT_EQ(mix.type, MaterialType::kMix);
    EXPECT_FLOAT_EQ(mix.mix_amount, 1.0f);
    ASSERT_NE(mix.mix_texture, kNoTexture);
    const Texture& weight = *scene->textures[mix.mix_texture];
    EXPECT_FLOAT_EQ(weight.texels[0].x, 1.0f) << "alpha, linear";
    EXPECT_NEAR(weight.texels[1].x, 0.2f, 1e-6f);
    EXPECT_FALSE(scene->materials[mix.mix_first].HasCoat()) << "Lambertian";
    const Material& layered = scene->materials[mix.mix_second];
    EXPECT_EQ(layered.coat_kind, gpu::kCoatFresnelMix);
    EXPECT_FLOAT_EQ(layered.coat_weight, 0.7f);
    // A factor of 0 keeps no layer, whatever the texture.
    testing::TestMaterial none = Gltf(
        0, 0.5f, R"("KHR_materials_specular":{"specularFactor":0,"specularTexture":{"index":0}})");
    none.texture_png_base64 = material.texture_png_base64;
    const absl::StatusOr<Scene> plain = QuadWith(none, "no-specular.gltf");
    ASSERT_TRUE(plain.ok()) << plain.status();
    EXPECT_EQ(QuadMaterial(*plain).type, MaterialType::kDiffuse);
    EXPECT_FALSE(QuadMaterial(*plain).HasCoat());
}

TEST(GltfMaterialsTest, SheenLiesOverEveryPartOfTheSurface) {
    // KHR_materials_sheen over glTF's dielectric (its Fresnel mix) and over the metal (no coat
    // but the sheen), each part carrying the sheen's colour, roughness and textures: the colour
    // texture sRGB, the roughness texture's alpha linear.
    testing::TestMaterial material =
        Gltf(0.5f, 0.6f,
             R"("KHR_materials_sheen":{"sheenColorFactor":[1,0.5,0.25],)"
             R"("sheenRoughnessFactor":0.4,"sheenColorTexture":{"index":0},)"
             R"("sheenRoughnessTexture":{"index":0}})");
    material.texture_png_base64 = absl::Base64Escape(
        testing::TwoTexelRgbaPng({200, 100, 50, 255, 20, 240, 60, 51}, "sheen.png"));
    const absl::StatusOr<Scene> scene = QuadWith(material, "sheen.gltf");
    ASSERT_TRUE(scene.ok()) << scene.status();
    const Material& mix = QuadMaterial(*scene);
    ASSERT_EQ(mix.type, MaterialType::kMix);
    EXPECT_FALSE(mix.HasSheen()) << "a mix is not shaded";
    const Material& plastic = scene->materials[mix.mix_first];
    const Material& metal = scene->materials[mix.mix_second];
    EXPECT_EQ(plastic.coat_kind, gpu::kCoatFresnelMix);
    EXPECT_EQ(metal.type, MaterialType::kRoughConductor);
    EXPECT_EQ(metal.coat_kind, gpu::kCoatNone);
    EXPECT_FLOAT_EQ(metal.coat_ior, 1.0f) << "the metal's own Fresnel term";
    for (const Material* part : {&plastic, &metal}) {
        EXPECT_TRUE(part->HasSheen());
        EXPECT_EQ(part->sheen_color, Rgb(1.0f, 0.5f, 0.25f));
        EXPECT_FLOAT_EQ(part->sheen_roughness, 0.4f);
        ASSERT_NE(part->sheen_texture, kNoTexture);
        ASSERT_NE(part->sheen_roughness_texture, kNoTexture);
        const Texture& colour = *scene->textures[part->sheen_texture];
        EXPECT_NEAR(colour.texels[0].x, std::pow((200 / 255.0 + 0.055) / 1.055, 2.4), 1e-3)
            << "sRGB";
        EXPECT_NEAR(scene->textures[part->sheen_roughness_texture]->texels[1].x, 0.2f, 1e-6f)
            << "alpha, linear";
    }
    // The textures apply at the point, as the roughness texture does: the first texel (alpha 1)
    // shows the colour, the second (alpha 0.2) the roughness.
    SurfacePoint surface;
    surface.material = mix.mix_second;
    std::optional<Material> scratch;
    surface.uv = {0.25f, 0.5f};
    EXPECT_NEAR(scene->ShadingMaterial(surface, scratch).sheen_color.y,
                0.5f * std::pow((100 / 255.0 + 0.055) / 1.055, 2.4), 1e-3f);
    surface.uv = {0.75f, 0.5f};
    EXPECT_NEAR(scene->ShadingMaterial(surface, scratch).sheen_roughness, 0.4f * 0.2f, 1e-3f);
    // Black turns the layer off.
    const absl::StatusOr<Scene> off = QuadWith(
        Gltf(0, 0.5f, R"("KHR_materials_sheen":{"sheenColorFactor":[0,0,0]})"), "no-sheen.gltf");
    ASSERT_TRUE(off.ok()) << off.status();
    EXPECT_FALSE(QuadMaterial(*off).HasSheen());
    EXPECT_EQ(QuadMaterial(*off).coat_kind, gpu::kCoatFresnelMix);
}

TEST(GltfMaterialsTest, APrimitiveWithoutMaterialTakesGltfsDefault) {
    // The default material is every property at its default: white, metallic 1, roughness 1.
    testing::TestScene scene = testing::LitQuadScene();
    std::string json = testing::GltfJson(scene);
    const std::string quad = R"(,"material":0})";
    const size_t at = json.find(quad);
    ASSERT_NE(at, std::string::npos);
    json.erase(at, quad.size() - 1);  // keeps the brace
    const absl::StatusOr<Scene> loaded =
        LoadScene(testing::WriteTextFile(json, "default-material.gltf"));
    ASSERT_TRUE(loaded.ok()) << loaded.status();
    const Material& material = QuadMaterial(*loaded);
    EXPECT_EQ(material.type, MaterialType::kRoughConductor);
    EXPECT_FLOAT_EQ(material.roughness, 1.0f);
    EXPECT_EQ(material.base_color, Rgb(1.0f));
}

// Solid glass, its KHR_materials_volume's members to follow.
constexpr const char* kVolume =
    R"("KHR_materials_transmission":{"transmissionFactor":1},"KHR_materials_volume":{)"
    R"("thicknessFactor":1,)";

TEST(GltfMaterialsTest, VolumeAttenuationIsAbsorptionInsideTheGlass) {
    const absl::StatusOr<Scene> scene = QuadWith(
        Gltf(0, 0,
             std::string(kVolume) + R"("attenuationDistance":2,"attenuationColor":[1,0.5,0.25]})"),
        "volume.gltf");
    ASSERT_TRUE(scene.ok()) << scene.status();
    const Material& glass = QuadMaterial(*scene);
    EXPECT_EQ(glass.type, MaterialType::kDielectric);
    // sigma_a = -ln(colour) / distance: the colour is what crossing the distance leaves.
    EXPECT_EQ(glass.absorption.x, 0.0f);
    EXPECT_NEAR(glass.absorption.y, std::log(2.0f) / 2, 1e-6f);
    EXPECT_NEAR(glass.absorption.z, std::log(4.0f) / 2, 1e-6f);
    const absl::StatusOr<Scene> clear =
        QuadWith(Gltf(0, 0, std::string(kVolume) + R"("attenuationColor":[1,1,1]})"), "clear.gltf");
    ASSERT_TRUE(clear.ok()) << clear.status();
    EXPECT_FALSE(QuadMaterial(*clear).HasVolume()) << "no attenuationDistance: no absorption";
}

TEST(GltfMaterialsTest, ValuesOutOfRangeAreRefusedNamingTheMaterial) {
    for (const auto& [material, what] :
         {std::pair{Gltf(2, 0.5f), "metallicFactor"}, std::pair{Gltf(0, -1), "roughnessFactor"},
          std::pair{Gltf(0, 0.5f, R"("KHR_materials_specular":{"specularFactor":-1})"),
                    "specularFactor"},
          std::pair{Gltf(0, 0.5f, R"("KHR_materials_ior":{"ior":0.5})"), "ior"},
          std::pair{Gltf(0, 0.5f, R"("KHR_materials_clearcoat":{"clearcoatFactor":3})"),
                    "clearcoatFactor"},
          std::pair{Gltf(0, 0, std::string(kVolume) + R"("attenuationDistance":0})"),
                    "attenuationDistance"},
          std::pair{Gltf(0, 0, std::string(kVolume) + R"("attenuationColor":[1,2,0]})"),
                    "attenuationColor"},
          std::pair{Gltf(0, 0.5f, R"("KHR_materials_sheen":{"sheenColorFactor":[1,2,0]})"),
                    "sheenColorFactor"},
          std::pair{Gltf(0, 0.5f,
                         R"("KHR_materials_sheen":{"sheenColorFactor":[1,1,1],)"
                         R"("sheenRoughnessFactor":-0.5})"),
                    "sheenRoughnessFactor"}}) {
        const absl::StatusOr<Scene> scene = QuadWith(material, "bad.gltf");
        ASSERT_FALSE(scene.ok()) << what;
        EXPECT_NE(scene.status().message().find("material #0"), std::string::npos)
            << scene.status();
        EXPECT_NE(scene.status().message().find(what), std::string::npos) << scene.status();
    }
}

TEST(GltfMaterialsTest, UnlitIsAnEmitterOfItsBaseColourOverABlackSurface) {
    testing::TestMaterial material{Rgb(0.2f, 0.4f, 0.6f), Rgb(0.0f)};
    material.extensions = R"("KHR_materials_unlit":{})";
    const absl::StatusOr<Scene> scene = QuadWith(material, "unlit.gltf");
    ASSERT_TRUE(scene.ok()) << scene.status();
    const Material& unlit = QuadMaterial(*scene);
    EXPECT_EQ(unlit.type, MaterialType::kDiffuse);
    EXPECT_EQ(unlit.base_color, Rgb(0.0f)) << "it reflects nothing";
    EXPECT_EQ(unlit.emission, Rgb(0.2f, 0.4f, 0.6f)) << "it shows its base colour";
    EXPECT_TRUE(unlit.EmitsToward(true));
    EXPECT_FALSE(unlit.EmitsToward(false)) << "single-sided: from its front alone";
    // It lights the scene as any emitter: the unit quad's power is pi A Le, beside the light's
    // 0.16 m^2 of 10.
    const Emitters emitters(*scene);
    const Rgbd expected = Rgbd(0.2, 0.4, 0.6) * (kPiD * 4) + Rgbd(10.0) * (kPiD * 0.16);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(emitters.TotalPower()[c], expected[c], 1e-4 * expected[c]);
    // Its texture is the emission's (sRGB, as the base colour's), times the factor.
    material.texture_png_base64 =
        absl::Base64Escape(testing::TwoTexelPng({255, 255, 255, 0, 0, 0}, "unlit.png"));
    const absl::StatusOr<Scene> textured = QuadWith(material, "unlit-textured.gltf");
    ASSERT_TRUE(textured.ok()) << textured.status();
    const Material& lit_texture = QuadMaterial(*textured);
    EXPECT_EQ(lit_texture.base_color_texture, kNoTexture);
    ASSERT_NE(lit_texture.emission_texture, kNoTexture);
    EXPECT_EQ(textured->textures[lit_texture.emission_texture]->texels[0], Rgb(1.0f));
    // The file may require it.
    testing::TestScene required = testing::LitQuadScene();
    required.materials[0] = material;
    required.extra = R"(,"extensionsUsed":["KHR_materials_unlit"],)"
                     R"("extensionsRequired":["KHR_materials_unlit"])";
    EXPECT_TRUE(LoadScene(testing::WriteGltf(required, "unlit-required.gltf")).ok());
}

// The Khronos converter's specular-glossiness to metallic-roughness (the extension's
// convert-between-workflows example, three.pbrUtilities.js), written out here from its text.
struct MetalRough {
    double base[3], metallic, roughness;
};
MetalRough KhronosConverter(const double diffuse[3], const double specular[3], double glossiness) {
    const auto brightness = [](const double* c) {
        return std::sqrt(0.299 * c[0] * c[0] + 0.587 * c[1] * c[1] + 0.114 * c[2] * c[2]);
    };
    const double one_minus_specular_strength =
        1 - std::max({specular[0], specular[1], specular[2]});
    double metallic = 0;
    if (brightness(specular) >= 0.04) {
        const double a = 0.04;
        const double b = brightness(diffuse) * one_minus_specular_strength / (1 - 0.04) +
                         brightness(specular) - 2 * 0.04;
        const double c = 0.04 - brightness(specular);
        metallic =
            std::clamp((-b + std::sqrt(std::max(b * b - 4 * a * c, 0.0))) / (2 * a), 0.0, 1.0);
    }
    MetalRough out{{}, metallic, 1 - glossiness};
    for (int i = 0; i < 3; ++i) {
        const double from_diffuse =
            diffuse[i] * one_minus_specular_strength / (1 - 0.04) / std::max(1 - metallic, 1e-6);
        const double from_specular =
            (specular[i] - 0.04 * (1 - metallic)) / std::max(metallic, 1e-6);
        out.base[i] = std::clamp(
            from_diffuse + (from_specular - from_diffuse) * metallic * metallic, 0.0, 1.0);
    }
    return out;
}

// The quad with a KHR_materials_pbrSpecularGlossiness material of `extension`'s members, the
// file requiring the extension (so its metallic-roughness values are not what is read).
absl::StatusOr<Scene> SpecGlossQuad(const std::string& extension, const std::string& name,
                                    const std::vector<std::string>& images = {}) {
    testing::TestScene scene = testing::LitQuadScene();
    scene.meshes[0].uvs = {0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1};
    scene.images_png_base64 = images;
    testing::TestMaterial material{Rgb(0.5f), Rgb(0.0f)};
    material.extensions =
        absl::StrCat(R"("KHR_materials_pbrSpecularGlossiness":{)", extension, "}");
    scene.materials[0] = material;
    scene.extra = R"(,"extensionsUsed":["KHR_materials_pbrSpecularGlossiness"],)"
                  R"("extensionsRequired":["KHR_materials_pbrSpecularGlossiness"])";
    return LoadScene(testing::WriteGltf(scene, name));
}

TEST(GltfMaterialsTest, SpecularGlossinessIsConvertedAsTheKhronosConverterDoes) {
    const double diffuse[3] = {0.5, 0.3, 0.2}, specular[3] = {0.9, 0.8, 0.7};
    const MetalRough expected = KhronosConverter(diffuse, specular, 0.6);
    ASSERT_GT(expected.metallic, 0.05);
    ASSERT_LT(expected.metallic, 0.99) << "a case that mixes both";
    const absl::StatusOr<Scene> scene = SpecGlossQuad(
        R"("diffuseFactor":[0.5,0.3,0.2,1],"specularFactor":[0.9,0.8,0.7],"glossinessFactor":0.6)",
        "spec-gloss.gltf");
    ASSERT_TRUE(scene.ok()) << scene.status();
    const Material& mix = QuadMaterial(*scene);
    ASSERT_EQ(mix.type, MaterialType::kMix);
    EXPECT_NEAR(mix.mix_amount, expected.metallic, 1e-5);
    const Material& dielectric = scene->materials[mix.mix_first];
    const Material& metal = scene->materials[mix.mix_second];
    EXPECT_EQ(metal.type, MaterialType::kRoughConductor);
    EXPECT_NEAR(metal.roughness, expected.roughness * expected.roughness, 1e-5)
        << "GGX alpha: roughness squared";
    EXPECT_NEAR(dielectric.coat_roughness, expected.roughness * expected.roughness, 1e-5);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(metal.base_color[c], expected.base[c], 1e-5) << c;
        EXPECT_NEAR(dielectric.base_color[c], expected.base[c], 1e-5) << c;
    }
    // A dielectric's F0 (0.04) and full glossiness: no metal, the diffuse colour kept, smooth.
    const absl::StatusOr<Scene> plastic = SpecGlossQuad(
        R"("diffuseFactor":[0.6,0.5,0.4,1],"specularFactor":[0.04,0.04,0.04])", "plastic-sg.gltf");
    ASSERT_TRUE(plastic.ok()) << plastic.status();
    const Material& smooth = QuadMaterial(*plastic);
    EXPECT_EQ(smooth.type, MaterialType::kDiffuse);
    EXPECT_EQ(smooth.coat_kind, gpu::kCoatFresnelMix);
    EXPECT_EQ(smooth.coat_roughness, 0.0f);
    const double plastic_diffuse[3] = {0.6, 0.5, 0.4}, f0[3] = {0.04, 0.04, 0.04};
    const MetalRough plain = KhronosConverter(plastic_diffuse, f0, 1.0);
    EXPECT_EQ(plain.metallic, 0.0);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(smooth.base_color[c], plain.base[c], 1e-5);
}

TEST(GltfMaterialsTest, SpecularGlossinessTexturesAreConvertedTexelByTexel) {
    // Diffuse texels (sRGB) and specular-glossiness texels (sRGB specular, linear glossiness).
    const std::array<unsigned char, 8> diffuse_texels = {200, 100, 50, 255, 30, 60, 90, 255};
    const std::array<unsigned char, 8> specular_texels = {230, 220, 210, 128, 10, 10, 10, 255};
    const absl::StatusOr<Scene> scene = SpecGlossQuad(
        R"("diffuseFactor":[1,0.8,1,1],"specularFactor":[1,1,0.9],"glossinessFactor":0.5,)"
        R"("diffuseTexture":{"index":0},"specularGlossinessTexture":{"index":1})",
        "spec-gloss-textured.gltf",
        {absl::Base64Escape(testing::TwoTexelRgbaPng(diffuse_texels, "sg-diffuse.png", true)),
         absl::Base64Escape(testing::TwoTexelRgbaPng(specular_texels, "sg-specular.png", true))});
    ASSERT_TRUE(scene.ok()) << scene.status();
    const Material& mix = QuadMaterial(*scene);
    ASSERT_EQ(mix.type, MaterialType::kMix) << "metallic varies: a mix by a baked texture";
    EXPECT_EQ(mix.mix_amount, 1.0f);
    ASSERT_NE(mix.mix_texture, kNoTexture);
    const Material& metal = scene->materials[mix.mix_second];
    ASSERT_NE(metal.base_color_texture, kNoTexture);
    ASSERT_NE(metal.roughness_texture, kNoTexture);
    EXPECT_EQ(metal.base_color, Rgb(1.0f));
    EXPECT_EQ(metal.roughness, 1.0f);
    const auto srgb = [](unsigned char v) {
        const double x = v / 255.0;
        return x <= 0.04045 ? x / 12.92 : std::pow((x + 0.055) / 1.055, 2.4);
    };
    for (int texel = 0; texel < 2; ++texel) {
        const unsigned char* d = &diffuse_texels[4 * texel];
        const unsigned char* s = &specular_texels[4 * texel];
        const double linear_diffuse[3] = {srgb(d[0]), 0.8 * srgb(d[1]), srgb(d[2])};
        const double linear_specular[3] = {srgb(s[0]), srgb(s[1]), 0.9 * srgb(s[2])};
        const MetalRough expected =
            KhronosConverter(linear_diffuse, linear_specular, 0.5 * s[3] / 255.0);
        const Rgb base = scene->textures[metal.base_color_texture]->texels[texel];
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(base[c], expected.base[c], 1e-4) << texel;
        EXPECT_NEAR(scene->textures[mix.mix_texture]->texels[texel].x, expected.metallic, 1e-4)
            << texel;
        EXPECT_NEAR(scene->textures[metal.roughness_texture]->texels[texel].x,
                    expected.roughness * expected.roughness, 1e-4)
            << texel;
    }
}

TEST(GltfMaterialsTest, SpecularGlossinessIsReadWhereNoMetallicRoughnessIsGiven) {
    // A material with both (the extension optional) is read as its metallic-roughness values;
    // one with no pbrMetallicRoughness as its specular-glossiness ones.
    testing::TestScene scene = testing::LitQuadScene();
    testing::TestMaterial material{Rgb(0.7f), Rgb(0.0f)};
    material.extensions =
        R"("KHR_materials_pbrSpecularGlossiness":{"diffuseFactor":[0.1,0.2,0.3,1],)"
        R"("specularFactor":[0.04,0.04,0.04],"glossinessFactor":0})";
    scene.materials[0] = material;
    const absl::StatusOr<Scene> both = LoadScene(testing::WriteGltf(scene, "both.gltf"));
    ASSERT_TRUE(both.ok()) << both.status();
    EXPECT_EQ(QuadMaterial(*both).base_color, Rgb(0.7f)) << "metallic-roughness read";
    scene.materials[0].metallic_roughness = false;
    const absl::StatusOr<Scene> alone = LoadScene(testing::WriteGltf(scene, "alone.gltf"));
    ASSERT_TRUE(alone.ok()) << alone.status();
    const Rgb base = QuadMaterial(*alone).base_color;
    EXPECT_NEAR(base.x, 0.1f, 1e-6f);
    EXPECT_NEAR(base.z, 0.3f, 1e-6f);
    EXPECT_FLOAT_EQ(QuadMaterial(*alone).coat_roughness, 1.0f) << "glossiness 0: roughness 1";
}

TEST(GltfMaterialsTest, Ktx2TexturesFallBackToTheirSourceOrAreRefusedNamingTheWayOut) {
    testing::TestScene scene = testing::LitQuadScene();
    scene.meshes[0].uvs = {0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1};
    testing::TestMaterial material{Rgb(1.0f), Rgb(0.0f)};
    material.texture_png_base64 =
        absl::Base64Escape(testing::TwoTexelPng({255, 0, 0, 0, 0, 255}, "fallback.png"));
    scene.materials[0] = material;
    scene.extra = R"(,"extensionsUsed":["KHR_texture_basisu"])";
    // The texture's KTX2 image (#1, a file that is not there: never read) by the extension, its
    // PNG (#0) as its source.
    std::string json = testing::GltfJson(scene);
    const std::string texture = R"(],"textures":[{"source":0})";
    ASSERT_NE(json.find(texture), std::string::npos);
    json.replace(json.find(texture), texture.size(),
                 R"(,{"uri":"absent.ktx2","mimeType":"image/ktx2"}],"textures":[{"source":0,)"
                 R"("extensions":{"KHR_texture_basisu":{"source":1}}})");
    // Its KTX2 image, skipped on purpose, is no cause for a warning.
    std::ostringstream log;
    const auto sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(log);
    spdlog::default_logger()->sinks().push_back(sink);
    const absl::StatusOr<Scene> fallback = LoadScene(testing::WriteTextFile(json, "basisu.gltf"));
    std::erase(spdlog::default_logger()->sinks(), sink);
    ASSERT_TRUE(fallback.ok()) << fallback.status();
    EXPECT_EQ(log.str().find("absent.ktx2"), std::string::npos) << log.str();
    EXPECT_EQ(log.str().find("Failed to load"), std::string::npos) << log.str();
    const Material& read = QuadMaterial(*fallback);
    ASSERT_NE(read.base_color_texture, kNoTexture);
    EXPECT_EQ(fallback->textures[read.base_color_texture]->texels[0], Rgb(1, 0, 0)) << "the PNG";
    // Without a fallback, the file requiring the extension: refused naming the texture and the
    // way out.
    json.replace(json.find(R"({"source":0,"extensions")"), 12, "{");
    const std::string used = R"("extensionsUsed":["KHR_texture_basisu"])";
    json.replace(json.find(used), used.size(),
                 used + R"(,"extensionsRequired":["KHR_texture_basisu"])");
    const absl::StatusOr<Scene> ktx2 = LoadScene(testing::WriteTextFile(json, "basisu-only.gltf"));
    ASSERT_FALSE(ktx2.ok());
    const std::string message(ktx2.status().message());
    EXPECT_NE(message.find("basisu-only.gltf"), std::string::npos) << message;
    EXPECT_NE(message.find("texture #0"), std::string::npos) << message;
    EXPECT_NE(message.find("KHR_texture_basisu"), std::string::npos) << message;
    EXPECT_NE(message.find("ktx extract"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    // A texture whose own source is the KTX2 image (as AnisotropyBarnLamp's KTX2 variant has
    // it): the same refusal, not the image reader's words.
    const std::string by_extension = R"({"extensions":{"KHR_texture_basisu":{"source":1}}})";
    ASSERT_NE(json.find(by_extension), std::string::npos);
    json.replace(json.find(by_extension), by_extension.size(), R"({"source":1})");
    const absl::StatusOr<Scene> direct =
        LoadScene(testing::WriteTextFile(json, "ktx2-source.gltf"));
    ASSERT_FALSE(direct.ok());
    EXPECT_NE(std::string(direct.status().message()).find("ktx extract"), std::string::npos)
        << direct.status();
}

}  // namespace
}  // namespace pf
