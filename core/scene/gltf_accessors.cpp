// Reading glTF accessors: bounds checked against their views and buffers, every number from
// the file distrusted.
#include "core/scene/gltf_accessors.h"

#include <cstring>

#include "absl/strings/str_cat.h"

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

}  // namespace

// Reads accessor `index` as `components` floats per element, converting normalised integer
// types; fails on out-of-range views.
absl::Status ReadFloats(const tinygltf::Model& model, int index, int components,
                        std::vector<float>* out) {
    if (index < 0 || index >= static_cast<int>(model.accessors.size()))
        return absl::InvalidArgumentError(absl::StrCat("accessor #", index, " does not exist"));
    const tinygltf::Accessor& accessor = model.accessors[index];
    if (tinygltf::GetNumComponentsInType(accessor.type) != components)
        return absl::InvalidArgumentError(absl::StrCat("accessor #", index, " has the wrong type"));
    if (accessor.sparse.isSparse)
        return absl::InvalidArgumentError(
            absl::StrCat("accessor #", index, " is sparse (unsupported)"));
    if (accessor.bufferView < 0 ||
        accessor.bufferView >= static_cast<int>(model.bufferViews.size()))
        return absl::InvalidArgumentError(absl::StrCat("accessor #", index, " has no buffer view"));
    const tinygltf::BufferView& view = model.bufferViews[accessor.bufferView];
    const int component_size = tinygltf::GetComponentSizeInBytes(accessor.componentType);
    const size_t stride =
        view.byteStride != 0 ? view.byteStride : size_t(component_size) * components;
    if (component_size <= 0 || accessor.count == 0 ||
        !AccessorFits(model, view, accessor.byteOffset, accessor.count, stride,
                      size_t(component_size) * components))
        return absl::InvalidArgumentError(
            absl::StrCat("accessor #", index, " lies outside its buffer"));
    const tinygltf::Buffer& buffer = model.buffers[view.buffer];
    const size_t begin = view.byteOffset + accessor.byteOffset;
    out->resize(accessor.count * components);
    for (size_t i = 0; i < accessor.count; ++i) {
        const unsigned char* element = buffer.data.data() + begin + i * stride;
        for (int c = 0; c < components; ++c) {
            const unsigned char* p = element + c * component_size;
            float value;
            switch (accessor.componentType) {
                case TINYGLTF_COMPONENT_TYPE_FLOAT:
                    std::memcpy(&value, p, 4);
                    break;
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
                    value = *p / 255.0f;
                    break;
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                    uint16_t v;
                    std::memcpy(&v, p, 2);
                    value = v / 65535.0f;
                    break;
                }
                default:
                    return absl::InvalidArgumentError(
                        absl::StrCat("accessor #", index, " has an unsupported component type"));
            }
            (*out)[i * components + c] = value;
        }
    }
    return absl::OkStatus();
}

absl::Status ReadIndices(const tinygltf::Model& model, int index, std::vector<uint32_t>* out) {
    if (index < 0 || index >= static_cast<int>(model.accessors.size()))
        return absl::InvalidArgumentError(
            absl::StrCat("index accessor #", index, " does not exist"));
    const tinygltf::Accessor& accessor = model.accessors[index];
    if (accessor.bufferView < 0 ||
        accessor.bufferView >= static_cast<int>(model.bufferViews.size()) ||
        accessor.type != TINYGLTF_TYPE_SCALAR)
        return absl::InvalidArgumentError(absl::StrCat("index accessor #", index, " is malformed"));
    const tinygltf::BufferView& view = model.bufferViews[accessor.bufferView];
    const int size = tinygltf::GetComponentSizeInBytes(accessor.componentType);
    const size_t stride = view.byteStride != 0 ? view.byteStride : size_t(size);
    if (size <= 0 ||
        !AccessorFits(model, view, accessor.byteOffset, accessor.count, stride, size_t(size)))
        return absl::InvalidArgumentError(
            absl::StrCat("index accessor #", index, " lies outside its buffer"));
    const tinygltf::Buffer& buffer = model.buffers[view.buffer];
    const size_t begin = view.byteOffset + accessor.byteOffset;
    out->resize(accessor.count);
    for (size_t i = 0; i < accessor.count; ++i) {
        const unsigned char* p = buffer.data.data() + begin + i * stride;
        switch (accessor.componentType) {
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
                (*out)[i] = *p;
                break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                uint16_t v;
                std::memcpy(&v, p, 2);
                (*out)[i] = v;
                break;
            }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
                std::memcpy(&(*out)[i], p, 4);
                break;
            default:
                return absl::InvalidArgumentError(
                    absl::StrCat("index accessor #", index, " has a non-integer type"));
        }
    }
    return absl::OkStatus();
}

}  // namespace pf
