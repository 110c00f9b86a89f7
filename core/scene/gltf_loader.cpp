// glTF 2.0 loading: node hierarchy, triangle meshes, the camera, KHR_lights_punctual and the
// materials (gltf_materials.h).
#include "core/scene/gltf_loader.h"

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
#include "core/scene/gltf_accessors.h"
#include "core/scene/gltf_bundle_files.h"
#include "core/scene/gltf_draco.h"
#include "core/scene/gltf_materials.h"
#include "core/scene/gltf_meshopt.h"
#include "core/scene/image_decode.h"
#include "core/scene/scene_bundle.h"
#include "core/scene/scene_files.h"

namespace pf {
namespace {

// Luminous efficacy of KHR_lights_punctual's photometric intensities (the maximum, at 555 nm).
constexpr double kLumensPerWatt = 683.0;
constexpr int kMaxNodeDepth = 256;

std::string Describe(const std::string& kind, int index, const std::string& name) {
    return name.empty() ? absl::StrCat(kind, " #", index)
                        : absl::StrCat(kind, " '", name, "' (#", index, ")");
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
        : path_(path), model_(model), wanted_camera_(camera), limits_(limits), images_(images) {
        scene_.source = path;
    }

    absl::StatusOr<Scene> Build();

private:
    absl::Status Error(const std::string& element, const std::string& what) const {
        return absl::InvalidArgumentError(absl::StrCat(path_, ": ", element, ": ", what));
    }
    absl::Status VisitNode(int index, const Transform& parent, int depth);
    absl::Status AddMesh(int mesh_index, const Transform& world);
    absl::StatusOr<TriangleMesh> ReadPrimitive(const tinygltf::Primitive& primitive,
                                               const std::string& element) const;
    absl::Status AddPrimitive(int mesh_index, size_t primitive_index, const std::string& element,
                              const Transform& world, uint32_t material,
                              std::optional<uint32_t> prototype);
    absl::Status AddLight(int light_index, const Transform& world);
    absl::Status SetCamera(int camera_index, const Transform& world);
    // Whether the camera node met now (the cameras_seen_.size()-th, named `names`) is the
    // one asked for.
    bool WantedCamera(const std::vector<std::string>& names) const;
    void FrameBounds();
    absl::StatusOr<uint32_t> MaterialIndex(int gltf_material);
    // The metallic-roughness materials of a glTF material without transmission, whose
    // common parts (base colour, emission, alpha) `material` holds: returns the one its
    // surfaces use (a mix where metallic or clearcoat lies between 0 and 1).
    absl::StatusOr<uint32_t> MetallicRoughness(const tinygltf::Material& source,
                                               const std::string& element, Material material);
    // Scene::textures' index of glTF texture `gltf_texture` decoded with `options` (by
    // default, glTF's colour: sRGB, alpha ignored).
    absl::StatusOr<int32_t> TextureIndex(int gltf_texture, const std::string& element,
                                         ImageDecodeOptions options = SrgbColour());
    static ImageDecodeOptions SrgbColour() {
        ImageDecodeOptions options;
        options.encoding = ImageEncoding::kSrgb;
        return options;
    }
    uint32_t AddMaterial(const Material& material) {
        scene_.materials.push_back(material);
        return static_cast<uint32_t>(scene_.materials.size() - 1);
    }

    const std::string& path_;
    const tinygltf::Model& model_;
    Scene scene_;
    bool has_camera_ = false;
    const std::string& wanted_camera_;          // LoadGltf's `camera`
    std::vector<std::string> cameras_seen_;     // "#index 'name'" of each camera node met
    std::map<int, uint32_t> material_indices_;  // glTF material -> Scene::materials
    // (glTF image, how it is decoded) -> Scene::textures
    std::map<std::pair<int, ImageDecodeOptions>, int32_t> texture_indices_;
    std::map<uint32_t, UvTransform> material_uvs_;  // Scene::materials -> its texture's transform
    std::map<std::pair<int, size_t>, TriangleMesh>
        meshes_;                    // (mesh, primitive) emitting in several nodes
    std::map<int, int> mesh_uses_;  // glTF mesh -> how many nodes name it
    std::map<int, uint32_t>
        mesh_prototypes_;  // glTF mesh used by several nodes -> Scene::prototypes
    const SceneLimits& limits_;
    const GltfImages& images_;
};

absl::StatusOr<Scene> GltfSceneBuilder::Build() {
    // A required extension changes what the file means: one not read here is refused, as the
    // glTF specification asks, rather than rendered wrong.
    static const std::set<std::string> kSupported = {
        "KHR_lights_punctual",        "KHR_materials_emissive_strength",
        "KHR_texture_transform",      "KHR_materials_transmission",
        "KHR_materials_ior",          "KHR_materials_volume",
        "KHR_materials_specular",     "KHR_materials_clearcoat",
        "KHR_materials_sheen",        "KHR_mesh_quantization",
        "KHR_draco_mesh_compression", "EXT_meshopt_compression",
        "KHR_meshopt_compression"};
    for (const std::string& extension : model_.extensionsRequired)
        if (!kSupported.contains(extension))
            return Error("extensionsRequired",
                         absl::StrCat("'", extension,
                                      "' is not supported (a sample model's glTF/ variant "
                                      "usually does without it)"));
    std::vector<int> roots;
    if (!model_.scenes.empty()) {
        const int scene_index = model_.defaultScene >= 0 ? model_.defaultScene : 0;
        if (scene_index >= static_cast<int>(model_.scenes.size()))
            return Error("scene", absl::StrCat("default scene #", scene_index, " does not exist"));
        roots = model_.scenes[scene_index].nodes;
    } else {
        for (int i = 0; i < static_cast<int>(model_.nodes.size()); ++i) roots.push_back(i);
    }
    for (const tinygltf::Node& node : model_.nodes)
        if (node.mesh >= 0) ++mesh_uses_[node.mesh];
    for (int root : roots)
        if (absl::Status status = VisitNode(root, Transform{}, 0); !status.ok()) return status;
    FinishInstancing(&scene_);
    if (scene_.triangles.empty()) return Error("scene", "has no triangles");
    if (!has_camera_ && !wanted_camera_.empty())
        return Error("--camera " + wanted_camera_,
                     cameras_seen_.empty() ? "the scene has no camera"
                                           : absl::StrCat("no such camera; the scene has ",
                                                          absl::StrJoin(cameras_seen_, ", ")));
    if (!has_camera_) FrameBounds();
    return std::move(scene_);
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
    if (node.mesh >= 0)
        if (absl::Status status = AddMesh(node.mesh, world); !status.ok()) return status;
    if (node.camera >= 0) {
        const std::string camera_name = node.camera < static_cast<int>(model_.cameras.size())
                                            ? model_.cameras[node.camera].name
                                            : "";
        cameras_seen_.push_back(absl::StrCat(cameras_seen_.size(), " '",
                                             node.name.empty() ? camera_name : node.name, "'"));
        if (!has_camera_ && WantedCamera({node.name, camera_name}))
            if (absl::Status status = SetCamera(node.camera, world); !status.ok()) return status;
    }
    if (const tinygltf::Value* light = Extension(node.extensions, "KHR_lights_punctual"))
        if (absl::Status status = AddLight(static_cast<int>(NumberOr(*light, "light", -1)), world);
            !status.ok())
            return status;
    for (int child : node.children)
        if (absl::Status status = VisitNode(child, world, depth + 1); !status.ok()) return status;
    return absl::OkStatus();
}

absl::Status GltfSceneBuilder::AddMesh(int mesh_index, const Transform& world) {
    if (mesh_index >= static_cast<int>(model_.meshes.size()))
        return Error(absl::StrCat("mesh #", mesh_index), "does not exist");
    const tinygltf::Mesh& mesh = model_.meshes[mesh_index];
    const std::string name = Describe("mesh", mesh_index, mesh.name);
    // Adds the primitives that emit (or, with false, those that do not; with nullopt, all).
    const auto add_primitives = [&](std::optional<bool> emitting, const Transform& placement,
                                    std::optional<uint32_t> prototype) {
        for (size_t p = 0; p < mesh.primitives.size(); ++p) {
            absl::StatusOr<uint32_t> material = MaterialIndex(mesh.primitives[p].material);
            if (!material.ok()) return material.status();
            if (emitting && scene_.materials[*material].IsEmissive() != *emitting) continue;
            if (absl::Status status =
                    AddPrimitive(mesh_index, p, absl::StrCat(name, " primitive ", p), placement,
                                 *material, prototype);
                !status.ok())
                return status;
        }
        return absl::OkStatus();
    };
    // A mesh that several nodes use is stored once, as a prototype each node places by an
    // instance; its emitting primitives are lights, placed as world triangles by every node.
    if (mesh_uses_[mesh_index] < 2) return add_primitives(std::nullopt, world, std::nullopt);
    auto [prototype, first] = mesh_prototypes_.try_emplace(mesh_index, 0);
    if (first) {
        prototype->second = BeginPrototype(&scene_);
        if (absl::Status status = add_primitives(false, Transform{}, prototype->second);
            !status.ok())
            return status;
    }
    if (absl::Status status = add_primitives(true, world, std::nullopt); !status.ok())
        return status;
    return AddInstance(prototype->second, world, limits_, absl::StrCat(path_, ": ", name), &scene_);
}

absl::StatusOr<TriangleMesh> GltfSceneBuilder::ReadPrimitive(const tinygltf::Primitive& primitive,
                                                             const std::string& element) const {
    absl::StatusOr<TriangleMesh> mesh = ReadTriangles(model_, primitive, limits_.max_triangles);
    if (!mesh.ok()) return Error(element, std::string(mesh.status().message()));
    return mesh;
}

absl::Status GltfSceneBuilder::AddPrimitive(int mesh_index, size_t primitive_index,
                                            const std::string& element, const Transform& world,
                                            uint32_t material, std::optional<uint32_t> prototype) {
    const tinygltf::Primitive& primitive = model_.meshes[mesh_index].primitives[primitive_index];
    if (primitive.mode != TINYGLTF_MODE_TRIANGLES && primitive.mode != -1) {
        spdlog::warn("{}: {}: mode {} is not triangles; skipped", path_, element, primitive.mode);
        return absl::OkStatus();
    }
    const MeshPlacement placement{world, material, FrontFace::kObjectWinding, false,
                                  material_uvs_[material]};
    const std::string where = absl::StrCat(path_, ": ", element);
    if (mesh_uses_[mesh_index] < 2 || prototype) {  // placed once
        absl::StatusOr<TriangleMesh> mesh = ReadPrimitive(primitive, element);
        if (!mesh.ok()) return mesh.status();
        return AppendMesh(*mesh, placement, limits_, where, &scene_, prototype);
    }
    // An emitting primitive of a mesh that several nodes use is read once and placed by each.
    const auto key = std::make_pair(mesh_index, primitive_index);
    auto cached = meshes_.find(key);
    if (cached == meshes_.end()) {
        absl::StatusOr<TriangleMesh> mesh = ReadPrimitive(primitive, element);
        if (!mesh.ok()) return mesh.status();
        cached = meshes_.emplace(key, std::move(*mesh)).first;
    }
    return AppendMesh(cached->second, placement, limits_, where, &scene_, prototype);
}

absl::Status GltfSceneBuilder::AddLight(int light_index, const Transform& world) {
    if (light_index < 0 || light_index >= static_cast<int>(model_.lights.size()))
        return Error(absl::StrCat("KHR_lights_punctual light #", light_index), "does not exist");
    const tinygltf::Light& source = model_.lights[light_index];
    const std::string element = Describe("light", light_index, source.name);
    PunctualLight light;
    light.name = source.name;
    const Vec3d color = source.color.size() == 3
                            ? Vec3d(source.color[0], source.color[1], source.color[2])
                            : Vec3d(1.0);
    // KHR_lights_punctual's photometric units (candela for point and spot lights, lux for
    // directional ones) in watts, at 683 lm/W, the factor Blender's exporter multiplies watts by
    // (so its lights come back as they were made).
    light.intensity = Rgb(color * (source.intensity / kLumensPerWatt));
    if (!IsFinite(light.intensity) || MinComponent(light.intensity) < 0)
        return Error(element, "intensity or colour is negative, NaN or Inf");
    if (!(source.range >= 0 && std::isfinite(source.range)))
        return Error(element, "range must be finite and not negative");
    light.position = Vec3(world.ApplyPoint(Vec3d(0.0)));
    light.direction = Vec3(Normalize(world.ApplyVector(Vec3d(0, 0, -1))));
    if (!IsFinite(light.direction))
        return Error(element, "node transform collapses the light's direction");
    if (source.type == "point") {
        light.type = LightType::kPoint;
        light.range = static_cast<float>(source.range);
    } else if (source.type == "spot") {
        light.type = LightType::kSpot;
        light.range = static_cast<float>(source.range);
        light.cos_inner = static_cast<float>(std::cos(source.spot.innerConeAngle));
        light.cos_outer = static_cast<float>(std::cos(source.spot.outerConeAngle));
        if (!(source.spot.outerConeAngle > 0 && source.spot.outerConeAngle <= kPiD / 2 &&
              source.spot.innerConeAngle >= 0 &&
              source.spot.innerConeAngle < source.spot.outerConeAngle))
            return Error(element, "spot cone angles must satisfy 0 <= inner < outer <= pi/2");
    } else if (source.type == "directional") {
        light.type = LightType::kDirectional;
        if (source.range > 0)
            spdlog::warn("{}: {}: a directional light has no range; ignored", path_, element);
    } else {
        return Error(element, absl::StrCat("unknown light type '", source.type, "'"));
    }
    scene_.lights.push_back(light);
    return absl::OkStatus();
}

absl::Status GltfSceneBuilder::SetCamera(int camera_index, const Transform& world) {
    if (camera_index >= static_cast<int>(model_.cameras.size()))
        return Error(absl::StrCat("camera #", camera_index), "does not exist");
    const tinygltf::Camera& source = model_.cameras[camera_index];
    const std::string element = Describe("camera", camera_index, source.name);
    Camera& camera = scene_.camera;
    if (source.type == "orthographic") {
        // xmag and ymag: half the view's width and height, world units.
        const double xmag = source.orthographic.xmag, ymag = source.orthographic.ymag;
        if (!(xmag > 0 && ymag > 0 && xmag < 1e30 && ymag < 1e30))
            return Error(element, "orthographic xmag and ymag must be positive and finite");
        camera.projection = Projection::kOrthographic;
        camera.window = {static_cast<float>(-xmag), static_cast<float>(xmag),
                         static_cast<float>(-ymag), static_cast<float>(ymag)};
        camera.aspect_ratio = static_cast<float>(xmag / ymag);
    } else if (source.type == "perspective") {
        camera.y_fov = static_cast<float>(source.perspective.yfov);
        camera.aspect_ratio = static_cast<float>(source.perspective.aspectRatio);
        if (!(camera.y_fov > 0 && camera.y_fov < kPi))
            return Error(element, "yfov must lie in (0, pi)");
    } else {
        return Error(element, absl::StrCat("type '", source.type,
                                           "' is unknown (perspective or orthographic)"));
    }
    camera.position = Vec3(world.ApplyPoint(Vec3d(0.0)));
    camera.forward = Vec3(Normalize(world.ApplyVector(Vec3d(0, 0, -1))));
    const Vec3 up_hint(Normalize(world.ApplyVector(Vec3d(0, 1, 0))));
    camera.right = Normalize(Cross(camera.forward, up_hint));
    camera.up = Cross(camera.right, camera.forward);
    if (!IsFinite(camera.position) || !IsFinite(camera.right) || !IsFinite(camera.up))
        return Error(element, "node transform is degenerate");
    has_camera_ = true;
    return absl::OkStatus();
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
        const absl::StatusOr<uint32_t> added = AddGltfMaterial(
            tinygltf::Material(), absl::StrCat(path_, ": the default material"),
            [](int, const ImageDecodeOptions&) -> absl::StatusOr<int32_t> { return kNoTexture; },
            scene_.materials);
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
                            "metallic-roughness texture"}})
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
        const absl::StatusOr<uint32_t> added = AddGltfMaterial(
            source, absl::StrCat(path_, ": ", element),
            [&](int texture, const ImageDecodeOptions& options) {
                return TextureIndex(texture, element, options);
            },
            scene_.materials);
        if (!added.ok()) return added.status();
        index = *added;
    }
    material_indices_[gltf_material] = index;
    material_uvs_[index] = uv;
    return index;
}

absl::StatusOr<int32_t> GltfSceneBuilder::TextureIndex(int gltf_texture, const std::string& element,
                                                       ImageDecodeOptions options) {
    if (gltf_texture >= static_cast<int>(model_.textures.size()) ||
        model_.textures[gltf_texture].source < 0 ||
        model_.textures[gltf_texture].source >= static_cast<int>(model_.images.size()))
        return Error(element, absl::StrCat("texture #", gltf_texture, " has no image"));
    const int image_index = model_.textures[gltf_texture].source;
    // The sampler's wrap modes (its filters are the renderer's: bilinear, MIP levels).
    if (const int sampler = model_.textures[gltf_texture].sampler;
        sampler >= 0 && sampler < static_cast<int>(model_.samplers.size())) {
        const auto wrap = [](int mode) {
            return mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE     ? gpu::kWrapClamp
                   : mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT ? gpu::kWrapMirror
                                                                   : gpu::kWrapRepeat;
        };
        options.wrap_u = wrap(model_.samplers[sampler].wrapS);
        options.wrap_v = wrap(model_.samplers[sampler].wrapT);
    }
    if (const auto it = texture_indices_.find({image_index, options}); it != texture_indices_.end())
        return it->second;
    const auto encoded = images_.find(image_index);
    if (encoded == images_.end())
        return Error(element, absl::StrCat("image #", image_index, " has no data"));
    absl::StatusOr<Texture> texture =
        DecodeImage(encoded->second.bytes, encoded->second.name, limits_, options);
    if (!texture.ok())
        return absl::Status(texture.status().code(),
                            absl::StrCat(path_, ": ", element, ": ", texture.status().message()));
    // An alpha channel that is all 1 (or none) cuts nothing out: no texture, no cost.
    if (options.channels == ImageChannels::kAlpha &&
        std::all_of(texture->texels.begin(), texture->texels.end(),
                    [](const Rgb& texel) { return texel.x >= 1.0f; })) {
        texture_indices_[{image_index, options}] = kNoTexture;
        return kNoTexture;
    }
    const auto index = static_cast<int32_t>(scene_.textures.size());
    scene_.textures.push_back(std::make_shared<const Texture>(std::move(*texture)));
    texture_indices_[{image_index, options}] = index;
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
    // Image files a bundle leaves out (no material reads them; PackSceneBundle) are expected
    // missing; a base colour image that is missing is an error below.
    for (size_t begin = 0; begin < warning.size();) {
        const size_t end = std::min(warning.find('\n', begin), warning.size());
        const std::string line = warning.substr(begin, end - begin);
        if (!line.empty() && !absl::StartsWith(line, "File not found")) {
            spdlog::warn("{}: {}", name, line);
            break;
        }
        begin = end + 1;
    }
    if (!loaded) {
        const std::string first_line = error.substr(0, error.find('\n'));
        return absl::InvalidArgumentError(absl::StrCat(
            name, ": not a valid glTF file: ", first_line.empty() ? "parse failed" : first_line));
    }
    return GltfSceneBuilder(name, model, limits, images, camera).Build();
}

}  // namespace pf
