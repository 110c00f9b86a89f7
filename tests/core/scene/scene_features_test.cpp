// The scene analysis that selects each backend's code paths.
#include "core/scene/scene_features.h"

#include <gtest/gtest.h>

#include "core/scene_io/scene_loader.h"
#include "core/shared/coat.h"
#include "tests/support/gltf_builder.h"

namespace pf {
namespace {

SceneFeatures FeaturesOf(const Scene& scene) { return AnalyseFeatures(scene, Emitters(scene)); }

Scene Shipped(const std::string& name) {
    return *LoadScene(std::string(PF_SOURCE_DIR) + "/scenes/" + name);
}

TEST(SceneFeaturesTest, ShippedScenesUseWhatTheyShow) {
    const SceneFeatures box = FeaturesOf(Shipped("cornell-box.gltf"));
    EXPECT_FALSE(box.Specular());
    EXPECT_FALSE(box.textures);
    EXPECT_TRUE(box.triangle_lights);
    EXPECT_FALSE(box.point_lights || box.spot_lights || box.directional_lights);
    // Its light is single-sided and open (glTF's default), but an emitter's back stops rays as
    // a pbrt area light's does: no cut-out test to pay for.
    EXPECT_EQ(box.ToString(), "diffuse, area lights");
    const SceneFeatures glass = FeaturesOf(Shipped("cornell-glass.gltf"));
    EXPECT_TRUE(glass.mirror && glass.dielectric);
    EXPECT_FALSE(glass.thin_dielectric);
    EXPECT_TRUE(glass.Specular());
    EXPECT_FALSE(glass.coats);
    EXPECT_TRUE(glass.smooth_normals && glass.ShadingNormals());
    // Normal maps, a feature of their own: diffuse tiles, no specular variant needed.
    const SceneFeatures bumpy = FeaturesOf(Shipped("cornell-bumpy.gltf"));
    EXPECT_TRUE(bumpy.shading_detail && bumpy.ShadingNormals() && bumpy.ReadsUv());
    EXPECT_FALSE(bumpy.Specular() || bumpy.smooth_normals);
    EXPECT_EQ(bumpy.ToString(), "diffuse, normal or bump maps, area lights");
    EXPECT_FALSE(box.ShadingNormals());
}

TEST(SceneFeaturesTest, CurvesAreAFeatureOnlyWhereAShapeIsOne) {
    // The kernels compile the curve test out (kHasCurves) of scenes without curves; a curve's
    // cylinder normal is a shading normal.
    const SceneFeatures curves = FeaturesOf(Shipped("pbrt/cornell-curves.pbrt"));
    EXPECT_TRUE(curves.curves);
    EXPECT_TRUE(curves.ShadingNormals());
    EXPECT_FALSE(FeaturesOf(Shipped("pbrt/cornell-box.pbrt")).curves);
}

TEST(SceneFeaturesTest, CoatsAreAFeatureOfTheirOwn) {
    Scene scene = Shipped("cornell-box.gltf");
    EXPECT_FALSE(FeaturesOf(scene).coats);
    // A coat over a material no triangle uses costs nothing; over one in use it is a feature,
    // and the passes take their non-diffuse variants for it.
    scene.materials.push_back(scene.materials[0]);
    scene.materials.back().coat_ior = 1.5f;
    EXPECT_FALSE(FeaturesOf(scene).coats);
    scene.materials[scene.triangles[0].material].coat_ior = 1.5f;
    const SceneFeatures coated = FeaturesOf(scene);
    EXPECT_TRUE(coated.coats);
    EXPECT_TRUE(coated.Specular());
    EXPECT_EQ(coated.ToString(), "diffuse, coated, area lights");
}

TEST(SceneFeaturesTest, DiffuseTransmissionTakesTheGeneralPathsButMakesNoCaustics) {
    Scene scene = Shipped("cornell-box.gltf");
    EXPECT_FALSE(FeaturesOf(scene).GeneralSurfaces());
    scene.materials[scene.triangles[0].material].transmittance = Rgb(0.3f);
    const SceneFeatures translucent = FeaturesOf(scene);
    EXPECT_TRUE(translucent.translucent && translucent.GeneralSurfaces());
    EXPECT_FALSE(translucent.Specular()) << "no caustic map or probe for it";
    EXPECT_EQ(translucent.ToString(), "diffuse, diffuse transmission, area lights");
}

TEST(SceneFeaturesTest, SheenIsAFeatureWhereASurfaceWearsOne) {
    Scene scene = Shipped("cornell-box.gltf");
    EXPECT_FALSE(FeaturesOf(scene).sheen);
    Material& material = scene.materials[scene.triangles[0].material];
    material.coat_kind = gpu::kCoatNone;
    material.coat_ior = 1.0f;
    material.sheen_color = Rgb(0.5f);
    const SceneFeatures features = FeaturesOf(scene);
    EXPECT_TRUE(features.sheen && features.coats);
    EXPECT_FALSE(features.sheen_textures);
    EXPECT_EQ(features.ToString(), "diffuse, coated, sheen, area lights");
}

TEST(SceneFeaturesTest, LightsCountOnlyWithPowerAndMaterialsOnlyWhereUsed) {
    testing::TestScene scene = testing::LitQuadScene();
    scene.meshes.resize(1);  // the emissive quad's material stays, unused
    scene.lights = {R"({"type":"spot","intensity":4,"spot":{"outerConeAngle":0.6}})",
                    R"({"type":"point","intensity":0})"};
    scene.light_node_fields = {R"(,"translation":[0,0,1])", ""};
    const SceneFeatures features =
        FeaturesOf(*LoadScene(testing::WriteGltf(scene, "features.gltf")));
    EXPECT_TRUE(features.spot_lights);
    EXPECT_FALSE(features.point_lights) << "a light of no power is no emitter";
    EXPECT_FALSE(features.triangle_lights) << "an emissive material on no triangle emits nothing";
    EXPECT_EQ(SceneFeatures::All().ToString(),
              "diffuse, mirror, glass, thin glass, rough metal, rough glass, coated, "
              "specular over diffuse, metal Fresnel, absorbing media, diffuse transmission, sheen, "
              "sheen textures, cut-outs, "
              "mixed materials, "
              "textures, vertex colours, roughness textures, "
              "textured mixes, procedural textures, smooth normals, curves, normal or bump maps, "
              "area lights, "
              "point lights, spot lights, directional lights, environment light, textured lights, "
              "goniometric or projection lights, caustics");
}

}  // namespace
}  // namespace pf
