// The PLY reader's refusals: malformed headers, counts beyond the data, truncation at every
// length, bad values, files that are not surfaces and the triangle limit, each in one line
// naming the file and where.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <string>

#include "core/scene_io/ply/ply_reader.h"
#include "tests/core/scene_io/ply_writer.h"

namespace pf {
namespace {

using testing::kPlyEncodings;
using testing::kPlyName;
using testing::PlyWriter;
using testing::Triangle;

void ExpectPlyRefused(const std::string& bytes, const std::string& fragment,
                      const SceneLimits& limits = SceneLimits{},
                      absl::StatusCode code = absl::StatusCode::kInvalidArgument) {
    const absl::StatusOr<TriangleMesh> mesh = ReadPly(bytes, kPlyName, limits);
    ASSERT_FALSE(mesh.ok()) << fragment;
    const std::string message(mesh.status().message());
    EXPECT_EQ(mesh.status().code(), code) << message;
    EXPECT_EQ(message.rfind(std::string(kPlyName) + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(fragment), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

void MalformedHeadersAreRefusedNamingTheLine() {
    ExpectPlyRefused("", "not a PLY file");
    ExpectPlyRefused("solid cube\nendsolid\n", "not a PLY file");
    ExpectPlyRefused(std::string("\x1f\x8b\x08\x00", 4), "gzip-compressed but not named .gz");
    ExpectPlyRefused("ply\nformat nonsense 1.0\nend_header\n",
                     "header line 2: unknown format \"nonsense\"");
    ExpectPlyRefused("ply\nformat ascii\nend_header\n", "header line 2: \"format\" needs");
    ExpectPlyRefused("ply\nformat ascii 2.0\nend_header\n", "version \"2.0\" is not 1.0");
    ExpectPlyRefused("ply\nformat ascii 1.0\nelement vertex 3\nproperty half x\n",
                     "header line 4: unknown type \"half\"");
    ExpectPlyRefused(
        "ply\nformat ascii 1.0\nelement face 1\nproperty list float int i\nend_header\n",
        "header line 4: a list's count type must be an integer");
    ExpectPlyRefused("ply\nformat ascii 1.0\nproperty float x\nend_header\n",
                     "header line 3: \"property\" before any \"element\"");
    ExpectPlyRefused("ply\nformat ascii 1.0\nelement vertex -1\nend_header\n",
                     "header line 3: element \"vertex\" has count \"-1\"");
    ExpectPlyRefused("ply\nformat ascii 1.0\nelement vertex 18446744073709551616\nend_header\n",
                     "not a whole number below 2^64");
    ExpectPlyRefused("ply\nformat ascii 1.0\nelement vertex 0\nelement vertex 0\nend_header\n",
                     "a second element \"vertex\"");
    ExpectPlyRefused("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n",
                     "no end_header line");
    ExpectPlyRefused("ply\nelement vertex 0\nend_header\n", "end_header before any \"format\"");
}

void CountsBeyondTheDataAreRefusedBeforeAnythingIsAllocated() {
    // Four billion vertices of 12 bytes declared in a file of a few dozen: refused from the
    // header, so no array is sized by the count.
    for (const char* encoding : kPlyEncodings)
        ExpectPlyRefused(
            PlyWriter(encoding)
                .PositionsAndAFace("4000000000")
                .EndHeader()
                .Row<float>({0, 0, 0})
                .bytes(),
            "element \"vertex\" (header line 3) declares 4000000000 instances, more than "
            "the");
    // A list whose length runs past the data: refused when it is met.
    ExpectPlyRefused(Triangle().Put<uint8_t>(255).Row<int32_t>({0, 1, 2}).bytes(),
                     "face 0 of 1, property \"vertex_indices\": the data ends early");
    ExpectPlyRefused(Triangle("binary_big_endian", "uint")
                         .Put<uint32_t>(0xffffffffu)
                         .Row<int32_t>({0, 1, 2})
                         .bytes(),
                     "face 0 of 1, property \"vertex_indices\": the data ends early");
    // A skipped element's list likewise.
    ExpectPlyRefused(PlyWriter("binary_little_endian")
                         .Line("element extra 1")
                         .Line("property list int double values")
                         .PositionsAndAFace()
                         .EndHeader()
                         .Put<int32_t>(1 << 30)
                         .Row<float>({0, 0, 0, 1, 0, 0, 0, 1, 0})
                         .Put<uint8_t>(3)
                         .Row<int32_t>({0, 1, 2})
                         .bytes(),
                     "\"extra\" 0 of 1, property \"values\": the data ends early");
    ExpectPlyRefused(Triangle("ascii").Row<int>({1000, 0, 1, 2}).bytes(),
                     "line 13, face 0 of 1, property \"vertex_indices\": the data ends early");
}

void TruncatedDataIsRefusedAtEveryLength() {
    for (const char* encoding : {"ascii", "binary_little_endian"}) {
        const std::string whole =
            Triangle(encoding).Put<uint8_t>(3).Row<int32_t>({0, 1, 2}).bytes();
        ASSERT_TRUE(ReadPly(whole, kPlyName, SceneLimits{}).ok()) << encoding;
        // Every shorter prefix is refused naming the file (ASCII data still parses without
        // the separator and line end after its last number).
        const size_t last_number =
            std::string(encoding) == "ascii" ? whole.size() - 2 : whole.size();
        for (size_t size = 0; size < last_number; ++size) {
            const absl::StatusOr<TriangleMesh> mesh =
                ReadPly(whole.substr(0, size), kPlyName, SceneLimits{});
            ASSERT_FALSE(mesh.ok()) << encoding << " " << size;
            EXPECT_EQ(mesh.status().message().rfind(std::string(kPlyName) + ": ", 0), 0u)
                << mesh.status();
        }
    }
    ExpectPlyRefused(Triangle().Put<uint8_t>(3).Row<int32_t>({0, 1}).bytes(),
                     "face 0 of 1, property \"vertex_indices\": the data ends early");
}

void BadValuesAreRefusedNamingWhere() {
    ExpectPlyRefused(Triangle().Put<uint8_t>(3).Row<int32_t>({0, 3, 1}).bytes(),
                     "face 0 of 1, property \"vertex_indices\": vertex index 3 is not one of the 3 "
                     "vertices");
    ExpectPlyRefused(Triangle().Put<uint8_t>(3).Row<int32_t>({0, -1, 1}).bytes(),
                     "vertex index -1 is not one of the 3 vertices");
    ExpectPlyRefused(Triangle("ascii").Row<double>({3, 0, 1.5, 2}).bytes(),
                     "line 13, face 0 of 1, property \"vertex_indices\": vertex index 1.5");
    ExpectPlyRefused(Triangle("ascii").Line("3 0 one 2").bytes(),
                     "line 13, face 0 of 1, property \"vertex_indices\": \"one\" is not a number");
    ExpectPlyRefused(Triangle("ascii").Line("-3 0 1 2").bytes(), "list length -3 is not a count");
    // Text from the file is shown escaped (no terminal control codes in a message) and cut.
    ExpectPlyRefused(Triangle("ascii").Line("3 0 \x1b[31m 2").bytes(),
                     "\"\\x1b[31m\" is not a number");
    ExpectPlyRefused("ply\nformat " + std::string(100, 'a') + " 1.0\nend_header\n",
                     "unknown format \"" + std::string(64, 'a') + "...\"");
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    for (const float bad : {nan, inf, -inf}) {
        PlyWriter ply("binary_big_endian");
        ply.Line("element vertex 3")
            .FloatProperties({"x", "y", "z"})
            .Line("element face 1")
            .Line("property list uchar int vertex_indices")
            .EndHeader()
            .Row<float>({0, 0, 0, 1, bad, 0, 0, 1, 0})
            .Put<uint8_t>(3)
            .Row<int32_t>({0, 1, 2});
        ExpectPlyRefused(ply.bytes(), "vertex 1 of 3: its position");
    }
    // Beyond a float's range becomes infinite: refused too.
    ExpectPlyRefused(PlyWriter("ascii")
                         .Line("element vertex 3")
                         .Line("property double x")
                         .Line("property double y")
                         .Line("property double z")
                         .Line("element face 1")
                         .Line("property list uchar int vertex_indices")
                         .EndHeader()
                         .Line("0 0 0")
                         .Line("1 0 0")
                         .Line("0 1e300 0")
                         .Line("3 0 1 2")
                         .bytes(),
                     "line 12, vertex 2 of 3: its position (0, 1e+300, 0) is not finite");
    ExpectPlyRefused(std::string(Triangle("ascii").bytes())
                         .replace(Triangle("ascii").bytes().find("1.000000"), 8, "nan"),
                     "line 11, vertex 1 of 3: its position (nan, 0, 0) is not finite");
}

void FilesThatAreNotSurfacesAreRefused() {
    ExpectPlyRefused(PlyWriter("ascii")
                         .Line("element vertex 2")
                         .FloatProperties({"x", "y", "z"})
                         .EndHeader()
                         .Line("0 0 0")
                         .Line("1 0 0")
                         .bytes(),
                     "PLY file has no faces (a point cloud is not a surface)");
    // Indices listed in the vertices themselves (a malformed file) are not faces either.
    ExpectPlyRefused(PlyWriter("ascii")
                         .Line("element vertex 3")
                         .FloatProperties({"x", "y", "z"})
                         .Line("property list uchar int vertex_indices")
                         .EndHeader()
                         .Line("0 0 0 3 0 1 2")
                         .Line("1 0 0 0")
                         .Line("0 1 0 0")
                         .bytes(),
                     "PLY file has no faces");
    ExpectPlyRefused(Triangle("ascii").Line("2 0 1").bytes(),
                     "no polygon of 3 or more vertices (1 faces of fewer");
    ExpectPlyRefused(PlyWriter("ascii")
                         .Line("element vertex 3")
                         .FloatProperties({"x", "y"})
                         .Line("element face 1")
                         .Line("property list uchar int vertex_indices")
                         .EndHeader()
                         .bytes(),
                     "element \"vertex\" has no scalar property \"z\"");
    ExpectPlyRefused(PlyWriter("ascii")
                         .Line("element vertex 3")
                         .FloatProperties({"x", "y", "z"})
                         .Line("element face 1")
                         .Line("property int vertex_indices")
                         .EndHeader()
                         .bytes(),
                     "element \"face\" (header line 7) has no list property \"vertex_indices\"");
    ExpectPlyRefused(PlyWriter("ascii")
                         .Line("element vertex 3")
                         .FloatProperties({"x", "y", "z"})
                         .Line("element tristrips 1")
                         .Line("property list int int vertex_indices")
                         .EndHeader()
                         .bytes(),
                     "element \"tristrips\" is not read");
    ExpectPlyRefused("ply\nformat ascii 1.0\nelement face 0\nend_header\n",
                     "has no \"vertex\" element");
}

void TheTriangleLimitHolds() {
    PlyWriter ply("binary_little_endian");
    ply.Line("element vertex 4")
        .FloatProperties({"x", "y", "z"})
        .Line("element face 2")
        .Line("property list uchar int vertex_indices")
        .EndHeader()
        .Row<float>({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0})
        .Put<uint8_t>(3)
        .Row<int32_t>({0, 1, 2})
        .Put<uint8_t>(4)
        .Row<int32_t>({0, 1, 2, 3});
    SceneLimits limits;
    limits.max_triangles = 3;
    const absl::StatusOr<TriangleMesh> mesh = ReadPly(ply.bytes(), kPlyName, limits);
    ASSERT_TRUE(mesh.ok()) << mesh.status();
    EXPECT_EQ(mesh->indices.size(), 9u);
    limits.max_triangles = 2;
    ExpectPlyRefused(ply.bytes(), "more triangles than the limit of 2 (passed at face 1 of 2)",
                     limits, absl::StatusCode::kResourceExhausted);
}

TEST(PlyReaderTest, RefusesBadInputInOneLineNamingTheFileAndWhere) {
    MalformedHeadersAreRefusedNamingTheLine();
    CountsBeyondTheDataAreRefusedBeforeAnythingIsAllocated();
    TruncatedDataIsRefusedAtEveryLength();
    BadValuesAreRefusedNamingWhere();
    FilesThatAreNotSurfacesAreRefused();
    TheTriangleLimitHolds();
}

}  // namespace
}  // namespace pf
