// PLY files written here in memory, value by value, for the PLY reader's tests.
#pragma once

#include <bit>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <string>
#include <type_traits>
#include <utility>

namespace pf::testing {

inline constexpr const char* kPlyName = "meshes/test.ply";

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
    // A "property float NAME" line for each name.
    PlyWriter& FloatProperties(std::initializer_list<std::string> names) {
        for (const std::string& name : names) Line("property float " + name);
        return *this;
    }
    // The header of `vertices` float positions and one face, a list of `count` counts.
    PlyWriter& PositionsAndAFace(const std::string& vertices = "3",
                                 const std::string& count = "uchar") {
        return Line("element vertex " + vertices)
            .FloatProperties({"x", "y", "z"})
            .Line("element face 1")
            .Line("property list " + count + " int vertex_indices");
    }
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

inline const char* const kPlyEncodings[] = {"ascii", "binary_little_endian", "binary_big_endian"};

// Writes a value of the PLY type called `type` (either of its names).
inline void PutAs(PlyWriter& ply, const std::string& type, double value) {
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

// A binary triangle (one face list of `count` counts; no face written): the refusal tests
// append the face they test.
inline PlyWriter Triangle(const std::string& encoding = "binary_little_endian",
                          const std::string& count = "uchar") {
    PlyWriter ply(encoding);
    ply.PositionsAndAFace("3", count)
        .EndHeader()
        .Row<float>({0, 0, 0})
        .Row<float>({1, 0, 0})
        .Row<float>({0, 1, 0});
    return ply;
}

}  // namespace pf::testing
