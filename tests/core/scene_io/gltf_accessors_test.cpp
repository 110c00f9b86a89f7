// glTF accessors as the specification defines them: KHR_mesh_quantization's integer
// attributes (normalised and not), sparse substitutions, texture coordinate sets other than 0,
// KHR_draco_mesh_compression streams; and hostile sparse data and streams refused.
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

#include "absl/strings/escaping.h"
#include "absl/strings/str_cat.h"
#include "core/scene_io/gltf/gltf_draco.h"
#include "core/scene_io/scene_loader.h"
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

// An emissive unit quad (two triangles, 2 m wide at z = 0) as a Draco stream, made with
// libdraco's encoder (positions and texture coordinates quantised to 14 bits); `corrupt`
// flips bytes in the stream's middle.
std::string DracoQuad(bool corrupt = false) {
    draco::TriangleSoupMeshBuilder builder;
    builder.Start(2);
    const int position =
        builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    const int uv = builder.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
    const float corners[4][3] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    const float uvs[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    const int faces[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (int f = 0; f < 2; ++f) {
        builder.SetAttributeValuesForFace(position, draco::FaceIndex(f), corners[faces[f][0]],
                                          corners[faces[f][1]], corners[faces[f][2]]);
        builder.SetAttributeValuesForFace(uv, draco::FaceIndex(f), uvs[faces[f][0]],
                                          uvs[faces[f][1]], uvs[faces[f][2]]);
    }
    const std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
    draco::Encoder encoder;
    encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 14);
    draco::EncoderBuffer stream;
    EXPECT_TRUE(encoder.EncodeMeshToBuffer(*mesh, &stream).ok());
    std::string bytes(stream.data(), stream.size());
    if (corrupt)
        for (size_t i = bytes.size() / 3; i < bytes.size() / 3 + 8; ++i) bytes[i] ^= 0x5a;
    const uint32_t position_id = mesh->attribute(position)->unique_id();
    const uint32_t uv_id = mesh->attribute(uv)->unique_id();
    return absl::StrCat(
        R"({"asset":{"version":"2.0"},"extensionsUsed":["KHR_draco_mesh_compression"],)",
        R"("extensionsRequired":["KHR_draco_mesh_compression"],)", R"("buffers":[{"byteLength":)",
        bytes.size(), R"(,"uri":"data:application/octet-stream;base64,)", absl::Base64Escape(bytes),
        R"("}],)", R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":)", bytes.size(),
        R"(}],)", R"("accessors":[{"componentType":5126,"count":4,"type":"VEC3","min":[-1,-1,0],)",
        R"("max":[1,1,0]},{"componentType":5126,"count":4,"type":"VEC2"},)",
        R"({"componentType":5125,"count":6,"type":"SCALAR"}],)",
        R"("materials":[{"emissiveFactor":[1,1,1]}],)",
        R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1},"indices":2,)",
        R"("material":0,"extensions":{"KHR_draco_mesh_compression":{"bufferView":0,)",
        R"("attributes":{"POSITION":)", position_id, R"(,"TEXCOORD_0":)", uv_id, R"(}}}}]}],)",
        R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]})");
}

TEST(GltfAccessorsTest, DracoStreamsDecode) {
    const absl::StatusOr<Scene> scene =
        LoadScene(testing::WriteTextFile(DracoQuad(), "draco-quad.gltf"));
    ASSERT_TRUE(scene.ok()) << scene.status();
    EXPECT_EQ(scene->triangles.size(), 2u);
    ASSERT_EQ(scene->positions.size(), scene->uvs.size());
    double area = 0;
    for (const Triangle& triangle : scene->triangles) {
        const Vec3 a = scene->positions[triangle.vertex[0]],
                   b = scene->positions[triangle.vertex[1]],
                   c = scene->positions[triangle.vertex[2]];
        area += 0.5 * Length(Cross(b - a, c - a));
    }
    EXPECT_NEAR(area, 4.0, 1e-3);  // the quad, to the 14-bit quantisation
    for (size_t v = 0; v < scene->positions.size(); ++v) {
        // Each corner's uv is its position mapped from [-1, 1] to [0, 1].
        EXPECT_NEAR(scene->uvs[v].x, (scene->positions[v].x + 1) / 2, 1e-3);
        EXPECT_NEAR(scene->uvs[v].y, (scene->positions[v].y + 1) / 2, 1e-3);
    }
    // The same as a .glb (the JSON chunk alone, the stream in a data URI).
    std::string json = DracoQuad();
    json.resize((json.size() + 3) / 4 * 4, ' ');
    std::string glb = "glTF";
    Put<uint32_t>(&glb, 4, 2);
    Put<uint32_t>(&glb, 8, static_cast<uint32_t>(20 + json.size()));
    Put<uint32_t>(&glb, 12, static_cast<uint32_t>(json.size()));
    glb += "JSON" + json;
    const absl::StatusOr<Scene> binary = LoadScene(testing::WriteTextFile(glb, "draco-quad.glb"));
    ASSERT_TRUE(binary.ok()) << binary.status();
    EXPECT_EQ(binary->triangles.size(), 2u);
    const absl::StatusOr<Scene> corrupt =
        LoadScene(testing::WriteTextFile(DracoQuad(true), "draco-corrupt.gltf"));
    if (!corrupt.ok()) {  // a flipped byte need not break the stream, but it must not crash
        EXPECT_NE(corrupt.status().message().find("KHR_draco_mesh_compression"), std::string::npos)
            << corrupt.status();
    }
}

TEST(GltfAccessorsTest, DracoStreamsDeclaringMoreThanTheyHoldAreRefusedBeforeDecoding) {
    // 43 bytes whose edgebreaker header declares 268 million faces: libdraco would spend
    // a minute and 3 GB on it (found by the draco fuzzer, kept as its seed).
    std::ifstream file(std::string(PF_SOURCE_DIR) +
                           "/tests/fuzz/corpus/draco/regression-oom-declared-vertices.drc",
                       std::ios::binary);
    const std::string stream((std::istreambuf_iterator<char>(file)),
                             std::istreambuf_iterator<char>());
    ASSERT_EQ(stream.size(), 43u);
    tinygltf::Model model;
    model.buffers.emplace_back().data.assign(stream.begin(), stream.end());
    tinygltf::BufferView& view = model.bufferViews.emplace_back();
    view.buffer = 0;
    view.byteLength = stream.size();
    const tinygltf::Value extension(tinygltf::Value::Object{
        {"bufferView", tinygltf::Value(0)},
        {"attributes",
         tinygltf::Value(tinygltf::Value::Object{{"POSITION", tinygltf::Value(0)}})}});
    const absl::StatusOr<TriangleMesh> mesh = DecodeDracoPrimitive(
        model, tinygltf::Primitive(), extension, "TEXCOORD_0", uint64_t{1} << 26);
    ASSERT_FALSE(mesh.ok());
    EXPECT_NE(mesh.status().message().find("268435414 triangles exceed the limit"),
              std::string::npos)
        << mesh.status();
    // Within the limit, 100000 faces in 42 bytes are still more than a stream could hold.
    const std::string within = stream.substr(0, 13) + "\xa0\x8d\x06" + stream.substr(17);
    model.buffers[0].data.assign(within.begin(), within.end());
    view.byteLength = within.size();
    const absl::StatusOr<TriangleMesh> dense = DecodeDracoPrimitive(
        model, tinygltf::Primitive(), extension, "TEXCOORD_0", uint64_t{1} << 26);
    ASSERT_FALSE(dense.ok());
    EXPECT_NE(dense.status().message().find("declares 100000 elements in 42 bytes"),
              std::string::npos)
        << dense.status();
}

}  // namespace
}  // namespace pf
