// Draco-compressed glTF primitives.
#include "core/scene_io/gltf/gltf_draco.h"

#include <draco/compression/decode.h>

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string_view>
#include <vector>

#include "absl/strings/str_cat.h"
#include "core/scene_io/gltf/gltf_json.h"

namespace pf {
namespace {

// The stream's attribute `name` (its unique id in the extension's attributes) as
// `components` floats a point, unsigned integers mapped to [0, 1] where `normalized`; empty
// where the extension does not name it.
absl::StatusOr<std::vector<float>> Attribute(const draco::Mesh& mesh,
                                             const tinygltf::Value& attributes,
                                             const std::string& name, int components,
                                             bool normalized = false) {
    if (!attributes.Has(name)) return std::vector<float>{};
    const tinygltf::Value& id = attributes.Get(name);
    if (!id.IsInt() || id.GetNumberAsInt() < 0)
        return absl::InvalidArgumentError(
            absl::StrCat("KHR_draco_mesh_compression: attribute ", name, " is not an id"));
    const draco::PointAttribute* attribute =
        mesh.GetAttributeByUniqueId(static_cast<uint32_t>(id.GetNumberAsInt()));
    if (attribute == nullptr || attribute->num_components() != components)
        return absl::InvalidArgumentError(
            absl::StrCat("KHR_draco_mesh_compression: the stream has no ", name, " of ", components,
                         " components (id ", id.GetNumberAsInt(), ")"));
    switch (attribute->data_type()) {  // glTF's component types; a bool or a double is hostile
        case draco::DT_INT8:
        case draco::DT_UINT8:
        case draco::DT_INT16:
        case draco::DT_UINT16:
        case draco::DT_INT32:
        case draco::DT_UINT32:
        case draco::DT_FLOAT32:
            break;
        default:
            return absl::InvalidArgumentError(
                absl::StrCat("KHR_draco_mesh_compression: ", name, " has data type ",
                             int(attribute->data_type()), ", not one of glTF's component types"));
    }
    std::vector<float> values(size_t(mesh.num_points()) * components);
    for (draco::PointIndex p(0); p < mesh.num_points(); ++p)
        if (!attribute->ConvertValue<float>(attribute->mapped_index(p), components,
                                            &values[size_t(p.value()) * components]))
            return absl::InvalidArgumentError(absl::StrCat(
                "KHR_draco_mesh_compression: ", name, " of point ", p.value(), " is unreadable"));
    // As glTF normalises an unsigned accessor (ConvertValue gives the integers).
    const float scale = attribute->data_type() == draco::DT_UINT8    ? 1.0f / 255
                        : attribute->data_type() == draco::DT_UINT16 ? 1.0f / 65535
                                                                     : 1.0f;
    if (normalized && scale != 1.0f)
        for (float& value : values) value *= scale;
    return values;
}

// Reads a Draco stream's header fields in order (the bitstream specification's types), so
// that the counts a hostile stream declares can be refused before libdraco allocates for them.
class DracoReader {
public:
    explicit DracoReader(std::string_view bytes) : bytes_(bytes) {}
    bool Byte(uint32_t* value) {
        if (at_ >= bytes_.size()) return false;
        *value = static_cast<unsigned char>(bytes_[at_++]);
        return true;
    }
    bool Skip(size_t count) {
        if (count > bytes_.size() - at_) return false;
        at_ += count;
        return true;
    }
    bool Varint(uint64_t* value) {  // LEB128, at most 10 bytes
        *value = 0;
        for (int shift = 0; shift < 70; shift += 7) {
            uint32_t byte = 0;
            if (!Byte(&byte)) return false;
            *value |= uint64_t(byte & 0x7f) << shift;
            if ((byte & 0x80) == 0) return true;
        }
        return false;
    }
    // A metadata element and its sub-elements, `depth` deep at most.
    bool SkipMetadata(int depth) {
        uint64_t entries = 0, subs = 0;
        uint32_t size = 0;
        if (depth == 0 || !Varint(&entries)) return false;
        for (uint64_t e = 0; e < entries; ++e)
            for (int part = 0; part < 2; ++part)
                if (!Byte(&size) || !Skip(size)) return false;
        if (!Varint(&subs)) return false;
        for (uint64_t e = 0; e < subs; ++e)
            if (!Byte(&size) || !Skip(size) || !SkipMetadata(depth - 1)) return false;
        return true;
    }

private:
    std::string_view bytes_;
    size_t at_ = 0;
};

// The counts of faces and points (or vertices, symbols and split symbols) a mesh stream of
// bitstream version 2.2 declares, against the scene's limit and against what its bytes could
// hold: real streams spend well over a bit a face, so more than 1024 of either a byte is a
// hostile stream (libdraco would allocate for it first: gigabytes from 43 bytes).
absl::Status CheckDracoCounts(std::string_view stream, uint64_t max_triangles) {
    const auto refused = [](const std::string& what) {
        return absl::InvalidArgumentError(absl::StrCat("KHR_draco_mesh_compression: ", what));
    };
    DracoReader in(stream);
    uint32_t major = 0, minor = 0, type = 0, method = 0, flags_low = 0, flags_high = 0;
    if (stream.substr(0, 5) != "DRACO" || !in.Skip(5) || !in.Byte(&major) || !in.Byte(&minor) ||
        !in.Byte(&type) || !in.Byte(&method) || !in.Byte(&flags_low) || !in.Byte(&flags_high))
        return refused("the stream has no Draco header");
    if (major != 2 || minor != 2)
        return refused(absl::StrCat("bitstream version ", major, ".", minor,
                                    " is not read (glTF's Draco streams are 2.2)"));
    if (type != 1) return refused("the stream is not a triangle mesh");
    if ((flags_high & 0x80) != 0) {  // metadata: a count, ids, then elements
        uint64_t count = 0, id = 0;
        bool ok = in.Varint(&count) && count <= stream.size();
        for (uint64_t i = 0; ok && i < count; ++i) ok = in.Varint(&id) && in.SkipMetadata(32);
        if (!ok || !in.SkipMetadata(32)) return refused("the stream's metadata is malformed");
    }
    std::vector<uint64_t> counts(method == 0 ? 2 : 4);
    uint32_t traversal = 0, attribute_data = 0;
    bool ok = method == 0 || (method == 1 && in.Byte(&traversal));
    if (method > 1) return refused(absl::StrCat("encoder method ", method, " is unknown"));
    for (size_t i = 0; ok && i < counts.size(); ++i) {
        ok = in.Varint(&counts[i]);
        if (ok && method == 1 && i == 1) ok = in.Byte(&attribute_data);  // after num_faces
    }
    if (!ok) return refused("the stream's connectivity header is truncated");
    const uint64_t faces = counts[method == 0 ? 0 : 1];
    const uint64_t plausible = 1024 * uint64_t(stream.size());
    if (faces > max_triangles)
        return refused(absl::StrCat(faces, " triangles exceed the limit of ", max_triangles));
    for (const uint64_t count : counts)
        if (count > plausible || count > 3 * max_triangles)
            return refused(absl::StrCat("the stream declares ", count, " elements in ",
                                        stream.size(), " bytes"));
    return absl::OkStatus();
}

}  // namespace

absl::StatusOr<TriangleMesh> DecodeDracoPrimitive(const tinygltf::Model& model,
                                                  const tinygltf::Primitive& primitive,
                                                  const tinygltf::Value& extension,
                                                  const std::string& uv_attribute,
                                                  uint64_t max_triangles, VertexAttributes* extra) {
    const auto malformed = [](const std::string& what) {
        return absl::InvalidArgumentError(absl::StrCat("KHR_draco_mesh_compression: ", what));
    };
    if (!extension.IsObject() || !extension.Has("bufferView") ||
        !extension.Get("bufferView").IsInt() || !extension.Has("attributes") ||
        !extension.Get("attributes").IsObject())
        return malformed("needs a bufferView and attributes");
    const int view_index = extension.Get("bufferView").GetNumberAsInt();
    if (view_index < 0 || view_index >= static_cast<int>(model.bufferViews.size()))
        return malformed(absl::StrCat("buffer view #", view_index, " does not exist"));
    const tinygltf::BufferView& view = model.bufferViews[view_index];
    if (view.buffer < 0 || view.buffer >= static_cast<int>(model.buffers.size()) ||
        view.byteOffset > model.buffers[view.buffer].data.size() ||
        view.byteLength > model.buffers[view.buffer].data.size() - view.byteOffset)
        return malformed(absl::StrCat("buffer view #", view_index, " lies outside its buffer"));
    const std::string_view bytes(
        reinterpret_cast<const char*>(model.buffers[view.buffer].data.data() + view.byteOffset),
        view.byteLength);
    if (absl::Status status = CheckDracoCounts(bytes, max_triangles); !status.ok()) return status;
    draco::DecoderBuffer stream;
    stream.Init(bytes.data(), bytes.size());
    draco::Decoder decoder;
    draco::StatusOr<std::unique_ptr<draco::Mesh>> decoded = decoder.DecodeMeshFromBuffer(&stream);
    if (!decoded.ok())
        return malformed(
            absl::StrCat("the stream does not decode (", decoded.status().error_msg_string(), ")"));
    const draco::Mesh& mesh = *decoded.value();
    if (mesh.num_faces() > max_triangles)
        return malformed(
            absl::StrCat(mesh.num_faces(), " triangles exceed the limit of ", max_triangles));
    const tinygltf::Value& attributes = extension.Get("attributes");
    absl::StatusOr<std::vector<float>> positions = Attribute(mesh, attributes, "POSITION", 3);
    if (!positions.ok()) return positions.status();
    if (positions->empty()) return malformed("the stream has no POSITION");
    absl::StatusOr<std::vector<float>> normals = Attribute(mesh, attributes, "NORMAL", 3);
    if (!normals.ok()) return normals.status();
    absl::StatusOr<std::vector<float>> uvs = Attribute(mesh, attributes, uv_attribute, 2);
    if (!uvs.ok()) return uvs.status();
    if (extra != nullptr)
        for (const auto& [name, components] : extra->wanted) {
            const auto accessor = primitive.attributes.find(name);
            const bool normalized = accessor != primitive.attributes.end() &&
                                    accessor->second >= 0 &&
                                    accessor->second < static_cast<int>(model.accessors.size()) &&
                                    model.accessors[accessor->second].normalized;
            absl::StatusOr<std::vector<float>> values =
                Attribute(mesh, attributes, name, components, normalized);
            if (!values.ok()) return values.status();
            if (!values->empty()) extra->values[name] = std::move(*values);
        }
    TriangleMesh out;
    const size_t points = mesh.num_points();
    for (size_t p = 0; p < points; ++p) {
        const Vec3 position((*positions)[3 * p], (*positions)[3 * p + 1], (*positions)[3 * p + 2]);
        if (!IsFinite(position))
            return malformed(absl::StrCat("point ", p, " position has NaN or Inf"));
        out.positions.push_back(position);
        if (!normals->empty())
            out.normals.emplace_back((*normals)[3 * p], (*normals)[3 * p + 1],
                                     (*normals)[3 * p + 2]);
        if (!uvs->empty()) out.uvs.push_back({(*uvs)[2 * p], (*uvs)[2 * p + 1]});
    }
    out.indices.reserve(size_t(mesh.num_faces()) * 3);
    for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f)
        for (int corner = 0; corner < 3; ++corner) {
            const uint32_t index = mesh.face(f)[corner].value();
            if (index >= points)
                return malformed(absl::StrCat("triangle ", f.value(), " has an index beyond the ",
                                              points, " points"));
            out.indices.push_back(index);
        }
    return out;
}

std::string WithoutDracoIndices(const std::string& contents, bool binary) {
    constexpr const char* kExtension = "KHR_draco_mesh_compression";
    if (contents.find(kExtension) == std::string::npos) return contents;
    std::optional<GltfJson> json = ParseGltfJson(contents, binary);
    if (!json || !json->document.contains("meshes") || !json->document["meshes"].is_array())
        return contents;
    bool changed = false;
    for (nlohmann::json& mesh : json->document["meshes"]) {
        if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array())
            continue;
        for (nlohmann::json& primitive : mesh["primitives"])
            if (primitive.is_object() && primitive.contains("extensions") &&
                primitive["extensions"].is_object() &&
                primitive["extensions"].contains(kExtension) && primitive.contains("indices")) {
                primitive.erase("indices");
                changed = true;
            }
    }
    return changed ? SerializeGltfJson(*json, binary) : contents;
}

}  // namespace pf
