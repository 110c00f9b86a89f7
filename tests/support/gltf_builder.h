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
    std::string extra;  // raw JSON fields of the material, e.g. ,"doubleSided":true
    // Raw JSON members of its "extensions" object: by default a specular layer of weight 0,
    // which makes glTF's dielectric BRDF Lambertian (gltf_materials.h).
    std::string extensions = R"("KHR_materials_specular":{"specularFactor":0})";
};

struct TestMesh {
    std::vector<Vec3> positions;  // three per triangle
    int material = 0;
    std::vector<float> uvs;  // TEXCOORD_0, two per position, or empty
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
};

// A unit quad in the z = 0 plane facing +z, lit by an emissive quad above it.
TestScene LitQuadScene();

// Serialises the scene; returns the file's path under this process's own temporary folder
// (test_env.h's TempPath: tests running side by side never write the same file).
std::string WriteGltf(const TestScene& scene, const std::string& name);
std::string WriteGlb(const TestScene& scene, const std::string& name);
// The JSON text alone (with the buffer as a data URI), for tests that corrupt it.
std::string GltfJson(const TestScene& scene);
// Writes text to a file of that name in this process's temporary folder; returns its path.
std::string WriteTextFile(const std::string& text, const std::string& name);

}  // namespace pf::testing
