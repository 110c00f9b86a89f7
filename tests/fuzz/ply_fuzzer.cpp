// libFuzzer target for the PLY reader pbrt scenes' meshes go through: any bytes must come back
// as a mesh whose indices all name its vertices (three a triangle, within the triangle limit)
// or as an error, never a crash, a sanitizer report, a leak or a read past the input.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/scene_io/ply/ply_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    pf::SceneLimits limits;
    limits.max_triangles = 1u << 16;
    // The input as its own allocation of exactly its size, so AddressSanitizer sees any read
    // past its end (libFuzzer's buffer is that already).
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    const absl::StatusOr<pf::TriangleMesh> mesh = pf::ReadPly(bytes, "fuzz.ply", limits);
    if (!mesh.ok()) return 0;
    const size_t vertices = mesh->positions.size();
    if (mesh->indices.empty() || mesh->indices.size() % 3 != 0 ||
        mesh->indices.size() / 3 > limits.max_triangles)
        __builtin_trap();
    if ((!mesh->normals.empty() && mesh->normals.size() != vertices) ||
        (!mesh->uvs.empty() && mesh->uvs.size() != vertices))
        __builtin_trap();
    for (const uint32_t index : mesh->indices)
        if (index >= vertices) __builtin_trap();
    for (const pf::Vec3& p : mesh->positions)
        if (!pf::IsFinite(p)) __builtin_trap();
    return 0;
}
