// EXT_meshopt_compression: streams encoded here with meshoptimizer's own encoders decode to
// the data they were made from, in .gltf and .glb files, packed with the files that hold
// them; malformed and hostile streams are refused with what is wrong.
#include "core/scene_io/gltf/gltf_meshopt.h"

#include <gtest/gtest.h>
#include <meshoptimizer.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "absl/strings/escaping.h"
#include "core/scene_io/scene_loader.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/test_env.h"

namespace pf {
namespace {

template <typename T>
std::string Bytes(const std::vector<T>& values) {
    return std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

std::string EncodeAttributes(const std::string& data, size_t stride) {
    const size_t count = data.size() / stride;
    std::string out(meshopt_encodeVertexBufferBound(count, stride), '\0');
    out.resize(meshopt_encodeVertexBuffer(reinterpret_cast<unsigned char*>(out.data()), out.size(),
                                          data.data(), count, stride));
    return out;
}

std::string EncodeTriangles(const std::vector<uint32_t>& indices, size_t vertices) {
    std::string out(meshopt_encodeIndexBufferBound(indices.size(), vertices), '\0');
    out.resize(meshopt_encodeIndexBuffer(reinterpret_cast<unsigned char*>(out.data()), out.size(),
                                         indices.data(), indices.size()));
    return out;
}

struct MeshoptFile {
    std::string main;     // the .gltf text or .glb bytes
    std::string streams;  // the compressed buffer, where it is a file of its own
};

// The lit quad with indices, every buffer view a meshopt stream (positions as ATTRIBUTES,
// indices as TRIANGLES) in one buffer, and a fallback buffer without data that the views
// stand for. In a .glb the streams are its binary chunk; in a .gltf, `external` puts them in
// quad.meshopt.bin beside it, else in a data URI.
MeshoptFile MeshoptLitQuad(bool glb, bool external) {
    nlohmann::json doc = nlohmann::json::parse(testing::GltfJson(testing::LitQuadScene()));
    std::string uri = doc["buffers"][0]["uri"].get<std::string>(), blob;
    EXPECT_TRUE(absl::Base64Unescape(uri.substr(uri.find(',') + 1), &blob));
    std::vector<std::string> modes(doc["bufferViews"].size(), "ATTRIBUTES");
    for (nlohmann::json& mesh : doc["meshes"]) {
        nlohmann::json& primitive = mesh["primitives"][0];
        const uint32_t count =
            doc["accessors"][primitive["attributes"]["POSITION"].get<int>()]["count"]
                .get<uint32_t>();
        std::vector<uint32_t> indices(count);
        for (uint32_t i = 0; i < count; ++i) indices[i] = i;
        doc["bufferViews"].push_back(
            {{"buffer", 0}, {"byteOffset", blob.size()}, {"byteLength", 4 * count}});
        blob += Bytes(indices);
        modes.push_back("TRIANGLES");
        doc["accessors"].push_back({{"bufferView", doc["bufferViews"].size() - 1},
                                    {"componentType", 5125},
                                    {"count", count},
                                    {"type", "SCALAR"}});
        primitive["indices"] = doc["accessors"].size() - 1;
    }
    const int fallback = glb ? 1 : 0, streams = glb ? 0 : 1;
    std::string compressed;
    for (size_t v = 0; v < doc["bufferViews"].size(); ++v) {
        nlohmann::json& view = doc["bufferViews"][v];
        const std::string data =
            blob.substr(view["byteOffset"].get<size_t>(), view["byteLength"].get<size_t>());
        const size_t stride = modes[v] == "TRIANGLES" ? 4 : 12;
        std::vector<uint32_t> indices(data.size() / 4);
        std::memcpy(indices.data(), data.data(), data.size());
        const std::string stream = modes[v] == "TRIANGLES"
                                       ? EncodeTriangles(indices, indices.size())
                                       : EncodeAttributes(data, stride);
        view["buffer"] = fallback;
        view["extensions"]["EXT_meshopt_compression"] = {{"buffer", streams},
                                                         {"byteOffset", compressed.size()},
                                                         {"byteLength", stream.size()},
                                                         {"byteStride", stride},
                                                         {"count", data.size() / stride},
                                                         {"mode", modes[v]}};
        compressed += stream;
        while (compressed.size() % 4) compressed.push_back('\0');
    }
    nlohmann::json buffers = nlohmann::json::array({nullptr, nullptr});
    buffers[fallback] = {{"byteLength", blob.size()},
                         {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}};
    buffers[streams] = {{"byteLength", compressed.size()}};
    if (!glb)
        buffers[streams]["uri"] =
            external ? "quad.meshopt.bin"
                     : "data:application/octet-stream;base64," + absl::Base64Escape(compressed);
    doc["buffers"] = buffers;
    doc["extensionsUsed"] = doc["extensionsRequired"] = {"EXT_meshopt_compression"};
    if (!glb) return {doc.dump(), external ? compressed : ""};
    std::string json = doc.dump();
    while (json.size() % 4) json.push_back(' ');
    const auto word = [](uint32_t value) {
        return std::string(reinterpret_cast<const char*>(&value), 4);
    };
    const std::string file =
        "glTF" + word(2) +
        word(static_cast<uint32_t>(12 + 8 + json.size() + 8 + compressed.size())) +
        word(static_cast<uint32_t>(json.size())) + "JSON" + json +
        word(static_cast<uint32_t>(compressed.size())) + std::string("BIN\0", 4) + compressed;
    return {file, ""};
}

// The corners of every triangle, in order.
std::vector<Vec3> Corners(const Scene& scene) {
    std::vector<Vec3> corners;
    for (const Triangle& triangle : scene.triangles)
        for (uint32_t vertex : triangle.vertex) corners.push_back(scene.positions[vertex]);
    return corners;
}

TEST(GltfMeshoptTest, CompressedFilesLoadAsTheirUncompressedForm) {
    const absl::StatusOr<Scene> plain =
        LoadScene(testing::WriteGltf(testing::LitQuadScene(), "meshopt-plain.gltf"));
    ASSERT_TRUE(plain.ok()) << plain.status();
    for (const bool glb : {false, true}) {
        const MeshoptFile file = MeshoptLitQuad(glb, false);
        const std::string path =
            testing::WriteTextFile(file.main, glb ? "meshopt-quad.glb" : "meshopt-quad.gltf");
        const absl::StatusOr<Scene> scene = LoadScene(path);
        ASSERT_TRUE(scene.ok()) << scene.status();
        EXPECT_EQ(Corners(*scene), Corners(*plain)) << (glb ? "glb" : "gltf");
    }
}

TEST(GltfMeshoptTest, PackingGathersTheFileThatHoldsTheStreams) {
    const std::filesystem::path folder = testing::ProcessTempDir() / "meshopt-scene";
    std::filesystem::create_directories(folder);
    const MeshoptFile file = MeshoptLitQuad(false, true);
    std::ofstream(folder / "quad.gltf", std::ios::binary) << file.main;
    std::ofstream(folder / "quad.meshopt.bin", std::ios::binary) << file.streams;
    const absl::StatusOr<SceneBundle> bundle = PackSceneBundle((folder / "quad.gltf").string());
    ASSERT_TRUE(bundle.ok()) << bundle.status();
    EXPECT_TRUE(bundle->files.contains("quad.meshopt.bin"));
    const absl::StatusOr<Scene> scene = LoadScene(*bundle, "quad.gltf");
    ASSERT_TRUE(scene.ok()) << scene.status();
    EXPECT_EQ(scene->triangles.size(), 4u);
}

TEST(GltfMeshoptTest, FiltersDecodeWhatTheirEncodersKept) {
    // Unit normals through OCTAHEDRAL (16-bit), and floats through EXPONENTIAL: within the
    // encodings' precision of the originals.
    std::vector<float> normals;
    for (int i = 0; i < 64; ++i) {
        const float z = -1 + 2 * (i + 0.5f) / 64, phi = 2.4f * i, r = std::sqrt(1 - z * z);
        normals.insert(normals.end(), {r * std::cos(phi), r * std::sin(phi), z, 0.0f});
    }
    std::vector<int16_t> octahedral(normals.size());
    meshopt_encodeFilterOct(octahedral.data(), 64, 8, 16, normals.data());
    absl::StatusOr<std::string> decoded = DecodeMeshoptStream(
        EncodeAttributes(Bytes(octahedral), 8), {64, 8, "ATTRIBUTES", "OCTAHEDRAL"});
    ASSERT_TRUE(decoded.ok()) << decoded.status();
    std::vector<int16_t> unit(4 * 64);
    std::memcpy(unit.data(), decoded->data(), decoded->size());
    for (size_t i = 0; i < unit.size(); ++i) {
        if (i % 4 == 3) continue;  // w, kept as it was
        EXPECT_NEAR(unit[i] / 32767.0, normals[i], 2e-3) << i;
    }
    std::vector<float> values;
    for (int i = 0; i < 32; ++i) values.push_back(std::ldexp(1.0f + i / 7.0f, i - 16));
    std::vector<uint32_t> exponential(values.size());
    meshopt_encodeFilterExp(exponential.data(), 32, 4, 24, values.data());
    decoded = DecodeMeshoptStream(EncodeAttributes(Bytes(exponential), 4),
                                  {32, 4, "ATTRIBUTES", "EXPONENTIAL"});
    ASSERT_TRUE(decoded.ok()) << decoded.status();
    std::vector<float> floats(32);
    std::memcpy(floats.data(), decoded->data(), decoded->size());
    for (int i = 0; i < 32; ++i) EXPECT_NEAR(floats[i], values[i], 1e-6 * values[i]) << i;
}

TEST(GltfMeshoptTest, MalformedAndHostileStreamsAreRefused) {
    const std::string stream = EncodeAttributes(std::string(48, '\1'), 12);
    const auto refused = [&](const std::string& bytes, const MeshoptStream& how,
                             const std::string& fragment) {
        const absl::StatusOr<std::string> decoded = DecodeMeshoptStream(bytes, how);
        ASSERT_FALSE(decoded.ok()) << fragment;
        EXPECT_NE(decoded.status().message().find(fragment), std::string::npos)
            << decoded.status().message();
    };
    refused(stream, {4, 12, "VERTICES"}, "mode \"VERTICES\" is unknown");
    refused(stream, {4, 10, "ATTRIBUTES"}, "byteStride 10 is not allowed");
    refused(stream, {4, 3, "TRIANGLES"}, "byteStride 3 is not allowed");
    refused(stream, {4, 4, "TRIANGLES"}, "no multiple of 3");
    refused(stream, {4, 12, "ATTRIBUTES", "OCTAHEDRAL"}, "OCTAHEDRAL needs byteStride 4 or 8");
    refused(stream, {4, 12, "ATTRIBUTES", "SWIRL"}, "filter \"SWIRL\" is unknown");
    refused(stream.substr(0, stream.size() / 2), {4, 12, "ATTRIBUTES"}, "malformed");
    // A count the stream could never hold is refused before anything is allocated.
    refused(stream, {uint64_t{1} << 40, 12, "ATTRIBUTES"}, "elements of 12 bytes");
    // In a file: the error names the buffer view.
    MeshoptFile file = MeshoptLitQuad(false, false);
    nlohmann::json doc = nlohmann::json::parse(file.main);
    doc["bufferViews"][1]["extensions"]["EXT_meshopt_compression"]["mode"] = "TRIANGLES";
    doc["bufferViews"][1]["extensions"]["EXT_meshopt_compression"]["byteStride"] = 7;
    const absl::StatusOr<Scene> scene =
        LoadScene(testing::WriteTextFile(doc.dump(), "meshopt-broken.gltf"));
    ASSERT_FALSE(scene.ok());
    EXPECT_NE(scene.status().message().find(
                  "meshopt-broken.gltf: bufferViews[1]: EXT_meshopt_compression: byteStride 7"),
              std::string::npos)
        << scene.status().message();
    // A view placed a terabyte into its fallback buffer is refused before the buffer grows.
    doc = nlohmann::json::parse(file.main);
    doc["bufferViews"][0]["byteOffset"] = uint64_t{1} << 40;
    const absl::StatusOr<Scene> far =
        LoadScene(testing::WriteTextFile(doc.dump(), "meshopt-far.gltf"));
    ASSERT_FALSE(far.ok());
    EXPECT_NE(far.status().message().find("is more than its streams could hold"), std::string::npos)
        << far.status().message();
}

}  // namespace
}  // namespace pf
