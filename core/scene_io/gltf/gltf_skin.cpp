// Morph targets at their default weights and skins in their default pose.
#include "core/scene_io/gltf/gltf_skin.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "absl/strings/str_cat.h"

namespace pf {
namespace {

Transform LocalTransform(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) return Transform::FromColumnMajor(node.matrix.data());
    const Vec3d t = node.translation.size() == 3
                        ? Vec3d(node.translation[0], node.translation[1], node.translation[2])
                        : Vec3d(0.0);
    const Vec3d s =
        node.scale.size() == 3 ? Vec3d(node.scale[0], node.scale[1], node.scale[2]) : Vec3d(1.0);
    const double identity[4] = {0, 0, 0, 1};
    return Transform::FromTrs(t, node.rotation.size() == 4 ? node.rotation.data() : identity, s);
}

// Transform `t` scaled by `w` and added to `sum` (the skinning equation's weighted sum).
void AddWeighted(const Transform& t, double w, Transform* sum) {
    for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 4; ++column) sum->m[row][column] += w * t.m[row][column];
}

}  // namespace

std::vector<Transform> NodeWorldTransforms(const tinygltf::Model& model) {
    const size_t count = model.nodes.size();
    std::vector<int> parent(count, -1);
    for (size_t n = 0; n < count; ++n)
        for (const int child : model.nodes[n].children)
            if (child >= 0 && size_t(child) < count && parent[child] < 0)
                parent[child] = static_cast<int>(n);
    std::vector<Transform> world(count);
    std::vector<char> done(count, 0);
    // Each node after its parent, by walking up to the nearest one done (a cycle stops the
    // walk: its nodes keep the identity).
    for (size_t n = 0; n < count; ++n) {
        std::vector<int> chain;
        int at = static_cast<int>(n);
        while (at >= 0 && !done[at] && chain.size() <= count) {
            chain.push_back(at);
            at = parent[at];
        }
        if (chain.size() > count) continue;
        Transform above = at >= 0 ? world[at] : Transform{};
        for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
            const Transform local = LocalTransform(model.nodes[*it]);
            if (local.IsFinite()) above = above * local;
            world[*it] = above;
            done[*it] = 1;
        }
    }
    return world;
}

absl::StatusOr<std::vector<Transform>> JointMatrices(const tinygltf::Model& model, int skin,
                                                     const std::vector<Transform>& node_world) {
    if (skin < 0 || skin >= static_cast<int>(model.skins.size()))
        return absl::InvalidArgumentError(absl::StrCat("skin #", skin, " does not exist"));
    const tinygltf::Skin& source = model.skins[skin];
    if (source.joints.empty()) return absl::InvalidArgumentError("the skin has no joints");
    std::vector<float> inverse_bind;
    if (source.inverseBindMatrices >= 0) {
        if (absl::Status status = ReadFloats(model, source.inverseBindMatrices, 16, &inverse_bind);
            !status.ok())
            return absl::InvalidArgumentError(
                absl::StrCat("inverseBindMatrices: ", status.message()));
        if (inverse_bind.size() != 16 * source.joints.size())
            return absl::InvalidArgumentError(
                absl::StrCat("inverseBindMatrices holds ", inverse_bind.size() / 16,
                             " matrices for ", source.joints.size(), " joints"));
    }
    std::vector<Transform> joints;
    for (size_t j = 0; j < source.joints.size(); ++j) {
        const int node = source.joints[j];
        if (node < 0 || size_t(node) >= node_world.size())
            return absl::InvalidArgumentError(
                absl::StrCat("joint ", j, " names node #", node, ", which does not exist"));
        Transform bind;
        if (!inverse_bind.empty()) {
            double values[16];
            for (int k = 0; k < 16; ++k) values[k] = inverse_bind[16 * j + k];
            bind = Transform::FromColumnMajor(values);
        }
        const Transform joint = node_world[node] * bind;
        if (!joint.IsFinite())
            return absl::InvalidArgumentError(absl::StrCat("joint ", j, "'s matrix is not finite"));
        joints.push_back(joint);
    }
    return joints;
}

void WantSkinAttributes(const tinygltf::Primitive& primitive, VertexAttributes* attributes) {
    for (int set = 0;; ++set) {
        const std::string joints = absl::StrCat("JOINTS_", set),
                          weights = absl::StrCat("WEIGHTS_", set);
        if (!primitive.attributes.contains(joints) && !primitive.attributes.contains(weights))
            return;
        attributes->wanted[joints] = 4;
        attributes->wanted[weights] = 4;
    }
}

absl::StatusOr<SkinInfluences> SkinInfluencesOf(const VertexAttributes& attributes) {
    SkinInfluences influences;
    std::vector<const std::vector<float>*> joints, weights;
    for (int set = 0;; ++set) {
        const auto j = attributes.values.find(absl::StrCat("JOINTS_", set));
        const auto w = attributes.values.find(absl::StrCat("WEIGHTS_", set));
        if (j == attributes.values.end() && w == attributes.values.end()) break;
        if (j == attributes.values.end() || w == attributes.values.end())
            return absl::InvalidArgumentError(
                absl::StrCat("JOINTS_", set, " and WEIGHTS_", set, " come in pairs"));
        joints.push_back(&j->second), weights.push_back(&w->second);
    }
    influences.sets = static_cast<int>(joints.size());
    if (influences.sets == 0)
        return absl::InvalidArgumentError("the primitive has no JOINTS_0 and WEIGHTS_0");
    const size_t vertices = joints[0]->size() / 4;
    for (size_t v = 0; v < vertices; ++v)
        for (int set = 0; set < influences.sets; ++set)
            for (int k = 0; k < 4; ++k) {
                influences.joints.push_back((*joints[set])[4 * v + k]);
                influences.weights.push_back((*weights[set])[4 * v + k]);
            }
    return influences;
}

absl::Status SkinMesh(const std::vector<Transform>& joints, const SkinInfluences& influences,
                      TriangleMesh* mesh, size_t* unweighted) {
    const size_t per_vertex = 4 * size_t(influences.sets);
    if (influences.joints.size() != per_vertex * mesh->positions.size())
        return absl::InvalidArgumentError("JOINTS and POSITION counts differ");
    for (size_t v = 0; v < mesh->positions.size(); ++v) {
        // S = sum_i w_i J_(joint i), the weights normalised to sum 1 (glTF asks that they do;
        // exporters round them).
        double total = 0;
        for (size_t k = 0; k < per_vertex; ++k) {
            const float w = influences.weights[v * per_vertex + k];
            if (!(w >= 0 && std::isfinite(w)))
                return absl::InvalidArgumentError(
                    absl::StrCat("vertex ", v, " has a weight that is negative or not finite"));
            total += w;
        }
        if (!(total > 0)) {
            ++*unweighted;
            continue;
        }
        Transform skin;
        skin.m = {};
        for (size_t k = 0; k < per_vertex; ++k) {
            const float w = influences.weights[v * per_vertex + k];
            if (w == 0) continue;
            const float joint = influences.joints[v * per_vertex + k];
            if (!(joint >= 0 && joint < float(joints.size()) && joint == std::floor(joint)))
                return absl::InvalidArgumentError(absl::StrCat("vertex ", v, " names joint ", joint,
                                                               " of the skin's ", joints.size()));
            AddWeighted(joints[size_t(joint)], w / total, &skin);
        }
        skin.m[3] = {0, 0, 0, 1};
        mesh->positions[v] = Vec3(skin.ApplyPoint(Vec3d(mesh->positions[v])));
        if (!mesh->normals.empty()) {
            const Vec3d n = skin.ApplyNormal(Vec3d(mesh->normals[v]));
            mesh->normals[v] = LengthSquared(n) > 0 ? Vec3(Normalize(n)) : Vec3(0.0f);
        }
        if (!mesh->tangents.empty())
            mesh->tangents[v] = Vec3(skin.ApplyVector(Vec3d(mesh->tangents[v])));
    }
    return absl::OkStatus();
}

absl::Status ApplyMorphTargets(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                               const std::vector<double>& weights, TriangleMesh* mesh,
                               std::vector<std::string>* left_out) {
    const size_t vertices = mesh->positions.size();
    // Adds target attribute `name`'s displacements times `w` to `values` (three a vertex).
    const auto displace = [&](const std::map<std::string, int>& target, const char* name, double w,
                              const std::function<Vec3&(size_t)>& value,
                              bool present) -> absl::Status {
        const auto it = target.find(name);
        if (it == target.end() || !present) return absl::OkStatus();
        std::vector<float> delta;
        if (absl::Status status = ReadFloats(model, it->second, 3, &delta); !status.ok())
            return absl::InvalidArgumentError(
                absl::StrCat("morph target ", name, ": ", status.message()));
        if (delta.size() != 3 * vertices)
            return absl::InvalidArgumentError(
                absl::StrCat("morph target ", name, " and POSITION counts differ"));
        for (size_t v = 0; v < vertices; ++v)
            value(v) += Vec3(Vec3d(delta[3 * v], delta[3 * v + 1], delta[3 * v + 2]) * w);
        return absl::OkStatus();
    };
    bool normals_moved = false;
    for (size_t t = 0; t < primitive.targets.size() && t < weights.size(); ++t) {
        const double w = weights[t];
        if (w == 0) continue;
        if (!std::isfinite(w))
            return absl::InvalidArgumentError(absl::StrCat("morph weight ", t, " is not finite"));
        const std::map<std::string, int>& target = primitive.targets[t];
        for (const auto& [name, accessor] : target)
            if (name != "POSITION" && name != "NORMAL" && name != "TANGENT" &&
                std::find(left_out->begin(), left_out->end(), name) == left_out->end())
                left_out->push_back(name);
        if (absl::Status status = displace(
                target, "POSITION", w, [&](size_t v) -> Vec3& { return mesh->positions[v]; }, true);
            !status.ok())
            return status;
        if (absl::Status status = displace(
                target, "NORMAL", w, [&](size_t v) -> Vec3& { return mesh->normals[v]; },
                !mesh->normals.empty());
            !status.ok())
            return status;
        normals_moved |= target.contains("NORMAL") && !mesh->normals.empty();
        if (absl::Status status = displace(
                target, "TANGENT", w, [&](size_t v) -> Vec3& { return mesh->tangents[v]; },
                !mesh->tangents.empty());
            !status.ok())
            return status;
    }
    if (normals_moved)
        for (Vec3& n : mesh->normals)
            if (LengthSquared(n) > 0) n = Normalize(n);
    for (const Vec3& p : mesh->positions)
        if (!IsFinite(p)) return absl::InvalidArgumentError("a morphed position is not finite");
    return absl::OkStatus();
}

}  // namespace pf
