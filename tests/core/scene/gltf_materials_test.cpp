// glTF's metallic-roughness materials (core/scene/gltf_materials.h): the dielectric as
// specular over diffuse, metallic as a mix by factor or texture, roughness squared (and its
// texture's green channel squared) as GGX alpha, KHR_materials_specular, _ior, _clearcoat and
// _sheen, and a clear error for values out of range.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include "absl/strings/escaping.h"
#include "core/scene/scene_loader.h"
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
    json.replace(at, quad.size(), "}");
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

}  // namespace
}  // namespace pf
