// Scene bundles: packing what a scene references, the content address, and refusing paths
// that would leave the bundle.
#include "core/scene/scene_bundle.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "absl/strings/escaping.h"
#include "core/scene_io/scene_loader.h"
#include "tests/support/png_fixture.h"
#include "tests/support/test_env.h"

namespace pf {
namespace {

// The shipped Cornell box with its embedded buffer moved out to `buffer_uri` (relative to
// the .gltf), written under a fresh folder; returns the .gltf's path.
std::string WriteWithExternalBuffer(const std::string& folder, const std::string& buffer_uri,
                                    const std::string& buffer_file) {
    std::ifstream in(std::string(PF_SOURCE_DIR) + "/scenes/cornell-box.gltf");
    std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string marker = "data:application/octet-stream;base64,";
    const size_t begin = json.find(marker);
    const size_t end = json.find('"', begin);
    const std::string base64 = json.substr(begin + marker.size(), end - begin - marker.size());
    json.replace(begin, end - begin, buffer_uri);
    const std::filesystem::path root = testing::FreshTempDir(folder);  // this process's own
    std::filesystem::create_directories(root / "scene");
    std::ofstream(root / "scene" / "box.gltf") << json;
    // The buffer's bytes: decode the base64 the generator wrote.
    std::string bytes;
    int value = 0, bits = 0;
    for (char c : base64) {
        const std::string alphabet =
            "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        const size_t digit = alphabet.find(c);
        if (digit == std::string::npos) break;
        value = value << 6 | static_cast<int>(digit), bits += 6;
        if (bits >= 8) bytes.push_back(static_cast<char>(value >> (bits - 8) & 0xff)), bits -= 8;
    }
    std::filesystem::create_directories((root / "scene" / buffer_file).parent_path());
    std::ofstream(root / "scene" / buffer_file, std::ios::binary) << bytes;
    return (root / "scene" / "box.gltf").string();
}

TEST(SceneBundleTest, PacksReferencedFilesAndLoadsFromTheBundleAlone) {
    const std::string path = WriteWithExternalBuffer("pack", "meshes/box.bin", "meshes/box.bin");
    const absl::StatusOr<SceneBundle> bundle = PackSceneBundle(path);
    ASSERT_TRUE(bundle.ok()) << bundle.status();
    EXPECT_EQ(bundle->main_file, "box.gltf");
    ASSERT_EQ(bundle->files.size(), 2u);
    EXPECT_TRUE(bundle->files.contains("meshes/box.bin"));
    // Loading reads the bundle only: removing the files on disk changes nothing.
    std::filesystem::remove_all(std::filesystem::path(path).parent_path());
    const absl::StatusOr<Scene> scene = LoadScene(*bundle, "box.gltf");
    ASSERT_TRUE(scene.ok()) << scene.status();
    EXPECT_GT(scene->triangles.size(), 10u);
}

TEST(SceneBundleTest, PacksEveryImageOfAPbrtScaleOfTwoTextures) {
    // kroken's "scale" of a spectrum image by a float image: packing once stopped at the first
    // operand, so the second was missing from the bundle and the load refused the scene.
    const std::filesystem::path root = testing::FreshTempDir("pack-pbrt-scale");
    for (const char* name : {"colour.png", "dirt.png"})
        std::ofstream(root / name, std::ios::binary)
            << testing::TwoTexelPng({10, 20, 30, 200, 210, 220}, std::string("pack-") + name);
    std::ofstream(root / "scene.pbrt")
        << "LookAt 0 0 -5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n"
           "LightSource \"point\" \"rgb I\" [1 1 1]\n"
           "Texture \"c\" \"spectrum\" \"imagemap\" \"string filename\" \"colour.png\"\n"
           "Texture \"d\" \"float\" \"imagemap\" \"string filename\" \"dirt.png\"\n"
           "Texture \"muddled\" \"spectrum\" \"scale\" \"texture tex\" \"c\" "
           "\"texture scale\" \"d\"\n"
           "Material \"diffuse\" \"texture reflectance\" \"muddled\"\n"
           "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0] "
           "\"integer indices\" [0 1 2 3]\n";
    const absl::StatusOr<SceneBundle> bundle = PackSceneBundle((root / "scene.pbrt").string());
    ASSERT_TRUE(bundle.ok()) << bundle.status();
    EXPECT_TRUE(bundle->files.contains("colour.png"));
    EXPECT_TRUE(bundle->files.contains("dirt.png"));
    const absl::StatusOr<Scene> scene = LoadScene(*bundle, "scene.pbrt");
    ASSERT_TRUE(scene.ok()) << scene.status();
    EXPECT_EQ(scene->textures.size(), 1u);  // the product, baked
}

TEST(SceneBundleTest, LeavesOutImagesNoMaterialReads) {
    // The fuzz corpus's textured quad reads image.png as its base colour; give it an occlusion
    // map, which photonfarm does not read, and a metallic-roughness map, which it does.
    const std::filesystem::path root = testing::FreshTempDir("unused-images");
    std::ifstream in(std::string(PF_SOURCE_DIR) + "/tests/fuzz/corpus/gltf/textured-quad.gltf");
    std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    json.replace(json.find(R"("images":[{"uri":"image.png"}])"),
                 std::strlen(R"("images":[{"uri":"image.png"}])"),
                 R"("images":[{"uri":"image.png"},{"uri":"occlusion.png"},{"uri":"maps.png"}])");
    json.replace(json.find(R"("textures":[{"source":0}])"),
                 std::strlen(R"("textures":[{"source":0}])"),
                 R"("textures":[{"source":0},{"source":1},{"source":2}])");
    json.replace(json.find(R"("emissiveFactor")"), std::strlen(R"("emissiveFactor")"),
                 R"("occlusionTexture":{"index":1},"emissiveFactor")");
    json.replace(json.find(R"("pbrMetallicRoughness":{)"),
                 std::strlen(R"("pbrMetallicRoughness":{)"),
                 R"("pbrMetallicRoughness":{"metallicRoughnessTexture":{"index":2},)");
    std::ofstream(root / "quad.gltf") << json;
    // A 2x1 PNG for both (the same bytes: what matters is which files travel).
    std::string png;
    absl::Base64Unescape(
        "iVBORw0KGgoAAAANSUhEUgAAAAIAAAABCAIAAAB7QOjdAAAAD0lEQVR4nGP4z8DQ0NAAAAkBAoCZxGkyAAAAAElFTk"
        "SuQmCC",
        &png);
    std::ofstream(root / "image.png", std::ios::binary) << png;
    std::ofstream(root / "occlusion.png", std::ios::binary) << png;
    std::ofstream(root / "maps.png", std::ios::binary) << png;
    const absl::StatusOr<SceneBundle> bundle = PackSceneBundle((root / "quad.gltf").string());
    ASSERT_TRUE(bundle.ok()) << bundle.status();
    EXPECT_TRUE(bundle->files.contains("image.png"));
    EXPECT_FALSE(bundle->files.contains("occlusion.png"));
    EXPECT_TRUE(bundle->files.contains("maps.png"));
    const absl::StatusOr<Scene> scene = LoadScene(*bundle, "quad.gltf");
    ASSERT_TRUE(scene.ok()) << scene.status();
    EXPECT_GE(scene->textures.size(), 2u) << "the base colour and the metallic-roughness map";
    std::filesystem::remove_all(root);
}

TEST(SceneBundleTest, DigestIsAContentAddress) {
    const absl::StatusOr<SceneBundle> a =
        PackSceneBundle(std::string(PF_SOURCE_DIR) + "/scenes/cornell-box.gltf");
    const absl::StatusOr<SceneBundle> b =
        PackSceneBundle(std::string(PF_SOURCE_DIR) + "/scenes/cornell-box.gltf");
    ASSERT_TRUE(a.ok() && b.ok());
    EXPECT_EQ(a->Digest(), b->Digest());
    EXPECT_EQ(a->Digest().size(), 64u);
    SceneBundle changed = *a;
    changed.files[changed.main_file].back() = ' ';
    EXPECT_NE(changed.Digest(), a->Digest());
}

TEST(SceneBundleTest, RefusesReferencesOutsideTheFolder) {
    const std::string path = WriteWithExternalBuffer("escape", "../outside.bin", "../outside.bin");
    const absl::StatusOr<SceneBundle> bundle = PackSceneBundle(path);
    ASSERT_FALSE(bundle.ok());
    const std::string message(bundle.status().message());
    EXPECT_NE(message.find("box.gltf"), std::string::npos) << message;
    EXPECT_NE(message.find("../outside.bin"), std::string::npos) << message;
}

TEST(SceneBundleTest, ChecksPaths) {
    for (const char* good : {"a.bin", "meshes/a.bin", "a/b/c.png"})
        EXPECT_TRUE(CheckBundlePath(good).ok()) << good;
    for (const char* bad :
         {"", "/etc/passwd", "../a", "a/../../b", "a//b", "./a", "C:\\a", "http://x/a", "a/"})
        EXPECT_FALSE(CheckBundlePath(bad).ok()) << bad;
    SceneBundle bundle;
    bundle.main_file = "scene.gltf";
    bundle.files["other.gltf"] = "{}";
    EXPECT_EQ(CheckSceneBundle(bundle).code(), absl::StatusCode::kInvalidArgument);
    bundle.files["../x"] = "";
    bundle.main_file = "other.gltf";
    EXPECT_EQ(CheckSceneBundle(bundle).code(), absl::StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace pf
