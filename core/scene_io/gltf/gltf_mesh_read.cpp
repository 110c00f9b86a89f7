// glTF primitives read as their nodes place them.
#include "core/scene_io/gltf/gltf_mesh_read.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "core/scene_io/gltf/gltf_accessors.h"
#include "core/scene_io/gltf/gltf_materials.h"
#include "core/scene_io/gltf/gltf_skin.h"

namespace pf {
namespace {

absl::Status Invalid(const std::string& where, const std::string& what) {
    return absl::InvalidArgumentError(absl::StrCat(where, ": ", what));
}

// COLOR_0 as read into `mesh` (float or normalised unsigned integers; clamped to [0, 1]),
// dropped where every vertex is white.
absl::Status TakeColors(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                        const std::string& where, VertexAttributes& attributes,
                        TriangleMesh& mesh) {
    const auto values = attributes.values.find("COLOR_0");
    if (values == attributes.values.end()) return absl::OkStatus();
    const tinygltf::Accessor& accessor = model.accessors[primitive.attributes.at("COLOR_0")];
    const int components = attributes.wanted["COLOR_0"];
    const int type = accessor.componentType;
    if ((components != 3 && components != 4) ||
        !(type == TINYGLTF_COMPONENT_TYPE_FLOAT ||
          (accessor.normalized && (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                   type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT))))
        return Invalid(where,
                       "COLOR_0 must be VEC3 or VEC4 of floats or normalised unsigned bytes or "
                       "shorts");
    size_t clamped = 0;
    bool white = true;
    mesh.colors.resize(mesh.positions.size());
    for (size_t v = 0; v < mesh.colors.size(); ++v) {
        float channel[4] = {1, 1, 1, 1};
        for (int c = 0; c < components; ++c) {
            const float x = values->second[v * components + c];
            if (std::isnan(x))
                return Invalid(where, absl::StrCat("COLOR_0 of vertex ", v, " is NaN"));
            channel[c] = std::clamp(x, 0.0f, 1.0f);
            clamped += channel[c] != x;
            white &= channel[c] == 1.0f;
        }
        mesh.colors[v] = {Rgb(channel[0], channel[1], channel[2]), channel[3]};
    }
    if (clamped > 0)
        spdlog::warn(
            "{}: {} COLOR_0 values outside [0, 1] clamped (a colour multiplies "
            "reflectance, which must not exceed 1)",
            where, clamped);
    if (white) mesh.colors.clear();  // multiplies nothing: no cost
    return absl::OkStatus();
}

}  // namespace

absl::StatusOr<std::optional<TriangleMesh>> ReadGltfPrimitive(const tinygltf::Model& model,
                                                              const tinygltf::Primitive& primitive,
                                                              const GltfPose& pose,
                                                              uint64_t max_triangles,
                                                              const std::string& where) {
    if (primitive.mode >= 0 && primitive.mode < TINYGLTF_MODE_TRIANGLES) {
        spdlog::warn("{}: mode {} (points or lines) is not surfaces; skipped", where,
                     primitive.mode);
        return std::nullopt;
    }
    VertexAttributes attributes;
    if (const auto it = primitive.attributes.find("COLOR_0");
        it != primitive.attributes.end() && it->second >= 0 &&
        it->second < static_cast<int>(model.accessors.size()))
        attributes.wanted["COLOR_0"] =
            tinygltf::GetNumComponentsInType(model.accessors[it->second].type);
    if (pose.joints != nullptr) WantSkinAttributes(primitive, &attributes);
    absl::StatusOr<TriangleMesh> mesh = ReadTriangles(model, primitive, max_triangles, &attributes);
    if (!mesh.ok()) return Invalid(where, std::string(mesh.status().message()));
    if (absl::Status status = TakeColors(model, primitive, where, attributes, *mesh); !status.ok())
        return status;
    const bool draco = primitive.extensions.contains("KHR_draco_mesh_compression");
    // Morph targets at the default weights (the base shape where there are none: all 0).
    if (pose.weights != nullptr && !primitive.targets.empty() &&
        std::any_of(pose.weights->begin(), pose.weights->end(), [](double w) { return w != 0; })) {
        std::vector<std::string> left_out;
        if (draco)
            spdlog::warn(
                "{}: its morph targets are left out (a Draco stream orders its vertices "
                "its own way)",
                where);
        else if (absl::Status status =
                     ApplyMorphTargets(model, primitive, *pose.weights, &*mesh, &left_out);
                 !status.ok())
            return Invalid(where, std::string(status.message()));
        if (!left_out.empty())
            spdlog::warn(
                "{}: morph targets' {} left out (positions, normals and tangents "
                "are moved)",
                where, absl::StrJoin(left_out, ", "));
    }
    if (pose.joints != nullptr) {
        absl::StatusOr<SkinInfluences> influences = SkinInfluencesOf(attributes);
        size_t unweighted = 0;
        absl::Status status = influences.status();
        if (status.ok()) status = SkinMesh(*pose.joints, *influences, &*mesh, &unweighted);
        if (!status.ok()) return Invalid(where, absl::StrCat("skin: ", status.message()));
        if (unweighted > 0)
            spdlog::warn("{}: {} vertices have no joint weight: left in the skin's bind pose",
                         where, unweighted);
    }
    return std::optional<TriangleMesh>(std::move(*mesh));
}

absl::StatusOr<std::vector<Transform>> GltfGpuInstances(const tinygltf::Model& model,
                                                        const tinygltf::Node& node) {
    const tinygltf::Value* e = Extension(node.extensions, "EXT_mesh_gpu_instancing");
    if (e == nullptr || !e->Has("attributes") || !e->Get("attributes").IsObject())
        return std::vector<Transform>{};
    const tinygltf::Value& attributes = e->Get("attributes");
    // Each attribute as `components` floats an instance (quantized ones normalised as
    // accessors say); absent: none.
    std::vector<float> values[3];
    const char* names[3] = {"TRANSLATION", "ROTATION", "SCALE"};
    const int components[3] = {3, 4, 3};
    size_t count = 0;
    for (int a = 0; a < 3; ++a) {
        if (!attributes.Has(names[a])) continue;
        const int accessor = static_cast<int>(NumberOr(attributes, names[a], -1));
        if (absl::Status status = ReadFloats(model, accessor, components[a], &values[a]);
            !status.ok())
            return absl::InvalidArgumentError(
                absl::StrCat("EXT_mesh_gpu_instancing ", names[a], ": ", status.message()));
        const size_t n = values[a].size() / components[a];
        if (count != 0 && n != count)
            return absl::InvalidArgumentError(
                "EXT_mesh_gpu_instancing: its attributes' counts differ");
        count = n;
    }
    std::vector<Transform> instances;
    for (size_t i = 0; i < count; ++i) {
        const auto at = [&](int a, int c, double fallback) {
            return values[a].empty() ? fallback : double(values[a][i * components[a] + c]);
        };
        const double rotation[4] = {at(1, 0, 0), at(1, 1, 0), at(1, 2, 0), at(1, 3, 1)};
        instances.push_back(Transform::FromTrs(Vec3d(at(0, 0, 0), at(0, 1, 0), at(0, 2, 0)),
                                               rotation,
                                               Vec3d(at(2, 0, 1), at(2, 1, 1), at(2, 2, 1))));
    }
    return instances;
}

}  // namespace pf
