// PLY meshes read by our own parser (Assimp's importer, used before, aborted the process on
// binary data beginning with a line feed): the header (ply_header.h), then the vertex and face
// elements from ASCII or binary data, every other element skipped by its declared layout.
#include "core/scene_io/ply/ply_reader.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>

#include "absl/strings/str_cat.h"
#include "core/scene_io/ply/ply_header.h"

namespace pf {
namespace {

inline uint16_t ByteSwap(uint16_t bits) { return __builtin_bswap16(bits); }
inline uint32_t ByteSwap(uint32_t bits) { return __builtin_bswap32(bits); }
inline uint64_t ByteSwap(uint64_t bits) { return __builtin_bswap64(bits); }

// A scalar of type T at `bytes`, swapped from the other byte order where `swap`.
template <typename T, typename Bits>
T Load(const char* bytes, bool swap) {
    Bits bits;
    std::memcpy(&bits, bytes, sizeof bits);
    if constexpr (sizeof(Bits) > 1)
        if (swap) bits = ByteSwap(bits);
    return std::bit_cast<T>(bits);
}

// Binary data in the file's byte order, read at a cursor that never passes its end.
class BinaryData {
public:
    BinaryData(std::string_view data, bool big_endian)
        : cursor_(data.data()),
          end_(data.data() + data.size()),
          swap_(big_endian != (std::endian::native == std::endian::big)) {}

    bool Read(PlyScalar type, double* value) {
        const size_t size = PlyScalarSize(type);
        if (static_cast<size_t>(end_ - cursor_) < size) return false;
        switch (type) {
            case PlyScalar::kInt8:
                *value = Load<int8_t, uint8_t>(cursor_, swap_);
                break;
            case PlyScalar::kUint8:
                *value = Load<uint8_t, uint8_t>(cursor_, swap_);
                break;
            case PlyScalar::kInt16:
                *value = Load<int16_t, uint16_t>(cursor_, swap_);
                break;
            case PlyScalar::kUint16:
                *value = Load<uint16_t, uint16_t>(cursor_, swap_);
                break;
            case PlyScalar::kInt32:
                *value = Load<int32_t, uint32_t>(cursor_, swap_);
                break;
            case PlyScalar::kUint32:
                *value = Load<uint32_t, uint32_t>(cursor_, swap_);
                break;
            case PlyScalar::kFloat32:
                *value = Load<float, uint32_t>(cursor_, swap_);
                break;
            case PlyScalar::kFloat64:
                *value = Load<double, uint64_t>(cursor_, swap_);
                break;
        }
        cursor_ += size;
        return true;
    }
    // Passes over `count` scalars of `type`.
    bool Skip(uint64_t count, PlyScalar type) {
        if (count > static_cast<uint64_t>(end_ - cursor_) / PlyScalarSize(type)) return false;
        cursor_ += count * PlyScalarSize(type);
        return true;
    }
    // Passes over every instance of `element`, which has no list.
    bool SkipAll(const PlyElement& element) {
        const uint64_t size = element.MinBinarySize();
        if (size != 0 && element.count > static_cast<uint64_t>(end_ - cursor_) / size) return false;
        cursor_ += element.count * size;
        return true;
    }
    // Whether `count` scalars of `type` remain (checked before a list is read).
    bool Holds(uint64_t count, PlyScalar type) const {
        return count <= static_cast<uint64_t>(end_ - cursor_) / PlyScalarSize(type);
    }
    std::string Problem() const { return "the data ends early"; }
    std::string Line() const { return ""; }

private:
    const char* cursor_;
    const char* end_;
    bool swap_;
};

// ASCII data: numbers separated by white space, their lines counted for messages.
class AsciiData {
public:
    AsciiData(std::string_view data, int first_line)
        : cursor_(data.data()),
          end_(data.data() + data.size()),
          line_(first_line),
          token_line_(first_line) {}

    bool Read(PlyScalar, double* value) {
        std::string_view token;
        if (!Next(&token)) return false;
        const char* first = token.data() + (token[0] == '+' ? 1 : 0);
        const auto [end, problem] = std::from_chars(first, token.data() + token.size(), *value);
        if (problem == std::errc() && end == token.data() + token.size()) return true;
        problem_ = absl::StrCat(PlyQuoted(token), " is not a number");
        return false;
    }
    bool Skip(uint64_t count, PlyScalar) {
        std::string_view token;
        for (uint64_t i = 0; i < count; ++i)
            if (!Next(&token)) return false;
        return true;
    }
    bool SkipAll(const PlyElement& element) {
        return Skip(element.count * element.properties.size(), PlyScalar::kUint8);
    }
    bool Holds(uint64_t, PlyScalar) const { return true; }  // known only by reading
    std::string Problem() const { return problem_; }
    // The line of the number read last.
    std::string Line() const { return absl::StrCat("line ", token_line_, ", "); }

private:
    static bool IsSpace(char c) { return c == ' ' || (c >= '\t' && c <= '\r'); }
    bool Next(std::string_view* token) {
        for (; cursor_ < end_ && IsSpace(*cursor_); ++cursor_)
            if (*cursor_ == '\n' ||
                (*cursor_ == '\r' && (cursor_ + 1 == end_ || cursor_[1] != '\n')))
                ++line_;
        if (cursor_ == end_) {
            problem_ = "the data ends early";
            return false;
        }
        token_line_ = line_;
        const char* start = cursor_;
        while (cursor_ < end_ && !IsSpace(*cursor_)) ++cursor_;
        *token = std::string_view(start, static_cast<size_t>(cursor_ - start));
        return true;
    }

    const char* cursor_;
    const char* end_;
    int line_, token_line_;
    std::string problem_;
};

// Where each vertex property goes: position x y z, normal, uv; -1 for none.
enum VertexSlot { kX, kY, kZ, kNx, kNy, kNz, kU, kV, kSlots };

struct Layout {
    size_t vertex = 0, face = 0;        // element indices
    std::vector<int> vertex_slots;      // per vertex property
    bool normals = false, uvs = false;  // every vertex has them
    int indices = -1;                   // the face property listing its vertices
};

struct Context {
    const std::string& name;
    const SceneLimits& limits;
};

// An element as messages name it: vertex and face bare, any other quoted as PlyQuoted shows it.
std::string ElementNoun(const PlyElement& element) {
    return element.name == "vertex" || element.name == "face" ? element.name
                                                              : PlyQuoted(element.name);
}

template <class Data>
absl::Status DataError(const Context& context, const Data& data, const PlyElement& element,
                       uint64_t index, const PlyProperty& property, const std::string& what) {
    return absl::InvalidArgumentError(
        absl::StrCat(context.name, ": PLY ", data.Line(), ElementNoun(element), " ", index, " of ",
                     element.count, ", property ", PlyQuoted(property.name), ": ", what));
}

// A list's length: a whole number (which ASCII data may fail to give).
template <class Data>
absl::Status ReadLength(const Context& context, Data& data, const PlyElement& element,
                        uint64_t index, const PlyProperty& property, uint64_t* length) {
    double value = 0;
    if (!data.Read(property.count_type, &value))
        return DataError(context, data, element, index, property, data.Problem());
    if (!(value >= 0 && value <= 4294967295.0 && value == std::floor(value)))
        return DataError(context, data, element, index, property,
                         absl::StrCat("list length ", value, " is not a count"));
    *length = static_cast<uint64_t>(value);
    return absl::OkStatus();
}

template <class Data>
absl::Status SkipProperty(const Context& context, Data& data, const PlyElement& element,
                          uint64_t index, const PlyProperty& property) {
    uint64_t length = 1;
    if (property.is_list)
        if (absl::Status status = ReadLength(context, data, element, index, property, &length);
            !status.ok())
            return status;
    if (!data.Skip(length, property.type))
        return DataError(context, data, element, index, property, data.Problem());
    return absl::OkStatus();
}

template <class Data>
absl::Status SkipElement(const Context& context, Data& data, const PlyElement& element) {
    if (!element.HasList()) {
        if (data.SkipAll(element)) return absl::OkStatus();
        return absl::InvalidArgumentError(absl::StrCat(context.name, ": PLY element ",
                                                       PlyQuoted(element.name), " (", element.count,
                                                       " instances): ", data.Problem()));
    }
    for (uint64_t i = 0; i < element.count; ++i)
        for (const PlyProperty& property : element.properties)
            if (absl::Status status = SkipProperty(context, data, element, i, property);
                !status.ok())
                return status;
    return absl::OkStatus();
}

template <class Data>
absl::Status ReadVertices(const Context& context, const Layout& layout, const PlyElement& element,
                          Data& data, TriangleMesh* mesh) {
    mesh->positions.resize(element.count);
    if (layout.normals) mesh->normals.resize(element.count);
    if (layout.uvs) mesh->uvs.resize(element.count);
    double values[kSlots] = {};
    for (uint64_t i = 0; i < element.count; ++i) {
        for (size_t p = 0; p < element.properties.size(); ++p) {
            const PlyProperty& property = element.properties[p];
            if (property.is_list) {
                if (absl::Status status = SkipProperty(context, data, element, i, property);
                    !status.ok())
                    return status;
                continue;
            }
            double value = 0;
            if (!data.Read(property.type, &value))
                return DataError(context, data, element, i, property, data.Problem());
            if (layout.vertex_slots[p] >= 0) values[layout.vertex_slots[p]] = value;
        }
        const Vec3 position(static_cast<float>(values[kX]), static_cast<float>(values[kY]),
                            static_cast<float>(values[kZ]));
        if (!IsFinite(position))
            return absl::InvalidArgumentError(
                absl::StrCat(context.name, ": PLY ", data.Line(), "vertex ", i, " of ",
                             element.count, ": its position (", values[kX], ", ", values[kY], ", ",
                             values[kZ], ") is not finite"));
        mesh->positions[i] = position;
        if (layout.normals)
            mesh->normals[i] =
                Vec3(static_cast<float>(values[kNx]), static_cast<float>(values[kNy]),
                     static_cast<float>(values[kNz]));
        if (layout.uvs) {
            const Point2 uv{static_cast<float>(values[kU]), static_cast<float>(values[kV])};
            if (!std::isfinite(uv.x) || !std::isfinite(uv.y))
                return absl::InvalidArgumentError(
                    absl::StrCat(context.name, ": PLY ", data.Line(), "vertex ", i, " of ",
                                 element.count, ": its texture coordinates (", values[kU], ", ",
                                 values[kV], ") are not finite"));
            mesh->uvs[i] = uv;
        }
    }
    return absl::OkStatus();
}

// Polygons of 3 or more vertices become triangles by a fan from their first vertex (exact for
// convex polygons; a quad's two triangles are the ones pbrt-v4's ConvertToOnlyTriangles makes);
// faces of fewer are counted in `small_faces` and dropped.
template <class Data>
absl::Status ReadFaces(const Context& context, const Layout& layout, const PlyElement& element,
                       uint64_t vertex_count, Data& data, TriangleMesh* mesh,
                       uint64_t* small_faces) {
    mesh->indices.reserve(3 * std::min(element.count, context.limits.max_triangles));
    std::vector<uint32_t> polygon;
    uint64_t triangles = 0;
    for (uint64_t i = 0; i < element.count; ++i) {
        for (size_t p = 0; p < element.properties.size(); ++p) {
            const PlyProperty& property = element.properties[p];
            // Every other property is passed over: colours, flags, and pbrt-v4's per-face
            // "face_indices" (which its ptex textures read: photonfarm has none).
            if (static_cast<int>(p) != layout.indices) {
                if (absl::Status status = SkipProperty(context, data, element, i, property);
                    !status.ok())
                    return status;
                continue;
            }
            uint64_t length = 0;
            if (absl::Status status = ReadLength(context, data, element, i, property, &length);
                !status.ok())
                return status;
            if (!data.Holds(length, property.type))
                return DataError(context, data, element, i, property, data.Problem());
            if (length >= 3 && triangles + (length - 2) > context.limits.max_triangles)
                return absl::ResourceExhaustedError(
                    absl::StrCat(context.name, ": PLY mesh has more triangles than the limit of ",
                                 context.limits.max_triangles, " (passed at ", ElementNoun(element),
                                 " ", i, " of ", element.count, ")"));
            polygon.clear();
            for (uint64_t k = 0; k < length; ++k) {
                double value = 0;
                if (!data.Read(property.type, &value))
                    return DataError(context, data, element, i, property, data.Problem());
                if (!(value >= 0 && value < static_cast<double>(vertex_count) &&
                      value == std::floor(value)))
                    return DataError(context, data, element, i, property,
                                     absl::StrCat("vertex index ", value, " is not one of the ",
                                                  vertex_count, " vertices"));
                polygon.push_back(static_cast<uint32_t>(value));
            }
            if (length < 3) {
                ++*small_faces;
                continue;
            }
            triangles += length - 2;
            for (size_t k = 1; k + 1 < polygon.size(); ++k) {
                mesh->indices.push_back(polygon[0]);
                mesh->indices.push_back(polygon[k]);
                mesh->indices.push_back(polygon[k + 1]);
            }
        }
    }
    return absl::OkStatus();
}

template <class Data>
absl::StatusOr<TriangleMesh> ReadData(const Context& context, const PlyHeader& header,
                                      const Layout& layout, Data data) {
    TriangleMesh mesh;
    uint64_t small_faces = 0;
    // Elements after both the vertices and the faces are not read at all.
    const size_t last = std::max(layout.vertex, layout.face);
    for (size_t e = 0; e <= last; ++e) {
        const PlyElement& element = header.elements[e];
        absl::Status status =
            e == layout.vertex ? ReadVertices(context, layout, element, data, &mesh)
            : e == layout.face
                ? ReadFaces(context, layout, element, header.elements[layout.vertex].count, data,
                            &mesh, &small_faces)
                : SkipElement(context, data, element);
        if (!status.ok()) return status;
    }
    if (mesh.indices.empty())
        return absl::InvalidArgumentError(
            absl::StrCat(context.name, ": PLY file has no polygon of 3 or more vertices (",
                         small_faces, " faces of fewer: points and lines are not a surface)"));
    return mesh;
}

// Which element and property holds what; errors name what a mesh needs and the file lacks.
absl::StatusOr<Layout> FindLayout(const PlyHeader& header, const std::string& name) {
    Layout layout;
    const auto element_named = [&](std::string_view wanted) {
        for (size_t e = 0; e < header.elements.size(); ++e)
            if (header.elements[e].name == wanted) return static_cast<int>(e);
        return -1;
    };
    const int vertex = element_named("vertex"), face = element_named("face");
    if (vertex < 0)
        return absl::InvalidArgumentError(
            absl::StrCat(name, ": PLY file has no \"vertex\" element"));
    if (face < 0 || header.elements[face].count == 0) {
        for (const PlyElement& other : header.elements)  // e.g. "tristrips" (triangle strips)
            if (other.name != "face" && other.name != "vertex" &&
                (other.Find("vertex_indices") >= 0 || other.Find("vertex_index") >= 0))
                return absl::InvalidArgumentError(
                    absl::StrCat(name, ": PLY element ", PlyQuoted(other.name),
                                 " is not read (only \"face\" polygons are)"));
        return absl::InvalidArgumentError(
            absl::StrCat(name, ": PLY file has no faces (a point cloud is not a surface)"));
    }
    layout.vertex = static_cast<size_t>(vertex);
    layout.face = static_cast<size_t>(face);
    const PlyElement& vertices = header.elements[layout.vertex];
    if (vertices.count > UINT32_MAX)
        return absl::InvalidArgumentError(
            absl::StrCat(name, ": PLY file has ", vertices.count, " vertices, more than 2^32 - 1"));
    // A property counts where it is a scalar; pbrt-v4's names for texture coordinates, in its
    // order of preference.
    const auto scalar = [&](std::string_view property) {
        const int p = vertices.Find(property);
        return p >= 0 && !vertices.properties[p].is_list ? p : -1;
    };
    layout.vertex_slots.assign(vertices.properties.size(), -1);
    for (const auto& [slot, property] : {std::pair{kX, "x"}, {kY, "y"}, {kZ, "z"}}) {
        const int p = scalar(property);
        if (p < 0)
            return absl::InvalidArgumentError(absl::StrCat(
                name, ": PLY element \"vertex\" has no scalar property \"", property, "\""));
        layout.vertex_slots[p] = slot;
    }
    if (scalar("nx") >= 0 && scalar("ny") >= 0 && scalar("nz") >= 0) {
        layout.normals = true;
        layout.vertex_slots[scalar("nx")] = kNx;
        layout.vertex_slots[scalar("ny")] = kNy;
        layout.vertex_slots[scalar("nz")] = kNz;
    }
    for (const auto& [u, v] :
         {std::pair{"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}})
        if (scalar(u) >= 0 && scalar(v) >= 0) {
            layout.uvs = true;
            layout.vertex_slots[scalar(u)] = kU;
            layout.vertex_slots[scalar(v)] = kV;
            break;
        }
    const PlyElement& faces = header.elements[layout.face];
    layout.indices = faces.Find("vertex_indices");
    if (layout.indices < 0) layout.indices = faces.Find("vertex_index");
    if (layout.indices < 0 || !faces.properties[layout.indices].is_list)
        return absl::InvalidArgumentError(
            absl::StrCat(name, ": PLY element \"face\" (header line ", faces.line,
                         ") has no list property \"vertex_indices\" (or \"vertex_index\")"));
    return layout;
}

// Where ASCII data fails to parse, the likeliest cause is rows holding more or fewer values
// than the header declares (a few writers add colours they do not declare): said where the
// first row shows it.
std::string AsciiRowHint(const PlyHeader& header, std::string_view data) {
    const PlyElement* first = nullptr;
    for (const PlyElement& element : header.elements)
        if (element.count > 0) {
            first = &element;
            break;
        }
    if (first == nullptr || first->HasList()) return "";
    const size_t start = data.find_first_not_of(" \t\r\n");
    if (start == std::string_view::npos) return "";
    const std::string_view row = data.substr(start, data.find_first_of("\r\n", start) - start);
    size_t values = 0;
    for (size_t i = 0; i < row.size(); ++i)
        values +=
            row[i] != ' ' && row[i] != '\t' && (i == 0 || row[i - 1] == ' ' || row[i - 1] == '\t');
    if (values == first->properties.size()) return "";
    return absl::StrCat(" (the first data line has ", values, " values where element \"",
                        first->name, "\" declares ", first->properties.size(),
                        ": the header does not describe the data)");
}

}  // namespace

absl::StatusOr<TriangleMesh> ReadPly(std::string_view bytes, const std::string& name,
                                     const SceneLimits& limits) {
    absl::StatusOr<PlyHeader> header = ParsePlyHeader(bytes, name);
    if (!header.ok()) return header.status();
    absl::StatusOr<Layout> layout = FindLayout(*header, name);
    if (!layout.ok()) return layout.status();
    const std::string_view data = bytes.substr(header->data_offset);
    if (absl::Status counts = CheckPlyCounts(*header, data.size(), name); !counts.ok())
        return counts;
    const Context context{name, limits};
    if (header->encoding == PlyEncoding::kAscii) {
        absl::StatusOr<TriangleMesh> mesh =
            ReadData(context, *header, *layout, AsciiData(data, header->lines + 1));
        if (mesh.ok() || !absl::IsInvalidArgument(mesh.status())) return mesh;
        return absl::InvalidArgumentError(
            absl::StrCat(mesh.status().message(), AsciiRowHint(*header, data)));
    }
    return ReadData(context, *header, *layout,
                    BinaryData(data, header->encoding == PlyEncoding::kBinaryBigEndian));
}

}  // namespace pf
