// libFuzzer target for a scene parser: the input is a scene's main file, loaded from a bundle
// that also holds a small valid PLY mesh, PNG image and spectrum it may reference (mesh.ply,
// image.png, spectrum.spd), under limits small enough that a few bytes cannot ask for
// gigabytes. Any outcome but a crash, a sanitizer report or a leak is fine: bad input must
// come back as an error. A scene that loads is also expanded as a backend without instancing
// would.
// PF_FUZZ_MAIN_FILE (scene.pbrt or scene.gltf) picks the parser.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/scene/mesh_builder.h"
#include "core/scene_io/scene_loader.h"
#include "tests/support/ply_fixture.h"

namespace {

const pf::SceneBundle& Fixtures() {
    static const pf::SceneBundle* bundle = [] {
        auto* b = new pf::SceneBundle;
        // A binary PLY triangle and a 1x1 PNG (white), the smallest of each.
        b->files["mesh.ply"] = pf::testing::TrianglePly();
        static const unsigned char kPng[] = {
            0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48,
            0x44, 0x52, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x02, 0x00, 0x00,
            0x00, 0x90, 0x77, 0x53, 0xde, 0x00, 0x00, 0x00, 0x0c, 0x49, 0x44, 0x41, 0x54, 0x78,
            0x9c, 0x63, 0xf8, 0xff, 0xff, 0x3f, 0x00, 0x05, 0xfe, 0x02, 0xfe, 0x0d, 0xef, 0x46,
            0xb8, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
        b->files["image.png"] = std::string(reinterpret_cast<const char*>(kPng), sizeof kPng);
        b->files["spectrum.spd"] = "380 0.2\n580 0.7\n780 0.4\n";
        return b;
    }();
    return *bundle;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    pf::SceneBundle bundle = Fixtures();
    bundle.main_file = PF_FUZZ_MAIN_FILE;
    bundle.files[bundle.main_file] = std::string(reinterpret_cast<const char*>(data), size);
    pf::SceneLoadOptions options;
    options.limits.max_triangles = 1u << 18;
    options.limits.max_image_pixels = 1u << 16;
    options.limits.max_include_depth = 8;
    options.limits.max_instances = 1u << 12;
    const absl::StatusOr<pf::Scene> scene = pf::LoadScene(bundle, bundle.main_file, options);
    // What a backend without instancing does with the scene (the Vulkan backend expands it).
    if (scene.ok()) (void)pf::FlattenInstances(*scene, options.limits.max_triangles);
    return 0;
}
