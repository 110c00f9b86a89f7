// glTF's vertex deformations for a still render: morph targets at their default weights and
// skins posed by their joints' default node transforms (glTF 2.0, "Morph Targets" and
// "Skins"), morph first, then skin, as the specification orders them.
#pragma once

#include <tiny_gltf.h>

#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/math/transform.h"
#include "core/scene/mesh_builder.h"
#include "core/scene_io/gltf/gltf_accessors.h"

namespace pf {

// Every node's world transform by its default translation, rotation and scale (or matrix),
// whether or not a scene holds it; identity for a node whose transform is not finite or that
// sits in a cycle (the node traversal refuses those where they matter).
std::vector<Transform> NodeWorldTransforms(const tinygltf::Model& model);

// The joint matrices of skin `skin`: each joint node's world transform times its inverse bind
// matrix (identity where the skin gives none). Errors say why the skin cannot be posed (a joint
// or the accessor that does not exist, a matrix that is not finite), for the caller to place.
absl::StatusOr<std::vector<Transform>> JointMatrices(const tinygltf::Model& model, int skin,
                                                     const std::vector<Transform>& node_world);

// The vertices' joints and weights: JOINTS_n and WEIGHTS_n of every set n the primitive has,
// four a set a vertex.
struct SkinInfluences {
    std::vector<float> joints, weights;  // `sets` x 4 a vertex
    int sets = 0;
};

// The attributes SkinInfluences needs of `primitive` (JOINTS_n, WEIGHTS_n: 4 components each),
// for ReadTriangles to read.
void WantSkinAttributes(const tinygltf::Primitive& primitive, VertexAttributes* attributes);
// The influences among what ReadTriangles read. Errors: a set without its joints or weights.
absl::StatusOr<SkinInfluences> SkinInfluencesOf(const VertexAttributes& attributes);

// Poses `mesh` by glTF's skinning equation: each vertex by the sum of its joints' matrices
// (`joints`) weighed by its weights, normalised to sum 1 (a vertex whose weights sum to 0 stays
// where it is, counted in `unweighted`); normals by that matrix's inverse transpose, tangents by
// its linear part. Errors: a joint index beyond the skin's joints, a weight not finite or
// negative.
absl::Status SkinMesh(const std::vector<Transform>& joints, const SkinInfluences& influences,
                      TriangleMesh* mesh, size_t* unweighted);

// Adds the primitive's morph targets to `mesh` (read from its accessors, the same vertices)
// weighed by `weights`: POSITION, NORMAL (then renormalised) and TANGENT displacements; targets
// of weight 0 are not read. `left_out` gets the names of other attributes a weighted target
// displaces (TEXCOORD_n, COLOR_n), which are not applied.
absl::Status ApplyMorphTargets(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                               const std::vector<double>& weights, TriangleMesh* mesh,
                               std::vector<std::string>* left_out);

}  // namespace pf
