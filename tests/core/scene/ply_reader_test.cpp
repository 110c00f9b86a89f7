// The PLY reader on files written here in memory: every encoding and scalar type, lists of
// every count and item type, binary data that begins with a line feed or carriage return,
// polygons, skipped elements and properties, and every error, each naming the file.
#include "core/scene/ply_reader.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

namespace pf {
namespace {

constexpr const char* kName = "meshes/test.ply";

// A PLY file written value by value: a header of the given lines, then the data as ASCII text
// (one instance a row) or binary in either byte order.
class PlyWriter {
public:
    explicit PlyWriter(std::string format, std::string terminator = "\n")
        : format_(std::move(format)), terminator_(std::move(terminator)) {
        file_ = "ply" + terminator_ + "format " + format_ + " 1.0" + terminator_;
    }
    PlyWriter& Line(const std::string& line) {
        file_ += line + terminator_;
        return *this;
    }
    PlyWriter& EndHeader() { return Line("end_header"); }
    template <typename T>
    PlyWriter& Put(T value) {
        if (format_ == "ascii") {
            if constexpr (std::is_floating_point_v<T>)
                file_ += std::to_string(static_cast<double>(value)) + " ";
            else
                file_ += std::to_string(static_cast<int64_t>(value)) + " ";
            return *this;
        }
        char bytes[sizeof(T)];
        std::memcpy(bytes, &value, sizeof(T));
        if ((format_ == "binary_big_endian") != (std::endian::native == std::endian::big))
            for (size_t i = 0; i < sizeof(T) / 2; ++i)
                std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
        file_.append(bytes, sizeof(T));
        return *this;
    }
    template <typename T>
    PlyWriter& Row(std::initializer_list<T> values) {
        for (T value : values) Put(value);
        if (format_ == "ascii") file_ += "\n";
        return *this;
    }
    const std::string& bytes() const { return file_; }

private:
    std::string format_, terminator_, file_;
};

const char* const kEncodings[] = {"ascii", "binary_little_endian", "binary_big_endian"};

// Writes a value of the PLY type called `type` (either of its names).
void PutAs(PlyWriter& ply, const std::string& type, double value) {
    if (type == "char" || type == "int8")
        ply.Put(static_cast<int8_t>(value));
    else if (type == "uchar" || type == "uint8")
        ply.Put(static_cast<uint8_t>(value));
    else if (type == "short" || type == "int16")
        ply.Put(static_cast<int16_t>(value));
    else if (type == "ushort" || type == "uint16")
        ply.Put(static_cast<uint16_t>(value));
    else if (type == "int" || type == "int32")
        ply.Put(static_cast<int32_t>(value));
    else if (type == "uint" || type == "uint32")
        ply.Put(static_cast<uint32_t>(value));
    else if (type == "float" || type == "float32")
        ply.Put(static_cast<float>(value));
    else if (type == "double" || type == "float64")
        ply.Put(value);
    else
        ADD_FAILURE() << type;
}

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
    for (const char* encoding : kEncodings)
        for (const char* type : types) {
            const std::string what = std::string(encoding) + " " + type;
            ExpectTriangleAndQuad(
                ReadPly(TriangleAndQuad(encoding, type, "uchar", "int"), kName, SceneLimits{}),
                what);
        }
}

void ReadsListsOfEveryCountAndItemType() {
    const char* const counts[] = {"uchar", "char", "ushort", "short",
                                  "uint",  "int",  "uint8",  "int32"};
    const char* const items[] = {"uint", "int",    "ushort", "short", "uchar",
                                 "char", "uint32", "float",  "double"};
    for (const char* encoding : kEncodings)
        for (const char* count : counts)
            for (const char* item : items) {
                const std::string what = std::string(encoding) + " list " + count + " " + item;
                ExpectTriangleAndQuad(
                    ReadPly(TriangleAndQuad(encoding, "float", count, item), kName, SceneLimits{}),
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
                .Line("element vertex 3")
                .Line("property float x")
                .Line("property float y")
                .Line("property float z")
                .Line("element face 1")
                .Line("property list uchar int vertex_indices")
                .EndHeader()
                .Row<float>({x, 0, 0})
                .Row<float>({x + 1, 0, 0})
                .Row<float>({x, 1, 0})
                .Put<uint8_t>(3)
                .Row<int32_t>({0, 1, 2});
            ASSERT_EQ(static_cast<unsigned char>(
                          ply.bytes()[ply.bytes().rfind("end_header") + 10 + terminator.size()]),
                      first_byte);
            const absl::StatusOr<TriangleMesh> mesh = ReadPly(ply.bytes(), kName, SceneLimits{});
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
        const absl::StatusOr<TriangleMesh> mesh = ReadPly(ply.bytes(), kName, SceneLimits{});
        ASSERT_TRUE(mesh.ok()) << mesh.status();
        EXPECT_EQ(mesh->positions[0], Vec3(first_byte, -300, 0.25f));
        EXPECT_EQ(mesh->positions[2], Vec3(10, -299, 0.25f));
    }
}

void PolygonsAreFannedAndSmallFacesDropped() {
    for (const char* encoding : kEncodings) {
        PlyWriter ply(encoding);
        ply.Line("element vertex 5")
            .Line("property float x")
            .Line("property float y")
            .Line("property float z")
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
        const absl::StatusOr<TriangleMesh> mesh = ReadPly(ply.bytes(), kName, SceneLimits{});
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
    for (const char* encoding : kEncodings) {
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
        const absl::StatusOr<TriangleMesh> mesh = ReadPly(ply.bytes(), kName, SceneLimits{});
        ASSERT_TRUE(mesh.ok()) << encoding << ": " << mesh.status();
        EXPECT_EQ(mesh->positions, (std::vector<Vec3>{{0, 0, 2}, {1, 0, 2}, {0, 1, 2}}))
            << encoding;
        EXPECT_EQ(mesh->indices, (std::vector<uint32_t>{2, 1, 0})) << encoding;
    }
}

void NormalsAndTextureCoordinatesUnderEveryName() {
    const std::pair<const char*, const char*> uv_names[] = {
        {"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}};
    for (const char* encoding : kEncodings)
        for (const auto& [u, v] : uv_names) {
            PlyWriter ply(encoding);
            ply.Line("element vertex 3")
                .Line("property float x")
                .Line("property float y")
                .Line("property float z")
                .Line("property float nx")
                .Line("property float ny")
                .Line("property float nz")
                .Line(std::string("property float ") + u)
                .Line(std::string("property float ") + v)
                .Line("element face 1")
                .Line("property list uchar int vertex_index")
                .EndHeader();
            ply.Row<float>({0, 0, 0, 0, 0, 1, 0.25f, 0.5f});
            ply.Row<float>({1, 0, 0, 0, 0.6f, 0.8f, 0.75f, 0.5f});
            ply.Row<float>({0, 1, 0, 0, 0, -1, 0.25f, 1});
            ply.Put<uint8_t>(3).Row<int32_t>({0, 1, 2});
            const std::string what = std::string(encoding) + " " + u + "/" + v;
            const absl::StatusOr<TriangleMesh> mesh = ReadPly(ply.bytes(), kName, SceneLimits{});
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
        .Line("property float x")
        .Line("property float y")
        .Line("property float z")
        .Line("property float nx")
        .Line("property float ny")
        .Line("property float u")
        .Line("property float t")
        .Line("element face 1")
        .Line("property list uchar int vertex_indices")
        .EndHeader()
        .Row<float>({0, 0, 0, 1, 0, 0.5f, 0.5f})
        .Row<float>({1, 0, 0, 1, 0, 0.5f, 0.5f})
        .Row<float>({0, 1, 0, 1, 0, 0.5f, 0.5f})
        .Row<int>({3, 0, 1, 2});
    const absl::StatusOr<TriangleMesh> mesh = ReadPly(ply.bytes(), kName, SceneLimits{});
    ASSERT_TRUE(mesh.ok()) << mesh.status();
    EXPECT_TRUE(mesh->normals.empty());
    EXPECT_TRUE(mesh->uvs.empty());
}

// The binary triangle every error below is made from.
PlyWriter Triangle(const std::string& encoding = "binary_little_endian") {
    PlyWriter ply(encoding);
    ply.Line("element vertex 3")
        .Line("property float x")
        .Line("property float y")
        .Line("property float z")
        .Line("element face 1")
        .Line("property list uchar int vertex_indices")
        .EndHeader()
        .Row<float>({0, 0, 0})
        .Row<float>({1, 0, 0})
        .Row<float>({0, 1, 0});
    return ply;
}

void ExpectPlyRefused(const std::string& bytes, const std::string& fragment,
                      const SceneLimits& limits = SceneLimits{},
                      absl::StatusCode code = absl::StatusCode::kInvalidArgument) {
    const absl::StatusOr<TriangleMesh> mesh = ReadPly(bytes, kName, limits);
    ASSERT_FALSE(mesh.ok()) << fragment;
    const std::string message(mesh.status().message());
    EXPECT_EQ(mesh.status().code(), code) << message;
    EXPECT_EQ(message.rfind(std::string(kName) + ": ", 0), 0u) << message;
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
    for (const char* encoding : kEncodings)
        ExpectPlyRefused(
            PlyWriter(encoding)
                .Line("element vertex 4000000000")
                .Line("property float x")
                .Line("property float y")
                .Line("property float z")
                .Line("element face 1")
                .Line("property list uchar int vertex_indices")
                .EndHeader()
                .Row<float>({0, 0, 0})
                .bytes(),
            "element \"vertex\" (header line 3) declares 4000000000 instances, more than "
            "the");
    // A list whose length runs past the data: refused when it is met.
    ExpectPlyRefused(Triangle().Put<uint8_t>(255).Row<int32_t>({0, 1, 2}).bytes(),
                     "face 0 of 1, property \"vertex_indices\": the data ends early");
    ExpectPlyRefused(PlyWriter("binary_big_endian")
                         .Line("element vertex 3")
                         .Line("property float x")
                         .Line("property float y")
                         .Line("property float z")
                         .Line("element face 1")
                         .Line("property list uint int vertex_indices")
                         .EndHeader()
                         .Row<float>({0, 0, 0, 1, 0, 0, 0, 1, 0})
                         .Put<uint32_t>(0xffffffffu)
                         .Row<int32_t>({0, 1, 2})
                         .bytes(),
                     "face 0 of 1, property \"vertex_indices\": the data ends early");
    // A skipped element's list likewise.
    ExpectPlyRefused(PlyWriter("binary_little_endian")
                         .Line("element extra 1")
                         .Line("property list int double values")
                         .Line("element vertex 3")
                         .Line("property float x")
                         .Line("property float y")
                         .Line("property float z")
                         .Line("element face 1")
                         .Line("property list uchar int vertex_indices")
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
        ASSERT_TRUE(ReadPly(whole, kName, SceneLimits{}).ok()) << encoding;
        // Every shorter prefix is refused naming the file (ASCII data still parses without
        // the separator and line end after its last number).
        const size_t last_number =
            std::string(encoding) == "ascii" ? whole.size() - 2 : whole.size();
        for (size_t size = 0; size < last_number; ++size) {
            const absl::StatusOr<TriangleMesh> mesh =
                ReadPly(whole.substr(0, size), kName, SceneLimits{});
            ASSERT_FALSE(mesh.ok()) << encoding << " " << size;
            EXPECT_EQ(mesh.status().message().rfind(std::string(kName) + ": ", 0), 0u)
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
            .Line("property float x")
            .Line("property float y")
            .Line("property float z")
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
                         .Line("property float x")
                         .Line("property float y")
                         .Line("property float z")
                         .EndHeader()
                         .Line("0 0 0")
                         .Line("1 0 0")
                         .bytes(),
                     "PLY file has no faces (a point cloud is not a surface)");
    // Indices listed in the vertices themselves (a malformed file) are not faces either.
    ExpectPlyRefused(PlyWriter("ascii")
                         .Line("element vertex 3")
                         .Line("property float x")
                         .Line("property float y")
                         .Line("property float z")
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
                         .Line("property float x")
                         .Line("property float y")
                         .Line("element face 1")
                         .Line("property list uchar int vertex_indices")
                         .EndHeader()
                         .bytes(),
                     "element \"vertex\" has no scalar property \"z\"");
    ExpectPlyRefused(PlyWriter("ascii")
                         .Line("element vertex 3")
                         .Line("property float x")
                         .Line("property float y")
                         .Line("property float z")
                         .Line("element face 1")
                         .Line("property int vertex_indices")
                         .EndHeader()
                         .bytes(),
                     "element \"face\" (header line 7) has no list property \"vertex_indices\"");
    ExpectPlyRefused(PlyWriter("ascii")
                         .Line("element vertex 3")
                         .Line("property float x")
                         .Line("property float y")
                         .Line("property float z")
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
        .Line("property float x")
        .Line("property float y")
        .Line("property float z")
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
    const absl::StatusOr<TriangleMesh> mesh = ReadPly(ply.bytes(), kName, limits);
    ASSERT_TRUE(mesh.ok()) << mesh.status();
    EXPECT_EQ(mesh->indices.size(), 9u);
    limits.max_triangles = 2;
    ExpectPlyRefused(ply.bytes(), "more triangles than the limit of 2 (passed at face 1 of 2)",
                     limits, absl::StatusCode::kResourceExhausted);
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
