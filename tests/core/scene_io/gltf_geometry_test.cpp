// glTF geometry beyond triangles as given: vertex colours, single-sided meshes, skins, morph
// targets, strips and fans, GPU instances.
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

RayHit HitAt(uint32_t triangle, float b1, float b2) {
    RayHit hit;
    hit.triangle = triangle, hit.b1 = b1, hit.b2 = b2;
    return hit;
}

TEST(GltfLoaderTest, VertexColoursMultiplyTheBaseColourAtTheHit) {
    // The floor's six corners (two triangles), each an RGBA colour; its base colour 0.5.
    const std::vector<float> colors = {1, 0, 0, 1, 0, 1, 0, 0.5f, 0, 0, 1, 1,
                                       1, 0, 0, 1, 0, 0, 1, 1,    1, 1, 1, 1};
    testing::TestScene scene = testing::LitQuadScene();
    scene.meshes[0].colors = colors;
    const absl::StatusOr<Scene> loaded = LoadScene(testing::WriteGltf(scene, "colors.gltf"));
    ASSERT_TRUE(loaded.ok()) << loaded.status();
    ASSERT_EQ(loaded->colors.size(), loaded->positions.size()) << "the light's vertices white";
    EXPECT_EQ(loaded->colors[1].rgb, Rgb(0, 1, 0));
    EXPECT_EQ(loaded->colors[1].alpha, 0.5f);
    EXPECT_EQ(loaded->colors[7].rgb, Rgb(1.0f)) << "the light has none: white";
    EXPECT_TRUE(AnalyseFeatures(*loaded, Emitters(*loaded)).vertex_colors);
    // Interpolated at the hit: base colour x (b0 c0 + b1 c1 + b2 c2).
    const SurfacePoint surface = loaded->Surface(HitAt(0, 0.25f, 0.5f));
    const Rgb expected =
        Rgb(0.5f) * (Rgb(1, 0, 0) * 0.25f + Rgb(0, 1, 0) * 0.25f + Rgb(0, 0, 1) * 0.5f);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(loaded->BaseColor(surface)[c], expected[c], 1e-6f);
    // OPAQUE reads no alpha: the colour's alpha cuts nothing (double-sided, so nothing else).
    scene.materials[0].extra = R"(,"doubleSided":true)";
    const absl::StatusOr<Scene> opaque = LoadScene(testing::WriteGltf(scene, "colors-opaque.gltf"));
    ASSERT_TRUE(opaque.ok()) << opaque.status();
    EXPECT_FALSE(opaque->materials[opaque->triangles[0].material].HasCutOuts());
    // BLEND multiplies the colours' alpha into the base colour's.
    scene.materials[0].extra = R"(,"doubleSided":true,"alphaMode":"BLEND")";
    const absl::StatusOr<Scene> blend = LoadScene(testing::WriteGltf(scene, "colors-blend.gltf"));
    ASSERT_TRUE(blend.ok()) << blend.status();
    EXPECT_TRUE(blend->materials[blend->triangles[0].material].HasCutOuts());
    EXPECT_NEAR(blend->Alpha(0, 0.25f, 0.5f), 0.25f * 1 + 0.25f * 0.5f + 0.5f * 1, 1e-6f);
    // Normalised unsigned bytes and shorts, and VEC3: 51/255 and 13107/65535 are 0.2.
    for (const int bytes : {1, 2}) {
        const uint16_t full = bytes == 1 ? 255 : 65535, fifth = bytes == 1 ? 51 : 13107;
        testing::TestScene integer = testing::LitQuadScene();
        integer.meshes[0].color_components = 3;
        integer.meshes[0].color_bytes = bytes;
        for (int v = 0; v < 6; ++v)
            integer.meshes[0].colors_unorm.insert(integer.meshes[0].colors_unorm.end(),
                                                  {fifth, full, 0});
        const absl::StatusOr<Scene> read =
            LoadScene(testing::WriteGltf(integer, absl::StrCat("colors-", bytes, ".gltf")));
        ASSERT_TRUE(read.ok()) << read.status();
        ASSERT_FALSE(read->colors.empty());
        EXPECT_NEAR(read->colors[0].rgb.x, 0.2f, 1e-7f);
        EXPECT_EQ(read->colors[0].rgb.y, 1.0f);
        EXPECT_EQ(read->colors[0].alpha, 1.0f);
    }
    // Colours that are all white multiply nothing, and cost nothing.
    scene.meshes[0].colors.assign(24, 1.0f);
    const absl::StatusOr<Scene> white = LoadScene(testing::WriteGltf(scene, "colors-white.gltf"));
    ASSERT_TRUE(white.ok()) << white.status();
    EXPECT_TRUE(white->colors.empty());
    EXPECT_FALSE(AnalyseFeatures(*white, Emitters(*white)).vertex_colors);
}

TEST(GltfLoaderTest, UnlitEmissionTakesTheVertexColours) {
    testing::TestScene scene = testing::LitQuadScene();
    scene.materials[0].extensions = R"("KHR_materials_unlit":{})";
    scene.materials[0].base_color = Rgb(0.8f);
    scene.meshes[0].color_components = 3;
    scene.meshes[0].colors = {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 1, 1};
    const absl::StatusOr<Scene> loaded = LoadScene(testing::WriteGltf(scene, "unlit-colors.gltf"));
    ASSERT_TRUE(loaded.ok()) << loaded.status();
    const SurfacePoint surface = loaded->Surface(HitAt(0, 0.5f, 0.25f));
    const Rgb expected = Rgb(0.8f) * Rgb(0.25f, 0.5f, 0.25f);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(loaded->Emission(surface)[c], expected[c], 1e-6f);
    // Photons and light samples see the same: a triangle's power is pi A Le x its colours'
    // mean (the mean of a linear function over a triangle is its value at the centroid).
    const Emitters emitters(*loaded);
    const Rgbd first = Rgbd(0.8) * (Rgbd(1, 0, 0) + Rgbd(0, 1, 0) + Rgbd(0, 0, 1)) * (kPiD * 2 / 3);
    const Rgbd second =
        Rgbd(0.8) * (Rgbd(1, 0, 0) + Rgbd(0, 0, 1) + Rgbd(1, 1, 1)) * (kPiD * 2 / 3);
    const Rgbd total = first + second + Rgbd(10.0) * (kPiD * 0.16);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(emitters.TotalPower()[c], total[c], 1e-5 * total[c]);
    const Emitters::Hit seen =
        emitters.HitEmitter(HitAt(0, 0.5f, 0.25f), Vec3(0, 0, 1), surface.position);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(seen.radiance[c], expected[c], 1e-6f);
}

TEST(GltfLoaderTest, OpenSingleSidedMeshesLetRaysThroughTheirBackFaces) {
    const auto material_of = [](const absl::StatusOr<Scene>& scene) -> const Material& {
        return scene->materials[scene->triangles[0].material];
    };
    // glTF's default: single-sided. The open quad's back faces are cut out.
    testing::TestScene scene = testing::LitQuadScene();
    const absl::StatusOr<Scene> open = LoadScene(testing::WriteGltf(scene, "open.gltf"));
    ASSERT_TRUE(open.ok()) << open.status();
    EXPECT_TRUE(material_of(open).SingleSided());
    EXPECT_TRUE(AnalyseFeatures(*open, Emitters(*open)).cut_outs);
    // Double-sided: as it was.
    scene.materials[0].extra = R"(,"doubleSided":true)";
    const absl::StatusOr<Scene> both = LoadScene(testing::WriteGltf(scene, "double.gltf"));
    ASSERT_TRUE(both.ok()) << both.status();
    EXPECT_FALSE(material_of(both).SingleSided());
    // A closed tetrahedron is never seen from behind: nothing to cut, nothing to pay; with a
    // face left out it is open.
    const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), d(0, 0, 1);
    scene.materials[0].extra = "";
    scene.meshes[0].positions = {a, c, b, a, b, d, a, d, c, b, c, d};
    const absl::StatusOr<Scene> closed = LoadScene(testing::WriteGltf(scene, "closed.gltf"));
    ASSERT_TRUE(closed.ok()) << closed.status();
    EXPECT_FALSE(material_of(closed).SingleSided());
    scene.meshes[0].positions.resize(9);
    const absl::StatusOr<Scene> holed = LoadScene(testing::WriteGltf(scene, "holed.gltf"));
    ASSERT_TRUE(holed.ok()) << holed.status();
    EXPECT_TRUE(material_of(holed).SingleSided());
    // Glass must be crossed both ways: never culled.
    scene.materials[0].extensions = R"("KHR_materials_transmission":{"transmissionFactor":1})";
    const absl::StatusOr<Scene> glass = LoadScene(testing::WriteGltf(scene, "open-glass.gltf"));
    ASSERT_TRUE(glass.ok()) << glass.status();
    EXPECT_FALSE(material_of(glass).SingleSided());
}

// A skinned triangle: `joints` and `weights` accessors' component types and bytes.
struct SkinCase {
    int joint_type;
    std::string joints;
    int weight_type;
    bool normalized;
    std::string weights;
};

TEST(GltfLoaderTest, SkinsArePosedByTheirJointsDefaultTransforms) {
    // Joint 0 at (0, 0, 3); joint 1 its child, 2 along x and turned 90 degrees about z, bound
    // where it would stand at (1, 0, 0) (its inverse bind matrix moves by -1 along x).
    const std::vector<float> positions = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    const std::vector<float> normals = {1, 0, 0, 1, 0, 0, 1, 0, 0};
    const std::vector<float> inverse_bind = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0,  0, 0, 1,
                                             1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -1, 0, 0, 1};
    // Vertex 0 follows joint 1, vertex 1 both by (w, 1 - w), vertex 2 joint 0.
    const auto posed = [](double w) {
        // Joint 0: x -> x + (0, 0, 3). Joint 1: x -> (0, 0, 3) + (2, 0, 0) + Rz(x - (1, 0, 0)),
        // Rz(x, y, z) = (-y, x, z).
        const auto joint1 = [](Vec3d p) { return Vec3d(2 - p.y, p.x - 1, p.z + 3); };
        return std::array<Vec3d, 3>{
            joint1({1, 0, 0}), Vec3d(0, 1, 3) * w + joint1({0, 1, 0}) * (1 - w), Vec3d(0, 0, 4)};
    };
    const std::vector<uint8_t> joints8 = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0};
    const std::vector<uint16_t> joints16(joints8.begin(), joints8.end());
    const std::vector<float> weights_float = {1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 1, 0, 0, 0};
    const std::vector<uint8_t> weights8 = {255, 0, 0, 0, 128, 127, 0, 0, 255, 0, 0, 0};
    const std::vector<uint16_t> weights16 = {65535, 0, 0, 0, 30000, 35535, 0, 0, 65535, 0, 0, 0};
    for (const auto& [skin, w] :
         {std::pair{
              SkinCase{5121, testing::Bytes(joints8), 5126, false, testing::Bytes(weights_float)},
              0.5},
          std::pair{SkinCase{5123, testing::Bytes(joints16), 5121, true, testing::Bytes(weights8)},
                    128.0 / 255},
          std::pair{SkinCase{5121, testing::Bytes(joints8), 5123, true, testing::Bytes(weights16)},
                    30000.0 / 65535}}) {
        testing::TestScene scene = testing::LitQuadScene();
        scene.accessors = {
            {testing::Bytes(normals), R"("componentType":5126,"count":3,"type":"VEC3")"},
            {skin.joints,
             absl::StrCat(R"("componentType":)", skin.joint_type, R"(,"count":3,"type":"VEC4")")},
            {skin.weights, absl::StrCat(R"("componentType":)", skin.weight_type,
                                        skin.normalized ? R"(,"normalized":true)" : "",
                                        R"(,"count":3,"type":"VEC4")")},
            {testing::Bytes(inverse_bind), R"("componentType":5126,"count":2,"type":"MAT4")"}};
        scene.materials[0].extra = R"(,"doubleSided":true)";
        scene.meshes[0].positions = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
        scene.meshes[0].attributes_extra = R"(,"NORMAL":0,"JOINTS_0":1,"WEIGHTS_0":2)";
        // The skinned node's own transform is ignored, as the specification says.
        scene.meshes[0].node_extra = R"(,"skin":0,"translation":[100,100,100])";
        // Nodes: the two meshes', the camera's, then the joints (3, 4).
        scene.extra_nodes = {R"({"translation":[0,0,3],"children":[4]})",
                             R"({"translation":[2,0,0],"rotation":[0,0,0.70710678,0.70710678]})"};
        scene.extra = R"(,"skins":[{"joints":[3,4],"inverseBindMatrices":3}])";
        const absl::StatusOr<Scene> loaded = LoadScene(testing::WriteGltf(scene, "skinned.gltf"));
        ASSERT_TRUE(loaded.ok()) << loaded.status();
        const std::array<Vec3d, 3> expected = posed(w);
        for (int v = 0; v < 3; ++v)
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(loaded->positions[v][c], expected[v][c], 1e-5) << v << " " << w;
        // Normals by the skin's inverse transpose: joint 1 turns (1, 0, 0) to (0, 1, 0); the
        // even blend of the two is a turn by 45 degrees.
        EXPECT_NEAR(loaded->normals[0].y, 1.0f, 1e-5f);
        EXPECT_NEAR(loaded->normals[2].x, 1.0f, 1e-5f);
        const double angle = std::atan2(1 - w, w);
        EXPECT_NEAR(loaded->normals[1].x, std::cos(angle), 1e-5);
        EXPECT_NEAR(loaded->normals[1].y, std::sin(angle), 1e-5);
    }
}

TEST(GltfLoaderTest, MorphTargetsTakeTheirDefaultWeights) {
    const std::vector<float> delta = {0, 0, 2, 0, 0, 0, 0, 0, -4};
    testing::TestScene scene = testing::LitQuadScene();
    scene.accessors = {{testing::Bytes(delta), R"("componentType":5126,"count":3,"type":"VEC3")"}};
    scene.materials[0].extra = R"(,"doubleSided":true)";
    scene.meshes[0].positions = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    scene.meshes[0].primitive_extra = R"(,"targets":[{"POSITION":0}])";
    scene.meshes[0].mesh_extra = R"(,"weights":[0.25])";
    const absl::StatusOr<Scene> mesh = LoadScene(testing::WriteGltf(scene, "morph.gltf"));
    ASSERT_TRUE(mesh.ok()) << mesh.status();
    EXPECT_NEAR(mesh->positions[0].z, 0.5f, 1e-6f);
    EXPECT_NEAR(mesh->positions[2].z, 0.0f, 1e-6f);
    // The node's weights stand for the mesh's.
    scene.meshes[0].node_extra = R"(,"weights":[0.5])";
    const absl::StatusOr<Scene> node = LoadScene(testing::WriteGltf(scene, "morph-node.gltf"));
    ASSERT_TRUE(node.ok()) << node.status();
    EXPECT_NEAR(node->positions[0].z, 1.0f, 1e-6f);
    EXPECT_NEAR(node->positions[2].z, -1.0f, 1e-6f);
}

TEST(GltfLoaderTest, TriangleStripsAndFansAreReadAsTriangles) {
    for (const int mode : {5, 6}) {
        testing::TestScene scene = testing::LitQuadScene();
        scene.materials[0].extra = R"(,"doubleSided":true)";
        // A strip of the unit square's corners zig-zagging, a fan around its first corner: two
        // triangles facing +z either way.
        scene.meshes[0].positions =
            mode == 5 ? std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}
                      : std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
        scene.meshes[0].primitive_extra = absl::StrCat(R"(,"mode":)", mode);
        const absl::StatusOr<Scene> loaded =
            LoadScene(testing::WriteGltf(scene, absl::StrCat("mode-", mode, ".gltf")));
        ASSERT_TRUE(loaded.ok()) << loaded.status();
        float area = 0;
        int floor = 0;
        for (uint32_t t = 0; t < loaded->triangles.size(); ++t) {
            if (loaded->materials[loaded->triangles[t].material].IsEmissive()) continue;
            ++floor;
            area += loaded->TriangleArea(t);
            EXPECT_NEAR(loaded->triangles[t].normal.z, 1.0f, 1e-6f) << mode;
        }
        EXPECT_EQ(floor, 2) << mode;
        EXPECT_NEAR(area, 1.0f, 1e-6f) << mode;
    }
}

TEST(GltfLoaderTest, GpuInstancesPlaceTheMeshAsInstances) {
    const std::vector<float> translations = {0, 0, 0, 3, 0, 0, 0, 0, -5};
    testing::TestScene scene = testing::LitQuadScene();
    scene.accessors = {
        {testing::Bytes(translations), R"("componentType":5126,"count":3,"type":"VEC3")"}};
    scene.meshes[0].node_extra =
        R"(,"extensions":{"EXT_mesh_gpu_instancing":{"attributes":{"TRANSLATION":0}}})";
    scene.extra = R"(,"extensionsUsed":["EXT_mesh_gpu_instancing"],)"
                  R"("extensionsRequired":["EXT_mesh_gpu_instancing"])";
    const absl::StatusOr<Scene> loaded = LoadScene(testing::WriteGltf(scene, "gpu-instances.gltf"));
    ASSERT_TRUE(loaded.ok()) << loaded.status();
    ASSERT_EQ(loaded->prototypes.size(), 1u);
    EXPECT_EQ(loaded->instances.size(), 3u);
    EXPECT_NEAR(loaded->bounds.upper.x, 4.0f, 1e-6f);
    EXPECT_NEAR(loaded->bounds.lower.z, -5.0f, 1e-6f);
}

}  // namespace
}  // namespace pf
