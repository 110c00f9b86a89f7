// Reading a glTF model's accessors (through tinygltf's parsed model) into plain arrays, with
// every offset, stride and count checked against the buffers: a hostile file cannot make a
// read leave them.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/scene/mesh_builder.h"

namespace pf {

// Accessor `index` as `components` floats per element, as glTF defines them: floats, and the
// integer types of KHR_mesh_quantization, normalised where the accessor says so; sparse
// substitutions applied; no buffer view: zeros. Errors name the accessor (missing, wrong
// type, out of its buffer, bad sparse indices).
absl::Status ReadFloats(const tinygltf::Model& model, int index, int components,
                        std::vector<float>* out);

// Index accessor `index` (unsigned byte, short or int scalars, sparse or not) as 32-bit
// indices.
absl::Status ReadIndices(const tinygltf::Model& model, int index, std::vector<uint32_t>* out);

// The texture whose coordinates a material's surfaces carry (one set per vertex): the base
// colour's, else the emissive one's, else the metallic-roughness one's; null where it has none
// (its normal texture's are carried then, CoordinateSet).
const tinygltf::TextureInfo* CoordinateTexture(const tinygltf::Material& material);
// The TEXCOORD_n set those are: CoordinateTexture's, else the normal texture's, else 0.
int CoordinateSet(const tinygltf::Material& material);

// Vertex attributes a caller asks ReadTriangles for beyond the mesh's own (COLOR_0, JOINTS_n,
// WEIGHTS_n): by name, the components a vertex; what the primitive has of them comes back in
// `values`, as ReadFloats reads them (normalised where the accessor says so), one per vertex.
struct VertexAttributes {
    std::map<std::string, int> wanted;
    std::map<std::string, std::vector<float>> values;
};

// A triangle primitive's mesh: POSITION, NORMAL and TANGENT if given, the TEXCOORD_n set its
// material's CoordinateSet names, and its indices (or 0, 1, 2, ... without; a triangle strip's
// or fan's turned into a list of triangles), every index checked against the vertices; and the
// `extra` attributes asked for; from its Draco stream where it is compressed
// (KHR_draco_mesh_compression, gltf_draco.h). Errors say what is wrong, for the caller to place.
absl::StatusOr<TriangleMesh> ReadTriangles(const tinygltf::Model& model,
                                           const tinygltf::Primitive& primitive,
                                           uint64_t max_triangles,
                                           VertexAttributes* extra = nullptr);

}  // namespace pf
