// Loading the shipped scenes, and one-line errors that name the file and element for bad ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "core/scene/emitters.h"
#include "core/scene/mesh_builder.h"
#include "core/scene/scene_features.h"
#include "core/scene_io/scene_loader.h"
#include "tests/support/gltf_builder.h"

namespace pf {
namespace {

std::string ScenePath(const std::string& name) {
    return std::string(PF_SOURCE_DIR) + "/scenes/" + name;
}

int CountMaterials(const Scene& scene, MaterialType type) {
    return static_cast<int>(std::count_if(scene.materials.begin(), scene.materials.end(),
                                          [&](const Material& m) { return m.type == type; }));
}

// Writes the scene's JSON with the first occurrence of `from` replaced by `to`.
std::string WriteEdited(const testing::TestScene& scene, const std::string& from,
                        const std::string& to, const std::string& name) {
    std::string json = testing::GltfJson(scene);
    const size_t at = json.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) json.replace(at, from.size(), to);
    return testing::WriteTextFile(json, name);
}

void ExpectError(const absl::StatusOr<Scene>& scene, const std::string& file,
                 const std::string& fragment) {
    ASSERT_FALSE(scene.ok());
    const std::string message(scene.status().message());
    EXPECT_NE(message.find(file), std::string::npos) << message;
    EXPECT_NE(message.find(fragment), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "error must be one line: " << message;
}

TEST(GltfLoaderTest, LoadsTheShippedScenes) {
    for (const char* name : {"cornell-box.gltf", "cornell-glass.gltf", "caustic-glass.gltf",
                             "furnace.gltf", "cornell-bumpy.gltf"}) {
        const absl::StatusOr<Scene> scene = LoadScene(ScenePath(name));
        ASSERT_TRUE(scene.ok()) << scene.status();
        EXPECT_GT(scene->triangles.size(), 0u);
        EXPECT_GT(scene->bounds.Diagonal(), 0.0f);
    }
    const absl::StatusOr<Scene> glass = LoadScene(ScenePath("cornell-glass.gltf"));
    ASSERT_TRUE(glass.ok());
    EXPECT_EQ(CountMaterials(*glass, MaterialType::kDielectric), 1);
    EXPECT_EQ(CountMaterials(*glass, MaterialType::kMirror), 1);
    const absl::StatusOr<Scene> box = LoadScene(ScenePath("cornell-box.gltf"));
    ASSERT_TRUE(box.ok());
    EXPECT_EQ(CountMaterials(*box, MaterialType::kDielectric), 0);
    // The measured camera: 35 mm lens on 25 mm film, looking down +z from z = -0.8.
    EXPECT_NEAR(box->camera.y_fov, 2 * std::atan(12.5 / 35), 1e-5);
    EXPECT_NEAR(box->camera.forward.z, 1.0f, 1e-5f);
    EXPECT_NEAR(box->camera.position.z, -0.8f, 1e-5f);
}

TEST(GltfLoaderTest, GlbAndGltfLoadTheSameGeometry) {
    const testing::TestScene scene = testing::LitQuadScene();
    const absl::StatusOr<Scene> text = LoadScene(testing::WriteGltf(scene, "quad.gltf"));
    const absl::StatusOr<Scene> binary = LoadScene(testing::WriteGlb(scene, "quad.glb"));
    ASSERT_TRUE(text.ok()) << text.status();
    ASSERT_TRUE(binary.ok()) << binary.status();
    ASSERT_EQ(text->positions.size(), binary->positions.size());
    for (size_t i = 0; i < text->positions.size(); ++i)
        EXPECT_EQ(text->positions[i], binary->positions[i]);
}

TEST(GltfLoaderTest, PunctualLightsAreRead) {
    testing::TestScene scene = testing::LitQuadScene();
    scene.materials[1].emission = Rgb(0.0f);
    scene.lights = {
        R"({"type":"point","intensity":3415,"color":[1,0.5,0.25],"range":4})",
        R"({"type":"spot","intensity":2,"spot":{"innerConeAngle":0.1,"outerConeAngle":0.5}})",
        R"({"type":"directional","intensity":683})"};
    const absl::StatusOr<Scene> loaded = LoadScene(testing::WriteGltf(scene, "lights.gltf"));
    ASSERT_TRUE(loaded.ok()) << loaded.status();
    ASSERT_EQ(loaded->lights.size(), 3u);
    EXPECT_EQ(loaded->lights[0].type, LightType::kPoint);
    // Candela and lux at 683 lm/W: 3415 cd is 5 W/sr.
    EXPECT_NEAR(loaded->lights[0].intensity.x, 5.0f, 1e-5f);
    EXPECT_NEAR(loaded->lights[0].intensity.z, 1.25f, 1e-5f);
    EXPECT_EQ(loaded->lights[0].range, 4.0f);
    EXPECT_EQ(loaded->lights[0].RangeWindow(2.0f), 1.0f - 1.0f / 16);
    EXPECT_EQ(loaded->lights[0].RangeWindow(5.0f), 0.0f);
    EXPECT_EQ(loaded->lights[1].range, 0.0f);
    EXPECT_EQ(loaded->lights[1].RangeWindow(1e9f), 1.0f);
    EXPECT_EQ(loaded->lights[1].type, LightType::kSpot);
    EXPECT_NEAR(loaded->lights[1].cos_outer, std::cos(0.5f), 1e-6f);
    EXPECT_EQ(loaded->lights[2].type, LightType::kDirectional);
    EXPECT_EQ(loaded->lights[2].direction, Vec3(0, 0, -1));
    EXPECT_NEAR(loaded->lights[2].intensity.y, 1.0f, 1e-6f);  // 683 lux: 1 W/m^2
}

TEST(GltfLoaderTest, OrthographicCamerasSpanTheirMagnification) {
    // xmag 2, ymag 1: a view 4 wide and 2 tall along the camera's -z, from z = 3.
    const std::string path = WriteEdited(
        testing::LitQuadScene(), R"("type":"perspective","perspective":{"yfov":0.8,"znear":0.01})",
        R"("type":"orthographic","orthographic":{"xmag":2,"ymag":1,"znear":0.01,"zfar":100})",
        "orthographic.gltf");
    const absl::StatusOr<Scene> scene = LoadScene(path);
    ASSERT_TRUE(scene.ok()) << scene.status();
    const Camera& camera = scene->camera;
    EXPECT_EQ(camera.projection, Projection::kOrthographic);
    EXPECT_EQ(camera.aspect_ratio, 2.0f);
    const Ray corner = camera.GenerateRay(0, 0, 2.0f);  // top left
    EXPECT_NEAR(corner.origin.x, -2.0f, 1e-6f);
    EXPECT_NEAR(corner.origin.y, 1.0f, 1e-6f);
    EXPECT_NEAR(corner.origin.z, 3.0f, 1e-6f);
    EXPECT_NEAR(corner.direction.z, -1.0f, 1e-6f);
    ExpectError(
        LoadScene(WriteEdited(
            testing::LitQuadScene(),
            R"("type":"perspective","perspective":{"yfov":0.8,"znear":0.01})",
            R"("type":"orthographic","orthographic":{"xmag":0,"ymag":1,"znear":0.01,"zfar":100})",
            "orthographic-flat.gltf")),
        "orthographic-flat.gltf", "orthographic xmag and ymag must be positive");
}

TEST(GltfLoaderTest, BaseColourTextureIsDecodedToLinearAndSampled) {
    // A 2x1 PNG: sRGB (255, 0, 0) on the left, (128, 128, 128) on the right.
    testing::TestScene scene = testing::LitQuadScene();
    scene.materials[0].base_color = Rgb(1.0f, 1.0f, 0.5f);
    scene.materials[0].texture_png_base64 =
        "iVBORw0KGgoAAAANSUhEUgAAAAIAAAABCAIAAAB7QOjdAAAAD0lEQVR4nGP4z8DQ0NAAAAkBAoCZxGkyAAAAAElFTk"
        "SuQmCC";
    scene.meshes[0].uvs = {0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1};
    const absl::StatusOr<Scene> loaded = LoadScene(testing::WriteGltf(scene, "textured.gltf"));
    ASSERT_TRUE(loaded.ok()) << loaded.status();
    ASSERT_EQ(loaded->textures.size(), 1u);
    const Texture& texture = *loaded->textures[0];
    EXPECT_EQ(texture.Texel(0, 0), Rgb(1.0f, 0.0f, 0.0f));
    EXPECT_NEAR(texture.Texel(1, 0).x, 0.2158605f, 1e-5f);  // sRGB 128 in linear
    // The surface's base colour is factor x texture at its uv: the left texel's centre.
    SurfacePoint surface;
    surface.material = loaded->triangles[0].material;
    surface.uv = {0.25f, 0.5f};
    EXPECT_EQ(loaded->BaseColor(surface), Rgb(1.0f, 0.0f, 0.0f));
    surface.uv = {0.75f, 0.5f};
    EXPECT_NEAR(loaded->BaseColor(surface).z, 0.5f * 0.2158605f, 1e-5f);
}

TEST(GltfLoaderTest, SamplersWrapModesAddressTheTexture) {
    testing::TestScene scene = testing::LitQuadScene();
    scene.materials[0].texture_png_base64 =
        "iVBORw0KGgoAAAANSUhEUgAAAAIAAAABCAIAAAB7QOjdAAAAD0lEQVR4nGP4z8DQ0NAAAAkBAoCZxGkyAAAAAElFTk"
        "SuQmCC";
    scene.materials[0].texture_sampler = R"({"wrapS":33071,"wrapT":33648,"magFilter":9728})";
    scene.meshes[0].uvs = {0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1};
    const absl::StatusOr<Scene> loaded = LoadScene(testing::WriteGltf(scene, "wrapped.gltf"));
    ASSERT_TRUE(loaded.ok()) << loaded.status();
    ASSERT_EQ(loaded->textures.size(), 1u);
    EXPECT_EQ(loaded->textures[0]->wrap_u, gpu::kWrapClamp);   // CLAMP_TO_EDGE
    EXPECT_EQ(loaded->textures[0]->wrap_v, gpu::kWrapMirror);  // MIRRORED_REPEAT
}

constexpr char kTwoTexelPng[] =
    "iVBORw0KGgoAAAANSUhEUgAAAAIAAAABCAIAAAB7QOjdAAAAD0lEQVR4nGP4z8DQ0NAAAAkBAoCZxGkyAAAAAElFTkSuQm"
    "CC";

// 2x1 RGBA: white, transparent on the left, opaque on the right.
constexpr char kHalfTransparentPng[] =
    "iVBORw0KGgoAAAANSUhEUgAAAAIAAAABCAYAAAD0In+KAAAAEElEQVR4nGP4//8/AxD/BwAe6gb6OStlagAAAABJRU5E"
    "rkJggg==";

TEST(GltfLoaderTest, AlphaModesCutOutWhereAlphaSays) {
    testing::TestScene scene = testing::LitQuadScene();
    scene.materials[0].texture_png_base64 = kHalfTransparentPng;
    scene.meshes[0].uvs = {0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1};
    // (Double-sided: a single-sided open quad has its back faces cut out.)
    const auto floor_of = [&](const std::string& extra) {
        scene.materials[0].extra = R"(,"doubleSided":true)" + extra;
        const absl::StatusOr<Scene> loaded = LoadScene(testing::WriteGltf(scene, "alpha.gltf"));
        EXPECT_TRUE(loaded.ok()) << loaded.status();
        return loaded.ok() ? std::optional<Scene>(*loaded) : std::nullopt;
    };
    // OPAQUE (the default) reads no alpha.
    std::optional<Scene> opaque = floor_of("");
    ASSERT_TRUE(opaque);
    EXPECT_FALSE(opaque->materials[opaque->triangles[0].material].HasCutOuts());
    // MASK: the texture's alpha (linear) against the cutoff; the surface is cut on the left.
    std::optional<Scene> mask = floor_of(R"(,"alphaMode":"MASK","alphaCutoff":0.3)");
    ASSERT_TRUE(mask);
    const Material& masked = mask->materials[mask->triangles[0].material];
    EXPECT_TRUE(masked.HasCutOuts());
    EXPECT_EQ(masked.alpha_cutoff, 0.3f);
    ASSERT_NE(masked.alpha_texture, kNoTexture);
    EXPECT_NE(masked.alpha_texture, masked.base_color_texture) << "a texture of its own";
    EXPECT_EQ(mask->textures[masked.alpha_texture]->texels[0], Rgb(0.0f));
    EXPECT_EQ(mask->textures[masked.alpha_texture]->texels[1], Rgb(1.0f));
    EXPECT_EQ(mask->textures[masked.base_color_texture]->texels[0], Rgb(1.0f)) << "colour kept";
    // BLEND: coverage, no cutoff.
    std::optional<Scene> blend = floor_of(R"(,"alphaMode":"BLEND")");
    ASSERT_TRUE(blend);
    EXPECT_EQ(blend->materials[blend->triangles[0].material].alpha_cutoff, 0.0f);
    EXPECT_TRUE(blend->materials[blend->triangles[0].material].HasCutOuts());
    // An image without alpha cuts nothing out, and costs nothing.
    scene.materials[0].texture_png_base64 = kTwoTexelPng;
    std::optional<Scene> rgb = floor_of(R"(,"alphaMode":"MASK")");
    ASSERT_TRUE(rgb);
    EXPECT_FALSE(rgb->materials[rgb->triangles[0].material].HasCutOuts());
    scene.materials[0].extra = R"(,"alphaMode":"MASK","alphaCutoff":-1)";
    const absl::StatusOr<Scene> bad = LoadScene(testing::WriteGltf(scene, "alpha-bad.gltf"));
    ASSERT_FALSE(bad.ok());
    EXPECT_NE(bad.status().message().find("alphaCutoff must lie in [0, 1]"), std::string::npos)
        << bad.status();
}

TEST(GltfLoaderTest, TextureTransformIsAppliedToTheTextureCoordinates) {
    // KHR_texture_transform: uv' = offset + rotation(scale uv); a quarter turn maps (1, 0) to
    // (0, -1) before the offset.
    testing::TestScene scene = testing::LitQuadScene();
    scene.materials[0].texture_png_base64 = kTwoTexelPng;
    scene.materials[0].texture_extra =
        R"(,"extensions":{"KHR_texture_transform":{"offset":[0.5,0.25],"scale":[2,3],"rotation":1.5707963267948966}})";
    scene.meshes[0].uvs = {0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1};
    const absl::StatusOr<Scene> loaded =
        LoadScene(testing::WriteGltf(scene, "texture-transform.gltf"));
    ASSERT_TRUE(loaded.ok()) << loaded.status();
    // Vertex 1 had uv (1, 0): scaled (2, 0), turned to (0, -2), offset to (0.5, -1.75).
    EXPECT_NEAR(loaded->uvs[1].x, 0.5f, 1e-6f);
    EXPECT_NEAR(loaded->uvs[1].y, -1.75f, 1e-6f);
    // Vertex 2, uv (1, 1): scaled (2, 3), turned to (3, -2), offset to (3.5, -1.75).
    EXPECT_NEAR(loaded->uvs[2].x, 3.5f, 1e-6f);
    EXPECT_NEAR(loaded->uvs[2].y, -1.75f, 1e-6f);
}

TEST(GltfLoaderTest, EmissiveTextureTimesFactorIsTheEmission) {
    // The lit quad's light (material 1) with the two-texel image as its emissiveTexture: the
    // emission is emissiveFactor x the sRGB-decoded texel at the surface's TEXCOORD_0; without
    // an emissiveFactor (glTF's default is black) the texture emits nothing.
    testing::TestScene scene = testing::LitQuadScene();
    scene.materials[1].texture_png_base64 = kTwoTexelPng;
    scene.materials[1].texture_emissive = true;
    scene.meshes[1].uvs = {0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1};
    const absl::StatusOr<Scene> loaded = LoadScene(testing::WriteGltf(scene, "emissive.gltf"));
    ASSERT_TRUE(loaded.ok()) << loaded.status();
    const Material* light = nullptr;
    for (const Triangle& triangle : loaded->triangles)
        if (loaded->materials[triangle.material].IsEmissive())
            light = &loaded->materials[triangle.material];
    ASSERT_NE(light, nullptr);
    EXPECT_EQ(light->base_color_texture, kNoTexture);
    ASSERT_NE(light->emission_texture, kNoTexture);
    SurfacePoint surface;
    surface.material = static_cast<uint32_t>(light - loaded->materials.data());
    surface.uv = {0.25f, 0.5f};
    EXPECT_EQ(loaded->Emission(surface), light->emission * Rgb(1.0f, 0.0f, 0.0f));
    surface.uv = {0.75f, 0.5f};
    EXPECT_NEAR(loaded->Emission(surface).y, light->emission.y * 0.2158605f, 1e-4f);

    scene.materials[0].emission = Rgb(0.0f);  // the floor: textured, with no emissiveFactor
    scene.materials[0].texture_png_base64 = kTwoTexelPng;
    scene.materials[0].texture_emissive = true;
    const absl::StatusOr<Scene> dark = LoadScene(testing::WriteGltf(scene, "dark-emissive.gltf"));
    ASSERT_TRUE(dark.ok()) << dark.status();
    EXPECT_EQ(dark->materials[dark->triangles[0].material].emission_texture, kNoTexture);
}

TEST(GltfLoaderTest, ADoubleSidedEmissiveMaterialEmitsFromBothFaces) {
    // glTF draws a doubleSided material's back face too: the lit quad's light then emits
    // from both, twice the power (pi A Le a face).
    testing::TestScene scene = testing::LitQuadScene();
    const absl::StatusOr<Scene> one = LoadScene(testing::WriteGltf(scene, "one-sided.gltf"));
    scene.materials[1].extra = R"(,"doubleSided":true)";
    const absl::StatusOr<Scene> two = LoadScene(testing::WriteGltf(scene, "two-sided.gltf"));
    ASSERT_TRUE(one.ok() && two.ok());
    const double area = 0.4 * 0.4, face = kPiD * area * 10;
    EXPECT_NEAR(Emitters(*one).TotalPower().x, face, 1e-4 * face);
    EXPECT_NEAR(Emitters(*two).TotalPower().x, 2 * face, 1e-4 * face);
    for (const Triangle& triangle : two->triangles) {
        const Material& material = two->materials[triangle.material];
        EXPECT_EQ(material.EmitsToward(false), material.IsEmissive());
    }
}

TEST(GltfLoaderTest, GlbWithTheImageInItsBinaryChunk) {
    testing::TestScene scene = testing::LitQuadScene();
    scene.materials[0].texture_png_base64 = kTwoTexelPng;
    scene.meshes[0].uvs = {0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1};
    scene.images_in_buffer = true;
    const std::string path = testing::WriteGlb(scene, "embedded-image.glb");
    const absl::StatusOr<SceneBundle> bundle = PackSceneBundle(path);
    ASSERT_TRUE(bundle.ok()) << bundle.status();
    EXPECT_EQ(bundle->files.size(), 1u);  // the image travels inside the .glb
    const absl::StatusOr<Scene> loaded = LoadScene(*bundle, path);
    ASSERT_TRUE(loaded.ok()) << loaded.status();
    ASSERT_EQ(loaded->textures.size(), 1u);
    EXPECT_EQ(loaded->textures[0]->Texel(0, 0), Rgb(1.0f, 0.0f, 0.0f));
}

TEST(GltfLoaderTest, MeshesUsedByManyNodesAreInstanced) {
    testing::TestScene scene = testing::LitQuadScene();
    scene.extra_nodes = {R"({"mesh":0,"translation":[0,0,-2]})",
                         R"({"mesh":0,"translation":[0,0,-4],"scale":[-1,1,1]})"};
    const absl::StatusOr<Scene> loaded = LoadScene(testing::WriteGltf(scene, "instanced.gltf"));
    ASSERT_TRUE(loaded.ok()) << loaded.status();
    // The quad is stored once and placed three times; the light, used by one node, is not a
    // prototype.
    ASSERT_EQ(loaded->prototypes.size(), 1u);
    EXPECT_EQ(loaded->prototypes[0].triangle_count, 2u);
    EXPECT_EQ(loaded->instances.size(), 3u);
    EXPECT_EQ(loaded->WorldTriangleCount(), 2u);
    EXPECT_EQ(loaded->triangles.size(), 4u);
    EXPECT_NEAR(loaded->bounds.lower.z, -4.0f, 1e-6f);
    // Expanded, the quad three times and the light once; the mirrored instance still faces +z.
    const absl::StatusOr<Scene> flat = FlattenInstances(*loaded, 100);
    ASSERT_TRUE(flat.ok()) << flat.status();
    ASSERT_EQ(flat->triangles.size(), 8u);
    EXPECT_TRUE(flat->instances.empty());
    for (const Triangle& t : flat->triangles) {
        if (flat->materials[t.material].emission.x == 0) {
            EXPECT_NEAR(t.normal.z, 1.0f, 1e-6f);
        }
    }
    EXPECT_EQ(FlattenInstances(*loaded, 7).status().code(), absl::StatusCode::kResourceExhausted);
}

TEST(GltfLoaderTest, OversizedImagesAreRefusedBeforeDecoding) {
    testing::TestScene scene = testing::LitQuadScene();
    scene.materials[0].texture_png_base64 = kTwoTexelPng;
    scene.meshes[0].uvs = {0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1};
    SceneLoadOptions options;
    options.limits.max_image_pixels = 1;
    const std::string path = testing::WriteGltf(scene, "big-image.gltf");
    const absl::StatusOr<Scene> loaded = LoadScene(path, options);
    ASSERT_FALSE(loaded.ok());
    EXPECT_EQ(loaded.status().code(), absl::StatusCode::kResourceExhausted);
    ExpectError(loaded, path, "image is 2x1, over the limit of 1 pixels");
}

TEST(GltfLoaderTest, MissingFileIsNamed) {
    ExpectError(LoadScene("/nonexistent/scene.gltf"), "/nonexistent/scene.gltf", "cannot open");
}

TEST(GltfLoaderTest, MalformedJsonIsRefused) {
    const std::string path =
        testing::WriteTextFile("{\"asset\": {\"version\": \"2.0\"", "broken.gltf");
    ExpectError(LoadScene(path), path, "not a valid glTF");
}

TEST(GltfLoaderTest, SceneWithoutCameraIsFramedOnItsBounds) {
    testing::TestScene test_scene = testing::LitQuadScene();
    test_scene.camera = false;
    const std::string path = testing::WriteGltf(test_scene, "no-camera.gltf");
    const absl::StatusOr<Scene> scene = LoadScene(path);
    ASSERT_TRUE(scene.ok()) << scene.status();
    // 45 degrees from +z at the bounds' centre; every corner of the bounds in view.
    const Camera& camera = scene->camera;
    EXPECT_NEAR(camera.y_fov, kPi / 4, 1e-6f);
    EXPECT_EQ(camera.forward, Vec3(0, 0, -1));
    const Vec3 centre = scene->bounds.Center();
    EXPECT_NEAR(camera.position.x, centre.x, 1e-6f);
    EXPECT_GT(camera.position.z, scene->bounds.upper.z);
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 p((corner & 1) ? scene->bounds.upper.x : scene->bounds.lower.x,
                     (corner & 2) ? scene->bounds.upper.y : scene->bounds.lower.y,
                     (corner & 4) ? scene->bounds.upper.z : scene->bounds.lower.z);
        const Vec3 to = Normalize(p - camera.position);
        EXPECT_GE(Dot(to, camera.forward), std::cos(camera.y_fov / 2) - 1e-5f) << corner;
    }
    // A camera asked for that is not there is an error.
    SceneLoadOptions options;
    options.camera = "1";
    ExpectError(LoadScene(path, options), "--camera 1", "the scene has no camera");
}

TEST(GltfLoaderTest, AnUnknownRequiredExtensionIsRefusedNamingIt) {
    testing::TestScene scene = testing::LitQuadScene();
    const std::string json = testing::GltfJson(scene);
    const std::string required = testing::WriteTextFile(
        json.substr(0, json.rfind('}')) +
            R"(,"extensionsUsed":["KHR_materials_anisotropy","KHR_texture_transform"],)"
            R"("extensionsRequired":["KHR_texture_transform","KHR_materials_anisotropy"]})",
        "anisotropy-required.gltf");
    ExpectError(LoadScene(required), required,
                "extensionsRequired: 'KHR_materials_anisotropy' is not supported");
    // Required extensions that are read load.
    const std::string supported = testing::WriteTextFile(
        json.substr(0, json.rfind('}')) +
            R"(,"extensionsUsed":["KHR_texture_transform"],"extensionsRequired":["KHR_texture_transform"]})",
        "transform-required.gltf");
    EXPECT_TRUE(LoadScene(supported).ok());
}

TEST(GltfLoaderTest, CameraChosenByNumberOrName) {
    testing::TestScene test_scene = testing::LitQuadScene();
    test_scene.extra_nodes = {
        R"({"name":"top","camera":0,"translation":[0,5,0],"rotation":[-0.7071068,0,0,0.7071068]})"};
    const std::string path = testing::WriteGltf(test_scene, "two-cameras.gltf");
    SceneLoadOptions options;
    for (const char* which : {"", "0"}) {
        options.camera = which;
        const absl::StatusOr<Scene> scene = LoadScene(path, options);
        ASSERT_TRUE(scene.ok()) << scene.status();
        EXPECT_EQ(scene->camera.position, Vec3(0, 0, 3)) << which;
    }
    for (const char* which : {"1", "top"}) {
        options.camera = which;
        const absl::StatusOr<Scene> scene = LoadScene(path, options);
        ASSERT_TRUE(scene.ok()) << scene.status();
        EXPECT_EQ(scene->camera.position, Vec3(0, 5, 0)) << which;
        EXPECT_NEAR(scene->camera.forward.y, -1.0f, 1e-5f) << which;
    }
    options.camera = "side";
    ExpectError(LoadScene(path, options), "--camera side", "no such camera; the scene has 0 '");
    ExpectError(LoadScene(path, options), "--camera side", "1 'top'");
}

TEST(GltfLoaderTest, SceneWithoutLightIsRefused) {
    testing::TestScene scene = testing::LitQuadScene();
    scene.materials[1].emission = Rgb(0.0f);
    const std::string path = testing::WriteGltf(scene, "no-light.gltf");
    ExpectError(LoadScene(path), path, "no light");
}

TEST(GltfLoaderTest, NonFiniteTransformIsRefusedNamingTheNode) {
    // JSON has no NaN or Inf literal: a non-finite transform arises when a hierarchy's scales
    // overflow. The camera node (#2) scales by 1e200 and so does its child (#3): 1e400 is Inf.
    testing::TestScene scene = testing::LitQuadScene();
    scene.camera_extra = R"(,"scale":[1e200,1,1],"children":[3])";
    const std::string path =
        WriteEdited(scene, R"(],"meshes")", R"(,{"name":"inner","scale":[1e200,1,1]}],"meshes")",
                    "inf-transform.gltf");
    ExpectError(LoadScene(path), path,
                "node 'inner' (#3): world transform overflows to NaN or Inf");
}

TEST(GltfLoaderTest, VertexOverflowingItsTransformIsRefused) {
    const std::string path =
        WriteEdited(testing::LitQuadScene(), R"({"mesh":0})", R"({"mesh":0,"scale":[1e300,1,1]})",
                    "vertex-overflow.gltf");
    ExpectError(LoadScene(path), path,
                "mesh #0 primitive 0: vertex 0 is not finite after its transform");
}

TEST(GltfLoaderTest, NonFiniteVertexIsRefusedNamingTheMesh) {
    testing::TestScene scene = testing::LitQuadScene();
    scene.meshes[0].positions[4].y = std::numeric_limits<float>::quiet_NaN();
    const std::string path = testing::WriteGltf(scene, "nan-vertex.gltf");
    ExpectError(LoadScene(path), path, "mesh #0 primitive 0: vertex 4 position has NaN or Inf");
}

TEST(GltfLoaderTest, IndexOutOfRangeCannotReadOutsideTheBuffer) {
    const std::string path =
        WriteEdited(testing::LitQuadScene(), R"("count":6)", R"("count":600)", "overrun.gltf");
    ExpectError(LoadScene(path), path, "accessor #0 lies outside its buffer");
}

// The hit of world triangle `triangle` at barycentrics (b1, b2).
}  // namespace
}  // namespace pf
