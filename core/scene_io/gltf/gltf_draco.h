// KHR_draco_mesh_compression: a glTF primitive whose vertices and triangles are a Draco
// stream in one of the file's buffer views, decoded through Debian's libdraco.
#pragma once

#include <tiny_gltf.h>

#include <string>

#include "absl/status/statusor.h"
#include "core/scene/mesh_builder.h"
#include "core/scene_io/gltf/gltf_accessors.h"

namespace pf {

// The primitive's mesh from its Draco stream (`extension`, the primitive's
// KHR_draco_mesh_compression object): POSITION, NORMAL where the stream has it, the
// `uv_attribute` (TEXCOORD_n) set where it has it, the `extra` attributes asked for that it has
// (normalised where the primitive's accessor of that name says so), and the triangles, every
// count and index checked. Errors say what is wrong (a malformed extension, a stream Draco
// refuses, an attribute missing or of the wrong size), for the caller to place.
absl::StatusOr<TriangleMesh> DecodeDracoPrimitive(const tinygltf::Model& model,
                                                  const tinygltf::Primitive& primitive,
                                                  const tinygltf::Value& extension,
                                                  const std::string& uv_attribute,
                                                  uint64_t max_triangles,
                                                  VertexAttributes* extra = nullptr);

// The glTF file `contents` (a .glb when `binary`) with the "indices" of every Draco-compressed
// primitive left out: the triangles are in the stream, and tinygltf refuses an index accessor
// without a buffer view, which is how such files give them. Unchanged where no primitive is
// compressed or the JSON does not parse (tinygltf then says what is wrong).
std::string WithoutDracoIndices(const std::string& contents, bool binary);

}  // namespace pf
