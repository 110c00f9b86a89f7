// The PLY reader on files written here in memory: every encoding and scalar type, lists of
// every count and item type, binary data that begins with a line feed or carriage return,
// polygons, skipped elements and properties (its refusals: ply_refusals_test.cpp).
#include "core/scene_io/ply/ply_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "tests/core/scene_io/ply_writer.h"

namespace pf {
namespace {

using testing::kPlyEncodings;
using testing::kPlyName;
using testing::PlyWriter;
using testing::PutAs;

// One triangle (0,0,0) (1,0,0) (0,1,0) then a quad spanning (0,0,2) to (1,1,2) in the given
// encoding, coordinates of type `coordinate`, a face list of `count` and `item` types.
std::string TriangleAndQuad(const std::string& encoding, const std::string& coordinate,
                            const std::string& count, const std::string& item) {
    PlyWriter ply(encoding);
    ply.Line("element vertex 7")
        .Line("property " + coordinate + " x")
        .Line("property " + coordinate + " y")
        .Line("property " + coordinate + " z")
        .Line("element face 2")
        .Line("property list " + count + " " + item + " vertex_indices")
        .EndHeader();
    const double vertices[7][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 2},
                                   {1, 0, 2}, {1, 1, 2}, {0, 1, 2}};
    for (const auto& v : vertices) {
        for (double c : v) PutAs(ply, coordinate, c);
        if (encoding == "ascii") ply.Line("");
    }
    const std::vector<std::vector<double>> faces = {{0, 1, 2}, {3, 4, 5, 6}};
    for (const auto& face : faces) {
        PutAs(ply, count, static_cast<double>(face.size()));
        for (double index : face) PutAs(ply, item, index);
        if (encoding == "ascii") ply.Line("");
    }
    return ply.bytes();
}

void ExpectTriangleAndQuad(const absl::StatusOr<TriangleMesh>& mesh, const std::string& what) {
    ASSERT_TRUE(mesh.ok()) << what << ": " << mesh.status();
    ASSERT_EQ(mesh->positions.size(), 7u) << what;
    EXPECT_EQ(mesh->positions[1], Vec3(1, 0, 0)) << what;
    EXPECT_EQ(mesh->positions[5], Vec3(1, 1, 2)) << what;
    // The quad as a fan from its first corner: (3,4,5) and (3,5,6).
    EXPECT_EQ(mesh->indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5, 3, 5, 6})) << what;
    EXPECT_TRUE(mesh->normals.empty() && mesh->uvs.empty()) << what;
}

void ReadsEveryEncodingAndScalarTypeName() {
    const char* const types[] = {"char",   "int8",    "uchar",  "uint8",  "short", "int16",
                                 "ushort", "uint16",  "int",    "int32",  "uint",  "uint32",
                                 "float",  "float32", "double", "float64"};
    for (const char* encoding : kPlyEncodings)
        for (const char* type : types) {
            const std::string what = std::string(encoding) + " " + type;
            ExpectTriangleAndQuad(
                ReadPly(TriangleAndQuad(encoding, type, "uchar", "int"), kPlyName, SceneLimits{}),
                what);
        }
}

void ReadsListsOfEveryCountAndItemType() {
    const char* const counts[] = {"uchar", "char", "ushort", "short",
                                  "uint",  "int",  "uint8",  "int32"};
    const char* const items[] = {"uint", "int",    "ushort", "short", "uchar",
                                 "char", "uint32", "float",  "double"};
    for (const char* encoding : kPlyEncodings)
        for (const char* count : counts)
            for (const char* item : items) {
                const std::string what = std::string(encoding) + " list " + count + " " + item;
                ExpectTriangleAndQuad(ReadPly(TriangleAndQuad(encoding, "float", count, item),
                                              kPlyName, SceneLimits{}),
                                      what);
            }
}

// The first vertex's x as a float whose first byte in little-endian order is `first_byte`.
float FloatStartingWith(unsigned char first_byte) {
    return std::bit_cast<float>(uint32_t{0x3f800000u} | first_byte);
}

void BinaryDataMayBeginWithALineFeedOrCarriageReturn() {
    // Assimp took a 0x0a right after end_header for part of the header's line end and aborted
    // the process; the data begins after exactly one terminator, LF or CRLF.
    for (const std::string terminator : {"\n", "\r\n", "\r"})
        for (const unsigned char first_byte : {0x0a, 0x0d}) {
            const float x = FloatStartingWith(first_byte);
            PlyWriter ply("binary_little_endian", terminator);
            ply.Line("comment first data byte follows end_header's line end")
                .PositionsAndAFace()
                .EndHeader()
                .Row<float>({x, 0, 0})
                .Row<float>({x + 1, 0, 0})
                .Row<float>({x, 1, 0})
                .Put<uint8_t>(3)
                .Row<int32_t>({0, 1, 2});
            ASSERT_EQ(static_cast<unsigned char>(
                          ply.bytes()[ply.bytes().rfind("end_header") + 10 + terminator.size()]),
                      first_byte);
            const absl::StatusOr<TriangleMesh> mesh = ReadPly(ply.bytes(), kPlyName, SceneLimits{});
            ASSERT_TRUE(mesh.ok()) << mesh.status();
            ASSERT_EQ(mesh->positions.size(), 3u);
            EXPECT_EQ(mesh->positions[0], Vec3(x, 0, 0));
            EXPECT_EQ(mesh->positions[2], Vec3(x, 1, 0));
            EXPECT_EQ(mesh->indices, (std::vector<uint32_t>{0, 1, 2}));
        }
    // Big-endian: the first byte is the first property's, here a uchar of 10 and of 13.
    for (const uint8_t first_byte : {uint8_t{10}, uint8_t{13}}) {
        PlyWriter ply("binary_big_endian", "\r\n");
        ply.Line("element vertex 3")
            .Line("property uchar x")
            .Line("property short y")
            .Line("property double z")
            .Line("element face 1")
            .Line("property list uchar uint vertex_indices")
            .EndHeader();
        ply.Put(first_byte).Put<int16_t>(-300).Put(0.25);
        ply.Put<uint8_t>(11).Put<int16_t>(-300).Put(0.25);
        ply.Put<uint8_t>(10).Put<int16_t>(-299).Put(0.25);
        ply.Put<uint8_t>(3).Row<uint32_t>({0, 1, 2});
        const absl::StatusOr<TriangleMesh> mesh = ReadPly(ply.bytes(), kPlyName, SceneLimits{});
        ASSERT_TRUE(mesh.ok()) << mesh.status();
        EXPECT_EQ(mesh->positions[0], Vec3(first_byte, -300, 0.25f));
        EXPECT_EQ(mesh->positions[2], Vec3(10, -299, 0.25f));
    }
}

void PolygonsAreFannedAndSmallFacesDropped() {
    for (const char* encoding : kPlyEncodings) {
        PlyWriter ply(encoding);
        ply.Line("element vertex 5")
            .FloatProperties({"x", "y", "z"})
            .Line("element face 4")
            .Line("property list uchar int vertex_indices")
            .EndHeader();
        // A regular pentagon of circumradius 1.
        for (int k = 0; k < 5; ++k)
            ply.Row<float>(
                {std::cos(2 * 3.14159265f * k / 5), std::sin(2 * 3.14159265f * k / 5), 0.0f});
        ply.Put<uint8_t>(5).Row<int32_t>({0, 1, 2, 3, 4});
        ply.Put<uint8_t>(2).Row<int32_t>({0, 1});  // a line: dropped
        ply.Put<uint8_t>(4).Row<int32_t>({4, 3, 2, 1});
        ply.Put<uint8_t>(1).Row<int32_t>({3});  // a point: dropped
        const absl::StatusOr<TriangleMesh> mesh = ReadPly(ply.bytes(), kPlyName, SceneLimits{});
        ASSERT_TRUE(mesh.ok()) << encoding << ": " << mesh.status();
        EXPECT_EQ(mesh->indices,
                  (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4, 4, 3, 2, 4, 2, 1}))
            << encoding;
        // The pentagon's triangles cover it: (5/2) sin(72°) of area.
        double area = 0;
        for (size_t t = 0; t < 9; t += 3) {
            const Vec3 a = mesh->positions[mesh->indices[t]],
                       b = mesh->positions[mesh->indices[t + 1]],
                       c = mesh->positions[mesh->indices[t + 2]];
            area += 0.5 * Length(Cross(b - a, c - a));
        }
        EXPECT_NEAR(area, 2.5 * std::sin(2 * 3.14159265358979 / 5), 1e-5) << encoding;
    }
}

void OtherElementsAndPropertiesAreSkipped() {
    for (const char* encoding : kPlyEncodings) {
        PlyWriter ply(encoding);
        ply.Line("comment elements before, between and after, with lists to walk")
            .Line("obj_info made by ply_reader_test")
            .Line("element material 2")
            .Line("property list int ushort names")
            .Line("property double shine")
            .Line("element vertex 3")
            .Line("property uchar red")
            .Line("property float x")
            .Line("property list uchar float weights")
            .Line("property float y")
            .Line("property double confidence")
            .Line("property float z")
            .Line("element edge 1")
            .Line("property int vertex1")
            .Line("property int vertex2")
            .Line("element face 1")
            .Line("property int face_indices")
            .Line("property list uchar float texcoord")
            .Line("property list uint uint vertex_indices")
            .Line("property ushort flags")
            .Line("element trailing 1")
            .Line("property list uchar uchar more")
            .EndHeader();
        ply.Put<int32_t>(3).Put<uint16_t>(1).Put<uint16_t>(2).Put<uint16_t>(3).Row({0.5});
        ply.Put<int32_t>(0).Row({0.25});
        for (int v = 0; v < 3; ++v) {
            ply.Put<uint8_t>(200).Put<float>(v == 1 ? 1.0f : 0.0f).Put<uint8_t>(2);
            ply.Put(7.5f).Put(-7.5f).Put<float>(v == 2 ? 1.0f : 0.0f).Put(0.9).Row({2.0f});
        }
        ply.Row<int32_t>({0, 1});
        ply.Put<int32_t>(17).Put<uint8_t>(6).Row<float>({0, 0, 1, 0, 0, 1});
        ply.Put<uint32_t>(3).Row<uint32_t>({2, 1, 0}).Row<uint16_t>({9});
        ply.Put<uint8_t>(2).Row<uint8_t>({1, 2});
        const absl::StatusOr<TriangleMesh> mesh = ReadPly(ply.bytes(), kPlyName, SceneLimits{});
        ASSERT_TRUE(mesh.ok()) << encoding << ": " << mesh.status();
        EXPECT_EQ(mesh->positions, (std::vector<Vec3>{{0, 0, 2}, {1, 0, 2}, {0, 1, 2}}))
            << encoding;
        EXPECT_EQ(mesh->indices, (std::vector<uint32_t>{2, 1, 0})) << encoding;
    }
}

void NormalsAndTextureCoordinatesUnderEveryName() {
    const std::pair<const char*, const char*> uv_names[] = {
        {"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}};
    for (const char* encoding : kPlyEncodings)
        for (const auto& [u, v] : uv_names) {
            PlyWriter ply(encoding);
            ply.Line("element vertex 3")
                .FloatProperties({"x", "y", "z", "nx", "ny", "nz", u, v})
                .Line("element face 1")
                .Line("property list uchar int vertex_index")
                .EndHeader();
            ply.Row<float>({0, 0, 0, 0, 0, 1, 0.25f, 0.5f});
            ply.Row<float>({1, 0, 0, 0, 0.6f, 0.8f, 0.75f, 0.5f});
            ply.Row<float>({0, 1, 0, 0, 0, -1, 0.25f, 1});
            ply.Put<uint8_t>(3).Row<int32_t>({0, 1, 2});
            const std::string what = std::string(encoding) + " " + u + "/" + v;
            const absl::StatusOr<TriangleMesh> mesh = ReadPly(ply.bytes(), kPlyName, SceneLimits{});
            ASSERT_TRUE(mesh.ok()) << what << ": " << mesh.status();
            ASSERT_EQ(mesh->normals.size(), 3u) << what;
            ASSERT_EQ(mesh->uvs.size(), 3u) << what;
            EXPECT_EQ(mesh->normals[1], Vec3(0, 0.6f, 0.8f)) << what;
            EXPECT_EQ(mesh->uvs[1].x, 0.75f) << what;
            EXPECT_EQ(mesh->uvs[2].y, 1.0f) << what;
        }
    // Only part of a normal or of a pair: neither is read.
    PlyWriter ply("ascii");
    ply.Line("element vertex 3")
        .FloatProperties({"x", "y", "z", "nx", "ny", "u", "t"})
        .Line("element face 1")
        .Line("property list uchar int vertex_indices")
        .EndHeader()
        .Row<float>({0, 0, 0, 1, 0, 0.5f, 0.5f})
        .Row<float>({1, 0, 0, 1, 0, 0.5f, 0.5f})
        .Row<float>({0, 1, 0, 1, 0, 0.5f, 0.5f})
        .Row<int>({3, 0, 1, 2});
    const absl::StatusOr<TriangleMesh> mesh = ReadPly(ply.bytes(), kPlyName, SceneLimits{});
    ASSERT_TRUE(mesh.ok()) << mesh.status();
    EXPECT_TRUE(mesh->normals.empty());
    EXPECT_TRUE(mesh->uvs.empty());
}

// Four test cases of several checks each: CTest runs every case as its own process.
TEST(PlyReaderTest, ReadsEveryEncodingScalarTypeListAndPolygon) {
    ReadsEveryEncodingAndScalarTypeName();
    ReadsListsOfEveryCountAndItemType();
    PolygonsAreFannedAndSmallFacesDropped();
}

TEST(PlyReaderTest, ReadsBinaryDataBeginningWithALineFeedOrCarriageReturn) {
    BinaryDataMayBeginWithALineFeedOrCarriageReturn();
}

TEST(PlyReaderTest, SkipsWhatItDoesNotReadAndFindsNormalsAndUvsByEveryName) {
    OtherElementsAndPropertiesAreSkipped();
    NormalsAndTextureCoordinatesUnderEveryName();
}

}  // namespace
}  // namespace pf
