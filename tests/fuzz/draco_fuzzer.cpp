// libFuzzer target for KHR_draco_mesh_compression: the input is a Draco stream in a glTF
// buffer view, decoded into a mesh or refused, never a crash, a sanitizer report or a leak;
// every index of a decoded mesh lies within its points.
#include <cstddef>
#include <cstdint>

#include "core/scene_io/gltf/gltf_draco.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    tinygltf::Model model;
    model.buffers.emplace_back().data.assign(data, data + size);
    tinygltf::BufferView& view = model.bufferViews.emplace_back();
    view.buffer = 0;
    view.byteLength = size;
    tinygltf::Value::Object attributes{{"POSITION", tinygltf::Value(0)},
                                       {"TEXCOORD_0", tinygltf::Value(1)},
                                       {"NORMAL", tinygltf::Value(2)}};
    const tinygltf::Value extension(tinygltf::Value::Object{
        {"bufferView", tinygltf::Value(0)}, {"attributes", tinygltf::Value(attributes)}});
    const absl::StatusOr<pf::TriangleMesh> mesh =
        pf::DecodeDracoPrimitive(model, tinygltf::Primitive(), extension, "TEXCOORD_0", 1 << 20);
    if (mesh.ok())
        for (uint32_t index : mesh->indices)
            if (index >= mesh->positions.size()) __builtin_trap();
    return 0;
}
