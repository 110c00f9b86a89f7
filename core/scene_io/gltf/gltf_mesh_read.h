// Reading a glTF primitive's triangles as its node places them: its vertex colours, its morph
// targets at their default weights, its skin in its default pose (gltf_skin.h); and
// EXT_mesh_gpu_instancing's instances.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "core/math/transform.h"
#include "core/scene/mesh_builder.h"

namespace pf {

// How a node deforms its mesh: morph weights (the node's, else the mesh's; null: none), and
// the joint matrices of its skin (null: placed rigidly by the node's transform).
struct GltfPose {
    const std::vector<double>* weights = nullptr;
    const std::vector<Transform>* joints = nullptr;
};

// The primitive's triangles (gltf_accessors.h's ReadTriangles) with COLOR_0 (float or
// normalised unsigned integers; clamped to [0, 1] with a warning; dropped where every vertex is
// white), morphed and skinned as `pose` says: in the mesh's space, or in the world where it is
// skinned. nullopt for points and lines, which are skipped with a warning. Errors and warnings
// begin with `where` ("scene.gltf: mesh 'm' (#0) primitive 1").
absl::StatusOr<std::optional<TriangleMesh>> ReadGltfPrimitive(const tinygltf::Model& model,
                                                              const tinygltf::Primitive& primitive,
                                                              const GltfPose& pose,
                                                              uint64_t max_triangles,
                                                              const std::string& where);

// EXT_mesh_gpu_instancing: each instance's transform relative to `node` (TRANSLATION, ROTATION,
// SCALE, as accessors give them); none without the extension. Errors say what is wrong.
absl::StatusOr<std::vector<Transform>> GltfGpuInstances(const tinygltf::Model& model,
                                                        const tinygltf::Node& node);

}  // namespace pf
