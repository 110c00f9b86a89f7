// glTF 2.0 loading: node hierarchy, triangle meshes (vertex colours, morph targets at their
// default weights, skins in their default pose: gltf_skin.h; single-sided open meshes), GPU
// instances, the camera, KHR_lights_punctual and the materials (gltf_materials.h).
#include "core/scene_io/gltf/gltf_loader.h"

#include <spdlog/spdlog.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <set>

#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "core/math/transform.h"
#include "core/scene/closed_surface.h"
#include "core/scene/scene_bundle.h"
#include "core/scene_io/gltf/gltf_accessors.h"
#include "core/scene_io/gltf/gltf_bundle_files.h"
#include "core/scene_io/gltf/gltf_draco.h"
#include "core/scene_io/gltf/gltf_lights.h"
#include "core/scene_io/gltf/gltf_materials.h"
#include "core/scene_io/gltf/gltf_mesh_read.h"
#include "core/scene_io/gltf/gltf_meshopt.h"
#include "core/scene_io/gltf/gltf_skin.h"
#include "core/scene_io/gltf/gltf_spec_gloss.h"
#include "core/scene_io/gltf/gltf_textures.h"
#include "core/scene_io/image_decode.h"
#include "core/scene_io/scene_files.h"

namespace pf {
namespace {

constexpr int kMaxNodeDepth = 256;

std::string Describe(const std::string& kind, int index, const std::string& name) {
    return DescribeGltf(kind, index, name);
}

// KHR_texture_transform: uv' = T(offset) R(rotation) S(scale) uv.
UvTransform TextureTransform(const tinygltf::Value& transform) {
    double offset[2] = {0, 0}, scale[2] = {1, 1};
    for (int i = 0; i < 2; ++i) {
        if (transform.Has("offset") && transform.Get("offset").IsArray() &&
            transform.Get("offset").ArrayLen() == 2)
            offset[i] = transform.Get("offset").Get(i).GetNumberAsDouble();
        if (transform.Has("scale") && transform.Get("scale").IsArray() &&
            transform.Get("scale").ArrayLen() == 2)
            scale[i] = transform.Get("scale").Get(i).GetNumberAsDouble();
    }
    const double rotation = NumberOr(transform, "rotation", 0.0), c = std::cos(rotation),
                 s = std::sin(rotation);
    UvTransform uv;
    uv.m[0] = c * scale[0], uv.m[1] = s * scale[1], uv.m[2] = offset[0];
    uv.m[3] = -s * scale[0], uv.m[4] = c * scale[1], uv.m[5] = offset[1];
    return uv;
}

class GltfSceneBuilder {
public:
    GltfSceneBuilder(const std::string& path, const tinygltf::Model& model,
                     const SceneLimits& limits, const GltfImages& images, const std::string& camera)
        : path_(path),
          model_(model),
          wanted_camera_(camera),
          limits_(limits),
          textures_(path, model, images, limits, &scene_) {
        scene_.source = path;
    }

    absl::StatusOr<Scene> Build();

private:
    absl::Status Error(const std::string& element, const std::string& what) const {
        return absl::InvalidArgumentError(absl::StrCat(path_, ": ", element, ": ", what));
    }
    // Notes the file's extensions that nothing here reads and its animations.
    void NoteLeftOut() const;
    absl::Status VisitNode(int index, const Transform& parent, int depth);
    // A mesh placed rigidly by `world`: once, or, where several nodes (or GPU instances) use
    // it, as an instance of its prototype.
    absl::Status AddMesh(int mesh_index, const Transform& world);
    // A mesh placed by one node alone: rigidly by `world`, or posed by `pose`'s joints.
    absl::Status AddPlacedMesh(int mesh_index, const Transform& world, const GltfPose& pose);
    // Each primitive of a mesh read, deformed as `pose` says (nullopt where it is skipped:
    // points, lines), and whether they close a surface together.
    struct MeshRead {
        std::vector<std::optional<TriangleMesh>> primitives;
        bool closed = false;
    };
    absl::StatusOr<MeshRead> ReadMesh(int mesh_index, const GltfPose& pose);
    // The Scene material primitive `primitive` of a mesh (`closed` or open) uses: its glTF
    // material's, as a single-sided variant where it is one-sided, open and opaque to
    // transmission, with its vertex colours' alpha where its alpha mode reads alpha.
    absl::StatusOr<uint32_t> PrimitiveMaterial(const tinygltf::Primitive& primitive,
                                               const TriangleMesh& mesh, bool closed);
    absl::Status AppendPrimitive(const TriangleMesh& mesh, const std::string& element,
                                 const Transform& world, uint32_t material,
                                 std::optional<uint32_t> prototype);
    // Whether the camera node met now (the cameras_seen_.size()-th, named `names`) is the
    // one asked for.
    bool WantedCamera(const std::vector<std::string>& names) const;
    void FrameBounds();
    absl::StatusOr<uint32_t> MaterialIndex(int gltf_material);
    // Material `material` with gpu::kSurface* `flags` added: itself without, else a copy made
    // once (the triangles name it; its mix's parts are shared).
    uint32_t Variant(uint32_t material, uint32_t flags);

    const std::string& path_;
    const tinygltf::Model& model_;
    Scene scene_;
    bool has_camera_ = false;
    const std::string& wanted_camera_;          // LoadGltf's `camera`
    std::vector<std::string> cameras_seen_;     // "#index 'name'" of each camera node met
    std::map<int, uint32_t> material_indices_;  // glTF material -> Scene::materials
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> variants_;  // (material, flags) -> variant
    std::map<uint32_t, UvTransform> material_uvs_;  // Scene::materials -> its texture's transform
    // A mesh that several nodes use: its emitting primitives (each with its material), placed
    // as world triangles by every node.
    std::map<int, std::vector<std::pair<TriangleMesh, uint32_t>>> emitting_;
    std::map<int, int> mesh_uses_;  // glTF mesh -> how many rigid placements name it
    std::map<int, uint32_t>
        mesh_prototypes_;                // glTF mesh used by several nodes -> Scene::prototypes
    std::vector<Transform> node_world_;  // every node's default world transform (skins)
    const SceneLimits& limits_;
    GltfTextureReader textures_;
};

absl::StatusOr<Scene> GltfSceneBuilder::Build() {
    // A required extension changes what the file means: one not read here is refused, as the
    // glTF specification asks, rather than rendered wrong.
    static const std::set<std::string> kSupported = {
        "KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_texture_transform",
        "KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_volume",
        "KHR_materials_specular", "KHR_materials_clearcoat", "KHR_materials_sheen",
        "KHR_mesh_quantization", "KHR_draco_mesh_compression", "EXT_meshopt_compression",
        "KHR_meshopt_compression", "KHR_materials_unlit", "KHR_materials_pbrSpecularGlossiness",
        // Read image by image: a texture whose only image is KTX2 is refused where a material
        // reads it, naming the way out (GltfTextureReader).
        "KHR_texture_basisu", "EXT_texture_webp", "EXT_mesh_gpu_instancing"};
    for (const std::string& extension : model_.extensionsRequired)
        if (!kSupported.contains(extension))
            return Error("extensionsRequired",
                         absl::StrCat("'", extension,
                                      "' is not supported (a sample model's glTF/ variant "
                                      "usually does without it)"));
    NoteLeftOut();
    std::vector<int> roots;
    if (!model_.scenes.empty()) {
        const int scene_index = model_.defaultScene >= 0 ? model_.defaultScene : 0;
        if (scene_index >= static_cast<int>(model_.scenes.size()))
            return Error("scene", absl::StrCat("default scene #", scene_index, " does not exist"));
        roots = model_.scenes[scene_index].nodes;
    } else {
        for (int i = 0; i < static_cast<int>(model_.nodes.size()); ++i) roots.push_back(i);
    }
    // Rigid placements of each mesh: a node's (or its GPU instances'); skinned nodes and nodes
    // with morph weights of their own pose theirs alone.
    for (int n = 0; n < static_cast<int>(model_.nodes.size()); ++n) {
        const tinygltf::Node& node = model_.nodes[n];
        if (node.mesh < 0 || node.skin >= 0 || !node.weights.empty()) continue;
        const absl::StatusOr<std::vector<Transform>> instances = GltfGpuInstances(model_, node);
        mesh_uses_[node.mesh] += instances.ok() && !instances->empty() ? 2 : 1;
    }
    if (!model_.skins.empty()) node_world_ = NodeWorldTransforms(model_);
    for (int root : roots)
        if (absl::Status status = VisitNode(root, Transform{}, 0); !status.ok()) return status;
    FinishInstancing(&scene_);
    if (absl::Status status = textures_.DecodePending(); !status.ok()) return status;
    if (scene_.triangles.empty()) return Error("scene", "has no triangles");
    if (!has_camera_ && !wanted_camera_.empty())
        return Error("--camera " + wanted_camera_,
                     cameras_seen_.empty() ? "the scene has no camera"
                                           : absl::StrCat("no such camera; the scene has ",
                                                          absl::StrJoin(cameras_seen_, ", ")));
    if (!has_camera_) FrameBounds();
    return std::move(scene_);
}

void GltfSceneBuilder::NoteLeftOut() const {
    // Read, or harmless to leave (metadata); KHR_materials_* ones are noted per material
    // (KHR_materials_variants, whose default materials are read, here).
    static const std::set<std::string> kRead = {"KHR_lights_punctual",
                                                "KHR_texture_transform",
                                                "KHR_mesh_quantization",
                                                "KHR_draco_mesh_compression",
                                                "EXT_meshopt_compression",
                                                "KHR_meshopt_compression",
                                                "KHR_texture_basisu",
                                                "EXT_texture_webp",
                                                "EXT_mesh_gpu_instancing",
                                                "KHR_xmp_json_ld",
                                                "KHR_xmp"};
    std::vector<std::string> left_out;
    for (const std::string& extension : model_.extensionsUsed)
        if (!kRead.contains(extension) &&
            (!extension.starts_with("KHR_materials_") || extension == "KHR_materials_variants"))
            left_out.push_back(extension);
    if (!left_out.empty())
        spdlog::warn("{}: {} not read (optional: what the file gives without them is rendered)",
                     path_, absl::StrJoin(left_out, ", "));
    if (!model_.animations.empty())
        spdlog::warn(
            "{}: {} animation(s) not played: the scene is rendered as its nodes' default "
            "transforms (and skins' default pose) place it",
            path_, model_.animations.size());
}

bool GltfSceneBuilder::WantedCamera(const std::vector<std::string>& names) const {
    if (wanted_camera_.empty()) return cameras_seen_.size() == 1;
    int index = -1;
    if (absl::SimpleAtoi(wanted_camera_, &index)) return index == int(cameras_seen_.size()) - 1;
    return std::find(names.begin(), names.end(), wanted_camera_) != names.end();
}

void GltfSceneBuilder::FrameBounds() {
    // As glTF viewers frame a scene that brings no camera (Khronos' sample viewer): look down
    // -z at the centre of the bounds, from where a 45-degree view holds the bounding sphere.
    Camera& camera = scene_.camera;
    camera.y_fov = kPi / 4;
    camera.aspect_ratio = 0;
    const Vec3 centre = scene_.bounds.Center();
    const float radius = std::max(0.5f * scene_.bounds.Diagonal(), 1e-6f);
    camera.position = centre + Vec3(0, 0, radius / std::sin(camera.y_fov / 2));
    camera.forward = Vec3(0, 0, -1), camera.right = Vec3(1, 0, 0), camera.up = Vec3(0, 1, 0);
    spdlog::warn(
        "{}: the scene has no camera: framed on its bounds as glTF viewers frame it "
        "(45 degrees, from +z); give it a camera node to choose the view",
        path_);
}

absl::Status GltfSceneBuilder::VisitNode(int index, const Transform& parent, int depth) {
    if (index < 0 || index >= static_cast<int>(model_.nodes.size()))
        return Error(absl::StrCat("node #", index), "does not exist");
    const tinygltf::Node& node = model_.nodes[index];
    const std::string element = Describe("node", index, node.name);
    if (depth > kMaxNodeDepth) return Error(element, "node hierarchy is too deep or cyclic");
    Transform local;
    if (node.matrix.size() == 16) {
        local = Transform::FromColumnMajor(node.matrix.data());
    } else {
        const Vec3d t = node.translation.size() == 3
                            ? Vec3d(node.translation[0], node.translation[1], node.translation[2])
                            : Vec3d(0.0);
        const Vec3d s = node.scale.size() == 3 ? Vec3d(node.scale[0], node.scale[1], node.scale[2])
                                               : Vec3d(1.0);
        const double identity[4] = {0, 0, 0, 1};
        local =
            Transform::FromTrs(t, node.rotation.size() == 4 ? node.rotation.data() : identity, s);
    }
    if (!local.IsFinite()) return Error(element, "transform has NaN or Inf");
    const Transform world = parent * local;
    if (!world.IsFinite()) return Error(element, "world transform overflows to NaN or Inf");
    if (node.mesh >= 0 && node.mesh >= static_cast<int>(model_.meshes.size()))
        return Error(absl::StrCat("mesh #", node.mesh), "does not exist");
    if (node.mesh >= 0 && node.skin >= 0) {
        // glTF's skinning places the vertices by the joints alone: the node's transform is not
        // applied (the specification: it must be ignored).
        absl::StatusOr<std::vector<Transform>> joints =
            JointMatrices(model_, node.skin, node_world_);
        GltfPose pose{node.weights.empty() ? &model_.meshes[node.mesh].weights : &node.weights,
                      joints.ok() ? &*joints : nullptr};
        if (!joints.ok())
            spdlog::warn(
                "{}: {}: skin #{} cannot be posed ({}): its mesh is placed by the node's "
                "transform, in its bind pose",
                path_, element, node.skin, std::string(joints.status().message()));
        if (absl::Status status = AddPlacedMesh(node.mesh, world, pose); !status.ok())
            return status;
    } else if (node.mesh >= 0 && !node.weights.empty()) {
        if (absl::Status status = AddPlacedMesh(node.mesh, world, {&node.weights, nullptr});
            !status.ok())
            return status;
    } else if (node.mesh >= 0) {
        absl::StatusOr<std::vector<Transform>> instances = GltfGpuInstances(model_, node);
        if (!instances.ok()) return Error(element, std::string(instances.status().message()));
        if (instances->empty()) instances->push_back(Transform{});
        for (const Transform& instance : *instances)
            if (absl::Status status = AddMesh(node.mesh, world * instance); !status.ok())
                return status;
    }
    if (node.camera >= 0) {
        const std::string camera_name = node.camera < static_cast<int>(model_.cameras.size())
                                            ? model_.cameras[node.camera].name
                                            : "";
        cameras_seen_.push_back(absl::StrCat(cameras_seen_.size(), " '",
                                             node.name.empty() ? camera_name : node.name, "'"));
        if (!has_camera_ && WantedCamera({node.name, camera_name})) {
            if (absl::Status status =
                    SetGltfCamera(model_, node.camera, world, path_, &scene_.camera);
                !status.ok())
                return status;
            has_camera_ = true;
        }
    }
    if (const tinygltf::Value* light = Extension(node.extensions, "KHR_lights_punctual")) {
        absl::StatusOr<PunctualLight> placed = GltfPunctualLight(
            model_, static_cast<int>(NumberOr(*light, "light", -1)), world, path_);
        if (!placed.ok()) return placed.status();
        scene_.lights.push_back(std::move(*placed));
    }
    for (int child : node.children)
        if (absl::Status status = VisitNode(child, world, depth + 1); !status.ok()) return status;
    return absl::OkStatus();
}

absl::Status GltfSceneBuilder::AddMesh(int mesh_index, const Transform& world) {
    const tinygltf::Mesh& mesh = model_.meshes[mesh_index];
    const GltfPose rigid{&mesh.weights, nullptr};
    if (mesh_uses_[mesh_index] < 2) return AddPlacedMesh(mesh_index, world, rigid);
    // A mesh that several nodes use is stored once, as a prototype each node places by an
    // instance; its emitting primitives are lights, placed as world triangles by every node.
    const std::string name = Describe("mesh", mesh_index, mesh.name);
    auto [prototype, first] = mesh_prototypes_.try_emplace(mesh_index, 0);
    if (first) {
        absl::StatusOr<MeshRead> read = ReadMesh(mesh_index, rigid);
        if (!read.ok()) return read.status();
        prototype->second = BeginPrototype(&scene_);
        std::vector<std::pair<TriangleMesh, uint32_t>>& emitting = emitting_[mesh_index];
        for (size_t p = 0; p < read->primitives.size(); ++p) {
            if (!read->primitives[p]) continue;
            absl::StatusOr<uint32_t> material =
                PrimitiveMaterial(mesh.primitives[p], *read->primitives[p], read->closed);
            if (!material.ok()) return material.status();
            if (scene_.materials[*material].IsEmissive()) {
                emitting.emplace_back(std::move(*read->primitives[p]), *material);
                continue;
            }
            if (absl::Status status =
                    AppendPrimitive(*read->primitives[p], absl::StrCat(name, " primitive ", p),
                                    Transform{}, *material, prototype->second);
                !status.ok())
                return status;
        }
    }
    for (const auto& [primitive, material] : emitting_[mesh_index])
        if (absl::Status status = AppendPrimitive(primitive, absl::StrCat(name, " (emitting)"),
                                                  world, material, std::nullopt);
            !status.ok())
            return status;
    return AddInstance(prototype->second, world, limits_, absl::StrCat(path_, ": ", name), &scene_);
}

absl::Status GltfSceneBuilder::AddPlacedMesh(int mesh_index, const Transform& world,
                                             const GltfPose& pose) {
    const tinygltf::Mesh& mesh = model_.meshes[mesh_index];
    absl::StatusOr<MeshRead> read = ReadMesh(mesh_index, pose);
    if (!read.ok()) return read.status();
    // A skinned mesh's vertices are in the world already.
    const Transform placement = pose.joints != nullptr ? Transform{} : world;
    for (size_t p = 0; p < read->primitives.size(); ++p) {
        if (!read->primitives[p]) continue;
        absl::StatusOr<uint32_t> material =
            PrimitiveMaterial(mesh.primitives[p], *read->primitives[p], read->closed);
        if (!material.ok()) return material.status();
        if (absl::Status status = AppendPrimitive(
                *read->primitives[p],
                absl::StrCat(Describe("mesh", mesh_index, mesh.name), " primitive ", p), placement,
                *material, std::nullopt);
            !status.ok())
            return status;
    }
    return absl::OkStatus();
}

absl::StatusOr<GltfSceneBuilder::MeshRead> GltfSceneBuilder::ReadMesh(int mesh_index,
                                                                      const GltfPose& pose) {
    const tinygltf::Mesh& mesh = model_.meshes[mesh_index];
    MeshRead read;
    std::vector<const TriangleMesh*> parts;
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
        absl::StatusOr<std::optional<TriangleMesh>> primitive = ReadGltfPrimitive(
            model_, mesh.primitives[p], pose, limits_.max_triangles,
            absl::StrCat(path_, ": ", Describe("mesh", mesh_index, mesh.name), " primitive ", p));
        if (!primitive.ok()) return primitive.status();
        read.primitives.push_back(std::move(*primitive));
    }
    for (const std::optional<TriangleMesh>& primitive : read.primitives)
        if (primitive) parts.push_back(&*primitive);
    // Only where some primitive is single-sided does it matter whether they close a surface.
    const bool single_sided = std::any_of(
        mesh.primitives.begin(), mesh.primitives.end(), [&](const tinygltf::Primitive& p) {
            return p.material < 0 || p.material >= static_cast<int>(model_.materials.size()) ||
                   !model_.materials[p.material].doubleSided;
        });
    read.closed = single_sided && IsClosedSurface(parts);
    return read;
}

absl::StatusOr<uint32_t> GltfSceneBuilder::PrimitiveMaterial(const tinygltf::Primitive& primitive,
                                                             const TriangleMesh& mesh,
                                                             bool closed) {
    absl::StatusOr<uint32_t> material = MaterialIndex(primitive.material);
    if (!material.ok()) return material;
    const bool given =
        primitive.material >= 0 && primitive.material < static_cast<int>(model_.materials.size());
    // glTF's default material is single-sided and opaque.
    const bool double_sided = given && model_.materials[primitive.material].doubleSided;
    const std::string alpha_mode =
        given ? model_.materials[primitive.material].alphaMode : "OPAQUE";
    const double cutoff = given ? model_.materials[primitive.material].alphaCutoff : 0.5;
    uint32_t flags = 0;
    // A viewer shows nothing of a single-sided surface from behind; a closed one is never seen
    // from behind, glass must be crossed both ways, and a light's back stops rays as pbrt's
    // area lights do (a light on a ceiling must not let photons through the 0.1 mm gap behind
    // it), so they stay as they are.
    const std::function<bool(uint32_t)> transmits = [&](uint32_t m) {
        const Material& at = scene_.materials[m];
        if (at.type == MaterialType::kMix)
            return transmits(at.mix_first) || transmits(at.mix_second);
        return at.type == MaterialType::kDielectric || at.type == MaterialType::kThinDielectric ||
               at.type == MaterialType::kRoughDielectric || at.IsTranslucent();
    };
    if (!double_sided && !closed && !transmits(*material) &&
        !scene_.materials[*material].IsEmissive())
        flags |= gpu::kSurfaceSingleSided;
    const bool vertex_alpha = std::any_of(mesh.colors.begin(), mesh.colors.end(),
                                          [](const VertexColor& c) { return c.alpha < 1.0f; });
    if (vertex_alpha && (alpha_mode == "BLEND" || (alpha_mode == "MASK" && cutoff > 0)))
        flags |= gpu::kSurfaceVertexAlpha;
    return Variant(*material, flags);
}

uint32_t GltfSceneBuilder::Variant(uint32_t material, uint32_t flags) {
    if ((scene_.materials[material].surface_flags | flags) ==
        scene_.materials[material].surface_flags)
        return material;
    const auto [it, made] = variants_.try_emplace({material, flags}, 0);
    if (!made) return it->second;
    Material variant = scene_.materials[material];
    variant.surface_flags |= flags;
    scene_.materials.push_back(variant);
    it->second = static_cast<uint32_t>(scene_.materials.size() - 1);
    material_uvs_[it->second] = material_uvs_[material];
    return it->second;
}

absl::Status GltfSceneBuilder::AppendPrimitive(const TriangleMesh& mesh, const std::string& element,
                                               const Transform& world, uint32_t material,
                                               std::optional<uint32_t> prototype) {
    const MeshPlacement placement{world, material, FrontFace::kObjectWinding, false,
                                  material_uvs_[material]};
    return AppendMesh(mesh, placement, limits_, absl::StrCat(path_, ": ", element), &scene_,
                      prototype);
}

// The materials of glTF material `gltf_material` (gltf_materials.h; -1: glTF's default
// material), and the transform of the texture coordinates its surfaces carry.
absl::StatusOr<uint32_t> GltfSceneBuilder::MaterialIndex(int gltf_material) {
    if (const auto it = material_indices_.find(gltf_material); it != material_indices_.end())
        return it->second;
    uint32_t index = 0;
    UvTransform uv;
    if (gltf_material < 0) {
        // glTF's default material: every property at its default (white rough metal).
        const absl::StatusOr<uint32_t> added =
            AddGltfMaterial(tinygltf::Material(), absl::StrCat(path_, ": the default material"),
                            textures_.Access("the default material"), scene_.materials);
        if (!added.ok()) return added.status();
        index = *added;
    } else {
        if (gltf_material >= static_cast<int>(model_.materials.size()))
            return Error(absl::StrCat("material #", gltf_material), "does not exist");
        const tinygltf::Material& source = model_.materials[gltf_material];
        const std::string element = Describe("material", gltf_material, source.name);
        // One set of coordinates per vertex, the base colour texture's where it has one: the
        // other textures are read with them.
        if (const tinygltf::TextureInfo* coordinates = CoordinateTexture(source)) {
            const tinygltf::Value* transform =
                Extension(coordinates->extensions, "KHR_texture_transform");
            if (transform) uv = TextureTransform(*transform);
            for (const auto& [other, name] :
                 {std::pair{&source.emissiveTexture, "emissive texture"},
                  std::pair{&source.pbrMetallicRoughness.metallicRoughnessTexture,
                            source.extensions.contains("KHR_materials_pbrSpecularGlossiness")
                                ? "specular-glossiness texture"
                                : "metallic-roughness texture"}})
                if (coordinates != other && other->index >= 0 &&
                    (other->texCoord != coordinates->texCoord ||
                     Extension(other->extensions, "KHR_texture_transform") != nullptr ||
                     transform != nullptr))
                    spdlog::warn(
                        "{}: {}: the {} is read with the coordinates of the material's first "
                        "texture (texCoord {}, its KHR_texture_transform)",
                        path_, element, name, coordinates->texCoord);
        }
        const tinygltf::NormalTextureInfo& normal = source.normalTexture;
        const tinygltf::Value* normal_transform =
            Extension(normal.extensions, "KHR_texture_transform");
        if (normal.index >= 0 && CoordinateTexture(source) == nullptr) {
            if (normal_transform) uv = TextureTransform(*normal_transform);
        } else if (normal.index >= 0 &&
                   (normal.texCoord != CoordinateSet(source) || normal_transform != nullptr)) {
            spdlog::warn(
                "{}: {}: the normal texture is read with the coordinates of the material's "
                "first texture (texCoord {}, its KHR_texture_transform)",
                path_, element, CoordinateSet(source));
        }
        const absl::StatusOr<uint32_t> added =
            AddGltfMaterial(source, absl::StrCat(path_, ": ", element), textures_.Access(element),
                            scene_.materials);
        if (!added.ok()) return added.status();
        index = *added;
    }
    material_indices_[gltf_material] = index;
    material_uvs_[index] = uv;
    return index;
}

}  // namespace

absl::StatusOr<Scene> LoadGltf(const SceneBundle& bundle, const std::string& name,
                               const SceneLimits& limits, const std::string& camera) {
    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks(BundleFsCallbacks(bundle));
    GltfImages images;
    loader.SetImageLoader(KeepEncodedImage, &images);
    tinygltf::Model model;
    std::string error, warning;
    const bool binary = absl::EndsWithIgnoreCase(bundle.main_file, ".glb");
    absl::StatusOr<std::string> decoded = DecodeMeshoptBuffers(
        bundle.files.at(bundle.main_file), binary, BundleFolder(bundle.main_file),
        [&bundle](const std::string& path) { return ReadBundleFile(bundle, path); });
    if (!decoded.ok())
        return absl::Status(decoded.status().code(),
                            absl::StrCat(name, ": ", decoded.status().message()));
    const std::string main = WithoutDracoIndices(*decoded, binary);
    const std::string::size_type slash = bundle.main_file.rfind('/');
    const std::string base_dir =
        slash == std::string::npos ? "" : bundle.main_file.substr(0, slash);
    const bool loaded =
        binary ? loader.LoadBinaryFromMemory(&model, &error, &warning,
                                             reinterpret_cast<const unsigned char*>(main.data()),
                                             static_cast<unsigned int>(main.size()), base_dir)
               : loader.LoadASCIIFromString(&model, &error, &warning, main.data(),
                                            static_cast<unsigned int>(main.size()), base_dir);
    // tinygltf reads buffers and images itself, and warns of an image it does not find: the
    // files a bundle leaves out on purpose (no material reads them: PackSceneBundle), and the
    // KTX2 images of KHR_texture_basisu beside their fallbacks. An image a material does read
    // and that is missing is refused where it is read, naming it (GltfTextureReader); the
    // warnings are tinygltf's others.
    for (size_t begin = 0; begin < warning.size();) {
        const size_t end = std::min(warning.find('\n', begin), warning.size());
        const std::string line = warning.substr(begin, end - begin);
        if (!line.empty() && !absl::StartsWith(line, "File not found") &&
            !absl::StartsWith(line, "Failed to load external 'uri' for image"))
            spdlog::warn("{}: {}", name, line);
        begin = end + 1;
    }
    if (!loaded) {
        const std::string first_line = error.substr(0, error.find('\n'));
        return absl::InvalidArgumentError(absl::StrCat(
            name, ": not a valid glTF file: ", first_line.empty() ? "parse failed" : first_line));
    }
    PrepareSpecularGlossiness(&model);
    return GltfSceneBuilder(name, model, limits, images, camera).Build();
}

}  // namespace pf
