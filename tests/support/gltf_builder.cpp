// Minimal glTF writer for tests.
#include "tests/support/gltf_builder.h"

#include <cstring>
#include <fstream>

#include "absl/strings/escaping.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "tests/support/test_env.h"

namespace pf::testing {
namespace {

std::string Floats(const Vec3& v) { return absl::StrCat("[", v.x, ",", v.y, ",", v.z, "]"); }

// Builds the JSON with the buffer either as a data URI or (for .glb) as the binary chunk.
std::string Json(const TestScene& scene, bool embed, std::string* blob) {
    std::vector<std::string> meshes, nodes, accessors, views, materials, images;
    std::vector<std::string> image_samplers;  // each image's texture's sampler, or empty
    // Adds an image (and a texture of it, with `sampler`); returns its index.
    const auto add_image = [&](const std::string& png_base64, const std::string& sampler) {
        image_samplers.push_back(sampler);
        if (scene.images_in_buffer) {
            std::string png;
            absl::Base64Unescape(png_base64, &png);
            views.push_back(absl::StrCat(R"({"buffer":0,"byteOffset":)", blob->size(),
                                         R"(,"byteLength":)", png.size(), "}"));
            blob->append(png);
            while (blob->size() % 4) blob->push_back('\0');
            images.push_back(
                absl::StrCat(R"({"bufferView":)", views.size() - 1, R"(,"mimeType":"image/png"})"));
        } else {
            images.push_back(absl::StrCat(R"({"uri":"data:image/png;base64,)", png_base64, "\"}"));
        }
        return images.size() - 1;
    };
    for (const std::string& png : scene.images_png_base64) add_image(png, "");
    for (const TestMaterial& m : scene.materials) {
        std::string texture;
        if (!m.texture_png_base64.empty())
            texture = absl::StrCat(
                m.texture_emissive             ? R"(,"emissiveTexture":{"index":)"
                : m.texture_metallic_roughness ? R"(,"metallicRoughnessTexture":{"index":)"
                                               : R"(,"baseColorTexture":{"index":)",
                add_image(m.texture_png_base64, m.texture_sampler), m.texture_extra, "}");
        std::string normal;
        if (!m.normal_png_base64.empty())
            normal =
                absl::StrCat(R"(,"normalTexture":{"index":)", add_image(m.normal_png_base64, ""),
                             R"(,"scale":)", m.normal_scale, "}");
        std::string material =
            m.metallic_roughness
                ? absl::StrCat(R"({"pbrMetallicRoughness":{"baseColorFactor":[)", m.base_color.x,
                               ",", m.base_color.y, ",", m.base_color.z, R"(,1],"metallicFactor":)",
                               m.metallic, R"(,"roughnessFactor":)", m.roughness,
                               m.texture_emissive ? "" : texture, "}",
                               m.texture_emissive ? texture : "", normal)
                : absl::StrCat(R"({"name":"m")", normal);
        if (!IsBlack(m.emission))
            absl::StrAppend(&material, R"(,"emissiveFactor":)", Floats(m.emission));
        if (!m.extensions.empty())
            absl::StrAppend(&material, R"(,"extensions":{)", m.extensions, "}");
        materials.push_back(material + m.extra + "}");
    }
    // Appends `bytes` to the buffer in a view of their own; returns the view's index.
    const auto add_view = [&](const std::string& bytes) {
        const size_t offset = blob->size();
        blob->append(bytes);
        while (blob->size() % 4) blob->push_back('\0');
        views.push_back(absl::StrCat(R"({"buffer":0,"byteOffset":)", offset, R"(,"byteLength":)",
                                     bytes.size(), "}"));
        return views.size() - 1;
    };
    for (const TestAccessor& accessor : scene.accessors)
        accessors.push_back(
            absl::StrCat(R"({"bufferView":)", add_view(accessor.bytes), ",", accessor.fields, "}"));
    for (const TestMesh& mesh : scene.meshes) {
        const size_t offset = blob->size();
        blob->resize(offset + mesh.positions.size() * 12);
        std::memcpy(blob->data() + offset, mesh.positions.data(), mesh.positions.size() * 12);
        Vec3 lower(1e30f), upper(-1e30f);
        for (const Vec3& p : mesh.positions) lower = Min(lower, p), upper = Max(upper, p);
        views.push_back(absl::StrCat(R"({"buffer":0,"byteOffset":)", offset, R"(,"byteLength":)",
                                     mesh.positions.size() * 12, "}"));
        accessors.push_back(absl::StrCat(R"({"bufferView":)", views.size() - 1,
                                         R"(,"componentType":5126,"count":)", mesh.positions.size(),
                                         R"(,"type":"VEC3","min":)", Floats(lower), R"(,"max":)",
                                         Floats(upper), "}"));
        std::string attributes = absl::StrCat(R"("POSITION":)", accessors.size() - 1);
        if (!mesh.uvs.empty()) {
            const size_t uv_offset = blob->size();
            blob->resize(uv_offset + mesh.uvs.size() * 4);
            std::memcpy(blob->data() + uv_offset, mesh.uvs.data(), mesh.uvs.size() * 4);
            views.push_back(absl::StrCat(R"({"buffer":0,"byteOffset":)", uv_offset,
                                         R"(,"byteLength":)", mesh.uvs.size() * 4, "}"));
            accessors.push_back(absl::StrCat(R"({"bufferView":)", views.size() - 1,
                                             R"(,"componentType":5126,"count":)",
                                             mesh.uvs.size() / 2, R"(,"type":"VEC2"})"));
            absl::StrAppend(&attributes, R"(,"TEXCOORD_0":)", accessors.size() - 1);
        }
        const size_t vertices = mesh.positions.size();
        const std::string type = mesh.color_components == 3 ? "VEC3" : "VEC4";
        if (!mesh.colors.empty()) {
            accessors.push_back(absl::StrCat(R"({"bufferView":)", add_view(Bytes(mesh.colors)),
                                             R"(,"componentType":5126,"count":)", vertices,
                                             R"(,"type":")", type, "\"}"));
            absl::StrAppend(&attributes, R"(,"COLOR_0":)", accessors.size() - 1);
        }
        if (!mesh.colors_unorm.empty()) {
            std::string bytes;
            for (const uint16_t value : mesh.colors_unorm)
                bytes.append(reinterpret_cast<const char*>(&value), mesh.color_bytes);
            accessors.push_back(
                absl::StrCat(R"({"bufferView":)", add_view(bytes), R"(,"componentType":)",
                             mesh.color_bytes == 1 ? 5121 : 5123, R"(,"normalized":true,"count":)",
                             vertices, R"(,"type":")", type, "\"}"));
            absl::StrAppend(&attributes, R"(,"COLOR_0":)", accessors.size() - 1);
        }
        meshes.push_back(absl::StrCat(R"({"primitives":[{"attributes":{)", attributes,
                                      mesh.attributes_extra, R"(},"material":)", mesh.material,
                                      mesh.primitive_extra, "}]", mesh.mesh_extra, "}"));
        nodes.push_back(absl::StrCat(R"({"mesh":)", meshes.size() - 1, mesh.node_extra, "}"));
    }
    std::string cameras = "[]";
    if (scene.camera) {
        cameras = R"([{"type":"perspective","perspective":{"yfov":0.8,"znear":0.01}}])";
        nodes.push_back(absl::StrCat(R"({"camera":0,"translation":)", Floats(scene.camera_position),
                                     scene.camera_extra, "}"));
    }
    std::string extensions;
    if (!images.empty()) {
        std::vector<std::string> textures, samplers;
        for (size_t i = 0; i < images.size(); ++i) {
            std::string sampler;
            if (!image_samplers[i].empty()) {
                sampler = absl::StrCat(R"(,"sampler":)", samplers.size());
                samplers.push_back(image_samplers[i]);
            }
            textures.push_back(absl::StrCat(R"({"source":)", i, sampler, "}"));
        }
        extensions = absl::StrCat(R"(,"images":[)", absl::StrJoin(images, ","), R"(],"textures":[)",
                                  absl::StrJoin(textures, ","), "]");
        if (!samplers.empty())
            absl::StrAppend(&extensions, R"(,"samplers":[)", absl::StrJoin(samplers, ","), "]");
    }
    for (const std::string& node : scene.extra_nodes) nodes.push_back(node);
    for (size_t i = 0; i < scene.lights.size(); ++i)
        nodes.push_back(absl::StrCat(
            R"({"extensions":{"KHR_lights_punctual":{"light":)", i, "}}",
            i < scene.light_node_fields.size() ? scene.light_node_fields[i] : "", "}"));
    if (!scene.lights.empty())
        absl::StrAppend(&extensions, R"(,"extensions":{"KHR_lights_punctual":{"lights":[)",
                        absl::StrJoin(scene.lights, ","), "]}}");
    std::vector<std::string> roots;
    for (size_t i = 0; i < nodes.size(); ++i) roots.push_back(absl::StrCat(i));
    while (blob->size() % 4) blob->push_back('\0');
    const std::string uri = embed ? absl::StrCat(R"(,"uri":"data:application/octet-stream;base64,)",
                                                 absl::Base64Escape(*blob), "\"")
                                  : "";
    return absl::StrCat(R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[)",
                        absl::StrJoin(roots, ","), R"(]}],"nodes":[)", absl::StrJoin(nodes, ","),
                        R"(],"meshes":[)", absl::StrJoin(meshes, ","), R"(],"materials":[)",
                        absl::StrJoin(materials, ","), R"(],"accessors":[)",
                        absl::StrJoin(accessors, ","), R"(],"bufferViews":[)",
                        absl::StrJoin(views, ","), R"(],"buffers":[{"byteLength":)", blob->size(),
                        uri, R"(}],"cameras":)", cameras, extensions, scene.extra, "}");
}

void AppendU32(std::string* out, uint32_t v) { out->append(reinterpret_cast<const char*>(&v), 4); }

}  // namespace

TestScene LitQuadScene() {
    TestScene scene;
    scene.materials = {TestMaterial{Rgb(0.5f), Rgb(0.0f)}, TestMaterial{Rgb(0.0f), Rgb(10.0f)}};
    scene.meshes.push_back(
        {{{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, -1, 0}, {1, 1, 0}, {-1, 1, 0}}, 0});
    // The light faces -z (down onto the quad): wound clockwise seen from +z.
    scene.meshes.push_back({{{-0.2f, -0.2f, 1},
                             {0.2f, 0.2f, 1},
                             {0.2f, -0.2f, 1},
                             {-0.2f, -0.2f, 1},
                             {-0.2f, 0.2f, 1},
                             {0.2f, 0.2f, 1}},
                            1});
    return scene;
}

std::string GltfJson(const TestScene& scene) {
    std::string blob;
    return Json(scene, true, &blob);
}

std::string WriteTextFile(const std::string& text, const std::string& name) {
    const std::string path = TempPath(name);
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

std::string WriteGltf(const TestScene& scene, const std::string& name) {
    return WriteTextFile(GltfJson(scene), name);
}

std::string WriteGlb(const TestScene& scene, const std::string& name) {
    std::string blob;
    std::string json = Json(scene, false, &blob);
    while (json.size() % 4) json.push_back(' ');
    std::string out = "glTF";
    AppendU32(&out, 2);
    AppendU32(&out, static_cast<uint32_t>(12 + 8 + json.size() + 8 + blob.size()));
    AppendU32(&out, static_cast<uint32_t>(json.size()));
    AppendU32(&out, 0x4E4F534A);  // JSON
    out += json;
    AppendU32(&out, static_cast<uint32_t>(blob.size()));
    AppendU32(&out, 0x004E4942);  // BIN
    out += blob;
    return WriteTextFile(out, name);
}

}  // namespace pf::testing
