// Reading glTF accessors: bounds checked against their views and buffers, every number from
// the file distrusted.
#include "core/scene_io/gltf/gltf_accessors.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "absl/strings/str_cat.h"
#include "core/scene_io/gltf/gltf_draco.h"

namespace pf {
namespace {

// Whether `count` elements of `element_size` bytes, `stride` apart, starting `offset` bytes
// into buffer view `view`, lie inside it and the view inside its buffer; overflow-safe, since
// every number here comes from the file.
bool AccessorFits(const tinygltf::Model& model, const tinygltf::BufferView& view, size_t offset,
                  size_t count, size_t stride, size_t element_size) {
    if (view.buffer < 0 || view.buffer >= static_cast<int>(model.buffers.size())) return false;
    const size_t buffer_size = model.buffers[view.buffer].data.size();
    if (view.byteOffset > buffer_size || view.byteLength > buffer_size - view.byteOffset)
        return false;
    if (count == 0) return true;
    if (offset > view.byteLength || element_size > view.byteLength - offset || stride == 0)
        return false;
    return count - 1 <= (view.byteLength - offset - element_size) / stride;
}

// Where `count` elements of `components` components of `component_type`, `view_index`'s
// stride apart (tightly packed when `packed` or the view gives none), start in their buffer;
// null where they do not fit.
const unsigned char* Elements(const tinygltf::Model& model, int view_index, size_t offset,
                              size_t count, int component_type, int components, bool packed,
                              size_t* stride) {
    if (view_index < 0 || view_index >= static_cast<int>(model.bufferViews.size())) return nullptr;
    const tinygltf::BufferView& view = model.bufferViews[view_index];
    const int component_size = tinygltf::GetComponentSizeInBytes(component_type);
    if (component_size <= 0 || components <= 0) return nullptr;
    const size_t element_size = size_t(component_size) * size_t(components);
    *stride = !packed && view.byteStride != 0 ? view.byteStride : element_size;
    if (!AccessorFits(model, view, offset, count, *stride, element_size)) return nullptr;
    return model.buffers[view.buffer].data.data() + view.byteOffset + offset;
}

// One component as glTF defines its value: a float as it is; an integer normalised (unsigned
// to [0, 1], signed to [-1, 1]) where the accessor says so, else its value (KHR_mesh_quantization).
bool Component(int type, bool normalized, const unsigned char* p, float* value) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            std::memcpy(value, p, 4);
            return true;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            *value = normalized ? *p / 255.0f : float(*p);
            return true;
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            const auto v = static_cast<int8_t>(*p);
            *value = normalized ? std::max(v / 127.0f, -1.0f) : float(v);
            return true;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t v;
            std::memcpy(&v, p, 2);
            *value = normalized ? v / 65535.0f : float(v);
            return true;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            int16_t v;
            std::memcpy(&v, p, 2);
            *value = normalized ? std::max(v / 32767.0f, -1.0f) : float(v);
            return true;
        }
        default:
            return false;
    }
}

// An index of `type` (unsigned byte, short or int) at p.
bool Index(int type, const unsigned char* p, uint32_t* index) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            *index = *p;
            return true;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t v;
            std::memcpy(&v, p, 2);
            *index = v;
            return true;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            std::memcpy(index, p, 4);
            return true;
        default:
            return false;
    }
}

// Calls `replace(element, values)` for each of a sparse accessor's substitutions: the element
// it replaces (checked below `accessor.count`, ascending as the specification asks) and where
// its `components` values of the accessor's type lie.
template <typename Replace>
absl::Status ForEachSparseValue(const tinygltf::Model& model, const tinygltf::Accessor& accessor,
                                const std::string& name, int components, Replace replace) {
    const auto& sparse = accessor.sparse;
    if (sparse.count <= 0 || size_t(sparse.count) > accessor.count)
        return absl::InvalidArgumentError(
            absl::StrCat(name, ": sparse.count must lie in [1, count]"));
    size_t index_stride = 0, value_stride = 0;
    const unsigned char* indices =
        Elements(model, sparse.indices.bufferView, size_t(std::max(0, sparse.indices.byteOffset)),
                 size_t(sparse.count), sparse.indices.componentType, 1, true, &index_stride);
    const unsigned char* values =
        Elements(model, sparse.values.bufferView, size_t(std::max(0, sparse.values.byteOffset)),
                 size_t(sparse.count), accessor.componentType, components, true, &value_stride);
    if (indices == nullptr || values == nullptr || sparse.indices.byteOffset < 0 ||
        sparse.values.byteOffset < 0)
        return absl::InvalidArgumentError(
            absl::StrCat(name, ": its sparse indices or values lie outside their buffer"));
    int64_t previous = -1;
    for (size_t i = 0; i < size_t(sparse.count); ++i) {
        uint32_t element = 0;
        if (!Index(sparse.indices.componentType, indices + i * index_stride, &element))
            return absl::InvalidArgumentError(
                absl::StrCat(name, ": sparse indices must be unsigned integers"));
        if (element >= accessor.count || int64_t(element) <= previous)
            return absl::InvalidArgumentError(absl::StrCat(name, ": sparse index ", element,
                                                           " is out of range or not ascending"));
        previous = element;
        if (absl::Status status = replace(element, values + i * value_stride); !status.ok())
            return status;
    }
    return absl::OkStatus();
}

}  // namespace

absl::Status ReadFloats(const tinygltf::Model& model, int index, int components,
                        std::vector<float>* out) {
    const std::string name = absl::StrCat("accessor #", index);
    if (index < 0 || index >= static_cast<int>(model.accessors.size()))
        return absl::InvalidArgumentError(absl::StrCat(name, " does not exist"));
    const tinygltf::Accessor& accessor = model.accessors[index];
    if (tinygltf::GetNumComponentsInType(accessor.type) != components)
        return absl::InvalidArgumentError(absl::StrCat(name, " has the wrong type"));
    const int type = accessor.componentType;
    const int component_size = tinygltf::GetComponentSizeInBytes(type);
    float probe;
    const unsigned char zero[4] = {};
    if (accessor.count == 0 || !Component(type, accessor.normalized, zero, &probe))
        return absl::InvalidArgumentError(
            absl::StrCat(name, " has no elements or an unsupported component type"));
    out->assign(accessor.count * components, 0.0f);
    // Without a buffer view every element is zero (then a sparse accessor gives the others).
    if (accessor.bufferView >= 0) {
        size_t stride = 0;
        const unsigned char* data = Elements(model, accessor.bufferView, accessor.byteOffset,
                                             accessor.count, type, components, false, &stride);
        if (data == nullptr)
            return absl::InvalidArgumentError(absl::StrCat(name, " lies outside its buffer"));
        for (size_t i = 0; i < accessor.count; ++i)
            for (int c = 0; c < components; ++c)
                Component(type, accessor.normalized, data + i * stride + c * component_size,
                          &(*out)[i * components + c]);
    }
    if (!accessor.sparse.isSparse) return absl::OkStatus();
    return ForEachSparseValue(
        model, accessor, name, components, [&](uint32_t element, const unsigned char* values) {
            for (int c = 0; c < components; ++c)
                Component(type, accessor.normalized, values + c * component_size,
                          &(*out)[size_t(element) * components + c]);
            return absl::OkStatus();
        });
}

absl::Status ReadIndices(const tinygltf::Model& model, int index, std::vector<uint32_t>* out) {
    const std::string name = absl::StrCat("index accessor #", index);
    if (index < 0 || index >= static_cast<int>(model.accessors.size()))
        return absl::InvalidArgumentError(absl::StrCat(name, " does not exist"));
    const tinygltf::Accessor& accessor = model.accessors[index];
    uint32_t probe;
    const unsigned char zero[4] = {};
    if (accessor.type != TINYGLTF_TYPE_SCALAR || !Index(accessor.componentType, zero, &probe))
        return absl::InvalidArgumentError(
            absl::StrCat(name, " is malformed (indices are unsigned integer scalars)"));
    out->assign(accessor.count, 0);
    if (accessor.bufferView >= 0) {
        size_t stride = 0;
        const unsigned char* data =
            Elements(model, accessor.bufferView, accessor.byteOffset, accessor.count,
                     accessor.componentType, 1, false, &stride);
        if (data == nullptr)
            return absl::InvalidArgumentError(absl::StrCat(name, " lies outside its buffer"));
        for (size_t i = 0; i < accessor.count; ++i)
            Index(accessor.componentType, data + i * stride, &(*out)[i]);
    }
    if (!accessor.sparse.isSparse) return absl::OkStatus();
    return ForEachSparseValue(model, accessor, name, 1,
                              [&](uint32_t element, const unsigned char* value) {
                                  Index(accessor.componentType, value, &(*out)[element]);
                                  return absl::OkStatus();
                              });
}

const tinygltf::TextureInfo* CoordinateTexture(const tinygltf::Material& material) {
    if (material.pbrMetallicRoughness.baseColorTexture.index >= 0)
        return &material.pbrMetallicRoughness.baseColorTexture;
    if (material.emissiveTexture.index >= 0) return &material.emissiveTexture;
    if (material.pbrMetallicRoughness.metallicRoughnessTexture.index >= 0)
        return &material.pbrMetallicRoughness.metallicRoughnessTexture;
    return nullptr;
}

int CoordinateSet(const tinygltf::Material& material) {
    if (const tinygltf::TextureInfo* texture = CoordinateTexture(material))
        return texture->texCoord;
    return material.normalTexture.index >= 0 ? material.normalTexture.texCoord : 0;
}

namespace {

// A triangle strip's or fan's indices as a list of triangles, as the glTF specification
// numbers them (3.7.2.1: strip triangle i is {v_i, v_(i+(1+i%2)), v_(i+(2-i%2))}, fan triangle
// i is {v_(i+1), v_(i+2), v_0}).
std::vector<uint32_t> TriangleList(int mode, const std::vector<uint32_t>& indices) {
    std::vector<uint32_t> list;
    if (indices.size() < 3) return list;
    list.reserve(3 * (indices.size() - 2));
    for (size_t i = 0; i + 2 < indices.size(); ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP)
            list.insert(list.end(), {indices[i], indices[i + 1 + i % 2], indices[i + 2 - i % 2]});
        else
            list.insert(list.end(), {indices[i + 1], indices[i + 2], indices[0]});
    }
    return list;
}

}  // namespace

absl::StatusOr<TriangleMesh> ReadTriangles(const tinygltf::Model& model,
                                           const tinygltf::Primitive& primitive,
                                           uint64_t max_triangles, VertexAttributes* extra) {
    auto error = [](const std::string& what) { return absl::InvalidArgumentError(what); };
    // The texture coordinates the material's texture reads (its texCoord), TEXCOORD_0 where it
    // has none.
    int set = 0;
    if (primitive.material >= 0 && primitive.material < static_cast<int>(model.materials.size()))
        set = CoordinateSet(model.materials[primitive.material]);
    const std::string uv_name = absl::StrCat("TEXCOORD_", set);
    const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN)
        return error(absl::StrCat("mode ", mode, " is not triangles"));
    if (const auto draco = primitive.extensions.find("KHR_draco_mesh_compression");
        draco != primitive.extensions.end()) {
        if (mode != TINYGLTF_MODE_TRIANGLES)
            return error("a Draco-compressed primitive must be triangles (mode 4)");
        return DecodeDracoPrimitive(model, primitive, draco->second, uv_name, max_triangles, extra);
    }
    const auto position_it = primitive.attributes.find("POSITION");
    if (position_it == primitive.attributes.end()) return error("has no POSITION attribute");
    std::vector<float> positions, normals, uvs, tangents;
    if (absl::Status s = ReadFloats(model, position_it->second, 3, &positions); !s.ok()) return s;
    const size_t vertex_count = positions.size() / 3;
    for (size_t v = 0; v < 3 * vertex_count; ++v)
        if (!std::isfinite(positions[v]))
            return error(absl::StrCat("vertex ", v / 3, " position has NaN or Inf"));
    if (auto it = primitive.attributes.find("NORMAL"); it != primitive.attributes.end()) {
        if (absl::Status s = ReadFloats(model, it->second, 3, &normals); !s.ok()) return s;
        if (normals.size() != positions.size()) return error("NORMAL and POSITION counts differ");
    }
    if (auto it = primitive.attributes.find("TANGENT"); it != primitive.attributes.end()) {
        if (absl::Status s = ReadFloats(model, it->second, 4, &tangents); !s.ok()) return s;
        if (tangents.size() / 4 != vertex_count) return error("TANGENT and POSITION counts differ");
    }
    if (auto it = primitive.attributes.find(uv_name); it != primitive.attributes.end()) {
        if (absl::Status s = ReadFloats(model, it->second, 2, &uvs); !s.ok()) return s;
        if (uvs.size() / 2 != vertex_count)
            return error(absl::StrCat(uv_name, " and POSITION counts differ"));
    } else if (set != 0) {
        return error(absl::StrCat("its material's texture reads ", uv_name,
                                  ", which the primitive does not have"));
    }
    TriangleMesh mesh;
    for (size_t v = 0; v < vertex_count; ++v) {
        mesh.positions.emplace_back(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
        if (!normals.empty())
            mesh.normals.emplace_back(normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]);
        if (!uvs.empty()) mesh.uvs.push_back({uvs[2 * v], uvs[2 * v + 1]});
        // xyz; w, the bitangent's side, is each triangle's own (core/scene/tangents.h).
        if (!tangents.empty())
            mesh.tangents.emplace_back(tangents[4 * v], tangents[4 * v + 1], tangents[4 * v + 2]);
    }
    if (primitive.indices >= 0) {
        if (absl::Status s = ReadIndices(model, primitive.indices, &mesh.indices); !s.ok())
            return s;
    } else {
        for (uint32_t i = 0; i < vertex_count; ++i) mesh.indices.push_back(i);
    }
    if (mode != TINYGLTF_MODE_TRIANGLES) mesh.indices = TriangleList(mode, mesh.indices);
    if (mesh.indices.size() % 3 != 0) return error("index count is not a multiple of 3");
    for (size_t i = 0; i < mesh.indices.size(); ++i)
        if (mesh.indices[i] >= vertex_count)
            return error(absl::StrCat("triangle ", i / 3, " has an index beyond the ", vertex_count,
                                      " vertices"));
    if (extra != nullptr)
        for (const auto& [name, components] : extra->wanted) {
            const auto it = primitive.attributes.find(name);
            if (it == primitive.attributes.end()) continue;
            std::vector<float>& values = extra->values[name];
            if (absl::Status s = ReadFloats(model, it->second, components, &values); !s.ok())
                return error(absl::StrCat(name, ": ", s.message()));
            if (values.size() != vertex_count * components)
                return error(absl::StrCat(name, " and POSITION counts differ"));
        }
    return mesh;
}

}  // namespace pf
