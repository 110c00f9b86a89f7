// The header of a PLY file (Turk's polygon file format, 1994): how its data is encoded and the
// elements and properties it declares, parsed from memory. ply_reader.cpp reads the data.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "absl/status/statusor.h"

namespace pf {

enum class PlyEncoding { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

// The format's scalar types, each known by two names: char/int8, uchar/uint8, short/int16,
// ushort/uint16, int/int32, uint/uint32, float/float32, double/float64.
enum class PlyScalar : uint8_t {
    kInt8,
    kUint8,
    kInt16,
    kUint16,
    kInt32,
    kUint32,
    kFloat32,
    kFloat64
};

// Bytes a scalar of `type` takes in binary data.
constexpr size_t PlyScalarSize(PlyScalar type) {
    switch (type) {
        case PlyScalar::kInt8:
        case PlyScalar::kUint8:
            return 1;
        case PlyScalar::kInt16:
        case PlyScalar::kUint16:
            return 2;
        case PlyScalar::kInt32:
        case PlyScalar::kUint32:
        case PlyScalar::kFloat32:
            return 4;
        case PlyScalar::kFloat64:
            return 8;
    }
    return 1;
}

struct PlyProperty {
    std::string name;
    PlyScalar type = PlyScalar::kFloat32;  // the value, or a list's items
    bool is_list = false;
    PlyScalar count_type = PlyScalar::kUint8;  // a list's length (an integer type)
};

struct PlyElement {
    std::string name;
    uint64_t count = 0;  // instances in the data
    std::vector<PlyProperty> properties;
    int line = 0;  // of its header line, for messages

    // The index of the property called `property`, or -1.
    int Find(std::string_view property) const;
    // Bytes one instance takes in binary data at least (every list empty); exactly, when it has
    // no list.
    uint64_t MinBinarySize() const;
    bool HasList() const;
};

struct PlyHeader {
    PlyEncoding encoding = PlyEncoding::kAscii;
    std::vector<PlyElement> elements;  // in the order of the data
    size_t data_offset = 0;            // where the data begins in the file
    int lines = 0;                     // the header's, so that ASCII data's lines follow on
};

// The header of PLY file `bytes`: the line "ply", a "format" line (ascii, binary_little_endian
// or binary_big_endian, version 1.0), "element" and "property" lines, and "end_header"; other
// lines ("comment", "obj_info", and the bare "Created by" line of Blender 2.4) are passed over.
// Lines end in LF or CRLF (or a lone CR where the first line does); the data begins right after
// the one line terminator of end_header, whatever its first byte. Errors (INVALID_ARGUMENT) are
// one line naming `name` and the header line.
// `text` from a file as a message shows it: quoted, control and non-ASCII bytes escaped, cut
// after 64 bytes.
std::string PlyQuoted(std::string_view text);

absl::StatusOr<PlyHeader> ParsePlyHeader(std::string_view bytes, const std::string& name);

// Whether every element's instances fit in the `data_size` bytes after the header: each takes
// a least size (its scalars, or in ASCII a digit and a separator each), so that nothing need be
// allocated for data the file cannot hold. The error names `name` and the element.
absl::Status CheckPlyCounts(const PlyHeader& header, size_t data_size, const std::string& name);

}  // namespace pf
