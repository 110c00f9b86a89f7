// Writes small glTF scenes for tests: a list of triangles with one material each, optional
// camera and lights, as .gltf (JSON with an embedded buffer) or .glb.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/math/vec3.h"

namespace pf::testing {

struct TestMaterial {
    Rgb base_color{0.5f};
    Rgb emission{0.0f};
    std::string texture_png_base64;  // a base colour texture, embedded as a data URI
    std::string texture_extra;       // raw JSON fields of its textureInfo, e.g. an extension
    std::string texture_sampler;     // raw JSON of its texture's sampler, e.g. {"wrapS":33071}
    bool texture_emissive = false;   // the texture is the emissive one, not the base colour's
    bool texture_metallic_roughness = false;  // it is the metallicRoughnessTexture
    float metallic = 0, roughness = 1;        // metallicFactor, roughnessFactor
    std::string normal_png_base64;            // a normalTexture, embedded as a data URI
    float normal_scale = 1;                   // its scale
    std::string extra;               // raw JSON fields of the material, e.g. ,"doubleSided":true
    bool metallic_roughness = true;  // write pbrMetallicRoughness (its factors, its texture)
    // Raw JSON members of its "extensions" object: by default a specular layer of weight 0,
    // which makes glTF's dielectric BRDF Lambertian (gltf_materials.h).
    std::string extensions = R"("KHR_materials_specular":{"specularFactor":0})";
};

struct TestMesh {
    std::vector<Vec3> positions;  // three per triangle
    int material = 0;
    std::vector<float> uvs;  // TEXCOORD_0, two per position, or empty
    // COLOR_0, `color_components` (3 or 4) a position: floats, or normalised unsigned integers
    // of `color_bytes` (1 or 2) each; empty for none.
    std::vector<float> colors;
    std::vector<uint16_t> colors_unorm;
    int color_components = 4, color_bytes = 1;
    std::string attributes_extra;  // raw JSON members of its attributes, e.g. ,"JOINTS_0":0
    std::string primitive_extra;   // raw JSON members of its primitive, e.g. ,"mode":5
    std::string mesh_extra;        // raw JSON members of its mesh, e.g. ,"weights":[0.5]
    std::string node_extra;        // raw JSON members of its node, e.g. ,"skin":0
};

// An accessor over bytes of its own (a buffer view made for it), for what TestMesh does not
// write: `fields` are its JSON members but the buffer view, e.g.
// R"("componentType":5126,"count":2,"type":"MAT4")".
struct TestAccessor {
    std::string bytes;
    std::string fields;
};

struct TestScene {
    std::vector<TestMaterial> materials{TestMaterial{}};
    std::vector<TestMesh> meshes;
    bool camera = true;
    Vec3 camera_position{0, 0, 3};               // looking down -z
    std::string camera_extra;                    // raw JSON fields appended to the camera node
    std::vector<std::string> lights;             // raw KHR_lights_punctual light objects
    std::vector<std::string> light_node_fields;  // raw JSON fields of each light's node, e.g.
                                                 // R"(,"translation":[0,0,1])"; none: at the origin
    bool images_in_buffer = false;  // textures in the buffer (a .glb's binary chunk), not data URIs
    std::vector<std::string> extra_nodes;  // raw node objects added to the scene, e.g. instances
    // Images, each with a texture of its own, before the materials' own: the i-th is texture #i.
    std::vector<std::string> images_png_base64;
    // Accessors written before the meshes' own: the i-th is accessor #i.
    std::vector<TestAccessor> accessors;
    std::string extra;  // raw top-level JSON members, e.g. ,"skins":[...]
};

// A unit quad in the z = 0 plane facing +z, lit by an emissive quad above it.
TestScene LitQuadScene();

// Serialises the scene; returns the file's path under this process's own temporary folder
// (test_env.h's TempPath: tests running side by side never write the same file).
std::string WriteGltf(const TestScene& scene, const std::string& name);
std::string WriteGlb(const TestScene& scene, const std::string& name);
// The bytes of `values`, as a buffer holds them.
template <typename T>
std::string Bytes(const std::vector<T>& values) {
    return std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

// The JSON text alone (with the buffer as a data URI), for tests that corrupt it.
std::string GltfJson(const TestScene& scene);
// Writes text to a file of that name in this process's temporary folder; returns its path.
std::string WriteTextFile(const std::string& text, const std::string& name);

}  // namespace pf::testing
