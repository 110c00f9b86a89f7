// glTF accessors as the specification defines them: KHR_mesh_quantization's integer
// attributes (normalised and not), sparse substitutions, texture coordinate sets other than 0;
// and hostile sparse data refused naming the accessor.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>

#include "absl/strings/escaping.h"
#include "absl/strings/str_cat.h"
#include "core/scene/scene_loader.h"
#include "tests/support/gltf_builder.h"

namespace pf {
namespace {

template <typename T>
void Put(std::string* bytes, size_t at, T value) {
    if (bytes->size() < at + sizeof value) bytes->resize(at + sizeof value, '\0');
    std::memcpy(bytes->data() + at, &value, sizeof value);
}

// One emissive triangle: SHORT positions (not normalised, scaled by the node to metres), a
// sparse substitution moving vertex 2 from (0, 100, 0) to (0, 200, 0), normalised UNSIGNED_BYTE
// texture coordinates in TEXCOORD_1, which the material's texture reads (texCoord 1).
// `sparse_index` replaces the substituted vertex's index; `tex_coord` the material's set.
std::string QuantizedTriangle(uint8_t sparse_index = 2, int tex_coord = 1) {
    std::string bytes;
    const int16_t positions[3][3] = {{0, 0, 0}, {100, 0, 0}, {0, 100, 0}};
    for (int v = 0; v < 3; ++v)
        for (int c = 0; c < 3; ++c) Put(&bytes, v * 8 + c * 2, positions[v][c]);  // stride 8
    const uint8_t uvs[3][2] = {{0, 0}, {255, 0}, {0, 255}};
    for (int v = 0; v < 3; ++v)
        for (int c = 0; c < 2; ++c) Put(&bytes, 24 + v * 4 + c, uvs[v][c]);  // stride 4
    Put(&bytes, 36, sparse_index);
    Put<int16_t>(&bytes, 40, 0), Put<int16_t>(&bytes, 42, 200), Put<int16_t>(&bytes, 44, 0);
    bytes.resize(48, '\0');
    return absl::StrCat(
        R"({"asset":{"version":"2.0"},"extensionsUsed":["KHR_mesh_quantization"],)",
        R"("extensionsRequired":["KHR_mesh_quantization"],)",
        R"("buffers":[{"byteLength":48,"uri":"data:application/octet-stream;base64,)",
        absl::Base64Escape(bytes), R"("}],)",
        R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":24,"byteStride":8},)",
        R"({"buffer":0,"byteOffset":24,"byteLength":12,"byteStride":4},)",
        R"({"buffer":0,"byteOffset":36,"byteLength":1},{"buffer":0,"byteOffset":40,"byteLength":6}],)",
        R"("accessors":[{"bufferView":0,"componentType":5122,"count":3,"type":"VEC3",)",
        R"("min":[0,0,0],"max":[100,200,0],"sparse":{"count":1,)",
        R"("indices":{"bufferView":2,"componentType":5121},"values":{"bufferView":3}}},)",
        R"({"bufferView":1,"componentType":5121,"normalized":true,"count":3,"type":"VEC2"}],)",
        R"("images":[{"uri":"data:image/png;base64,)",
        "iVBORw0KGgoAAAANSUhEUgAAAAIAAAABCAIAAAB7QOjdAAAAD0lEQVR4nGP4z8DQ0NAAAAkBAoCZxGkyAAAAAElFTk"
        "SuQmCC",
        R"("}],"textures":[{"source":0}],)",
        R"("materials":[{"emissiveFactor":[1,1,1],"pbrMetallicRoughness":{"baseColorTexture":)",
        R"({"index":0,"texCoord":)", tex_coord, R"(}}}],)",
        R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_1":1},"material":0}]}],)",
        R"("nodes":[{"mesh":0,"scale":[0.01,0.01,0.01]}],"scenes":[{"nodes":[0]}]})");
}

TEST(GltfAccessorsTest, QuantizedSparseAttributesAndASecondUvSet) {
    const absl::StatusOr<Scene> scene =
        LoadScene(testing::WriteTextFile(QuantizedTriangle(), "quantized.gltf"));
    ASSERT_TRUE(scene.ok()) << scene.status();
    ASSERT_EQ(scene->positions.size(), 3u);
    EXPECT_NEAR(scene->positions[1].x, 1.0f, 1e-6f);  // SHORT 100, not normalised, x 0.01
    EXPECT_NEAR(scene->positions[2].y, 2.0f, 1e-6f);  // the sparse substitution, 200 x 0.01
    ASSERT_EQ(scene->uvs.size(), 3u);
    EXPECT_EQ(scene->uvs[1].x, 1.0f);  // UNSIGNED_BYTE 255, normalised
    EXPECT_EQ(scene->uvs[2].y, 1.0f);
}

TEST(GltfAccessorsTest, BadSparseDataAndMissingUvSetsAreRefused) {
    auto error = [](const std::string& json, const std::string& name) {
        const absl::StatusOr<Scene> scene = LoadScene(testing::WriteTextFile(json, name));
        return scene.ok() ? std::string("loaded") : std::string(scene.status().message());
    };
    const std::string out_of_range = error(QuantizedTriangle(7), "sparse-out-of-range.gltf");
    EXPECT_NE(out_of_range.find("accessor #0: sparse index 7 is out of range or not ascending"),
              std::string::npos)
        << out_of_range;
    const std::string missing = error(QuantizedTriangle(2, 3), "missing-uv-set.gltf");
    EXPECT_NE(missing.find("its material's texture reads TEXCOORD_3, which the primitive does "
                           "not have"),
              std::string::npos)
        << missing;
}

}  // namespace
}  // namespace pf
