// What a worker fetches and does before its first batch, before and after prepared scenes:
// the scene bundle's bytes and the time to parse it (the worker's old start-up), against the
// prepared scene's bytes and the time to decode it. Shipped scenes, and textured glTFs made
// here (a photograph-like texture: smooth gradients with fine grain, 8-bit sRGB PNG).
// Usage: scene_transfer [SCENE...]   (none: the shipped scenes and textured ones)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "absl/strings/escaping.h"
#include "core/film/png_writer.h"
#include "core/scene_io/scene_files.h"
#include "core/scene_io/scene_loader.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/test_env.h"
#include "wire/blob_codec.h"
#include "wire/proto_convert.h"

namespace {

double Seconds(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A size x size PNG, base64: smooth colour gradients with fine grain (8-bit sRGB).
std::string TexturePng(int size) {
    pf::Image image;
    image.width = image.height = size;
    image.pixels.resize(size_t(size) * size);
    uint32_t state = 12345;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            state = state * 1664525u + 1013904223u;
            const float grain = float(state >> 24) / 255.0f - 0.5f;
            const float u = float(x) / size, v = float(y) / size;
            image.pixels[size_t(y) * size + x] =
                pf::Rgb(0.5f + 0.4f * std::sin(6 * u + 2 * v),
                        0.5f + 0.4f * std::cos(5 * v - 3 * u), 0.4f + 0.3f * std::sin(9 * u * v)) +
                pf::Rgb(0.06f * grain);
        }
    const std::string path = pf::testing::TempPath("scene-transfer.png");
    if (!pf::WritePng(path, image).ok()) return "";
    return absl::Base64Escape(*pf::ReadWholeFile(path));
}

std::string TexturedScene(int size) {
    pf::testing::TestScene scene = pf::testing::LitQuadScene();
    scene.materials[0].texture_png_base64 = TexturePng(size);
    scene.meshes[0].uvs = {0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1};
    return pf::testing::WriteGltf(scene, "textured-" + std::to_string(size) + ".gltf");
}

void Measure(const std::string& path, const std::string& label) {
    const absl::StatusOr<pf::SceneBundle> bundle = pf::PackSceneBundle(path);
    if (!bundle.ok()) {
        std::printf("%-28s %s\n", label.c_str(), std::string(bundle.status().message()).c_str());
        return;
    }
    const std::string bundle_bytes = pf::ToProto(*bundle).SerializeAsString();
    // Before: the worker parsed the bundle (texture filter too, as for sppm, path and pm).
    auto start = std::chrono::steady_clock::now();
    const absl::StatusOr<pf::Scene> parsed = pf::LoadScene(*bundle, bundle->main_file);
    const double parse_seconds = Seconds(start);
    if (!parsed.ok()) return;
    start = std::chrono::steady_clock::now();
    const std::string blob = pf::EncodeSceneBlob(*parsed);
    const double encode_seconds = Seconds(start);
    // After: it decodes the prepared scene.
    start = std::chrono::steady_clock::now();
    const absl::StatusOr<pf::Scene> decoded = pf::DecodeSceneBlob(blob, true);
    const double decode_seconds = Seconds(start);
    std::printf("%-28s %12zu %12zu %7.2f %10.1f %10.1f %7.2f %10.1f\n", label.c_str(),
                bundle_bytes.size(), blob.size(), double(blob.size()) / bundle_bytes.size(),
                1e3 * parse_seconds, 1e3 * decode_seconds, decode_seconds / parse_seconds,
                1e3 * encode_seconds);
    if (!decoded.ok()) std::printf("  decode failed: %s\n", decoded.status().ToString().c_str());
}

}  // namespace

int main(int argc, char** argv) {
    std::printf("%-28s %12s %12s %7s %10s %10s %7s %10s\n", "scene", "bundle B", "prepared B",
                "ratio", "parse ms", "decode ms", "ratio", "encode ms");
    if (argc > 1) {
        for (int i = 1; i < argc; ++i) Measure(argv[i], argv[i]);
        return 0;
    }
    const std::string scenes = std::string(PF_SOURCE_DIR) + "/scenes/";
    for (const char* name : {"cornell-box.gltf", "cornell-glass.gltf", "caustic-glass.gltf",
                             "pbrt/cornell-room.pbrt", "pbrt/caustic-glass.pbrt"})
        Measure(scenes + name, name);
    for (int size : {512, 2048}) {
        const std::string label = "textured " + std::to_string(size) + "^2";
        Measure(TexturedScene(size), label);
    }
    return 0;
}
