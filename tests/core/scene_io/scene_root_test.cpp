// A scene whose files lie in sibling folders: refused without --scene-root, naming it; packed
// and loaded with the root named; nothing outside the root read either way.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "absl/strings/escaping.h"
#include "core/scene_io/scene_loader.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/test_env.h"

namespace pf {
namespace {

void Write(const std::filesystem::path& path, const std::string& text) {
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
}

TEST(SceneRootTest, SiblingFoldersNeedTheRootAndStayInsideIt) {
    const std::filesystem::path root = testing::ProcessTempDir() / "project";
    Write(root / "scenes" / "room.pbrt",
          "LookAt 0 0 -5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n"
          "LightSource \"point\" \"rgb I\" [1 1 1]\nInclude \"../geometry/quad.pbrt\"\n");
    Write(root / "geometry" / "quad.pbrt",
          "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2]\n");
    Write(root.parent_path() / "secret.pbrt", "# outside the root\n");
    const std::string scene = (root / "scenes" / "room.pbrt").string();

    const absl::StatusOr<SceneBundle> refused = PackSceneBundle(scene);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.status().message().find("room.pbrt:5:1: Include: scene reference "
                                              "'../geometry/quad.pbrt' leaves the scene's folder"),
              std::string::npos)
        << refused.status();
    EXPECT_NE(refused.status().message().find("--scene-root"), std::string::npos);

    const absl::StatusOr<SceneBundle> bundle = PackSceneBundle(scene, nullptr, root.string());
    ASSERT_TRUE(bundle.ok()) << bundle.status();
    EXPECT_EQ(bundle->main_file, "scenes/room.pbrt");
    EXPECT_TRUE(bundle->files.contains("geometry/quad.pbrt"));
    const absl::StatusOr<Scene> loaded = LoadScene(*bundle, scene);
    ASSERT_TRUE(loaded.ok()) << loaded.status();
    EXPECT_EQ(loaded->triangles.size(), 1u);

    // Past the root, even with it named.
    Write(root / "scenes" / "escape.pbrt", "WorldBegin\nInclude \"../../secret.pbrt\"\n");
    const absl::StatusOr<SceneBundle> escape =
        PackSceneBundle((root / "scenes" / "escape.pbrt").string(), nullptr, root.string());
    ASSERT_FALSE(escape.ok());
    EXPECT_NE(escape.status().message().find("leaves the scene's folder"), std::string::npos);
    // A root that does not hold the scene.
    const absl::StatusOr<SceneBundle> elsewhere =
        PackSceneBundle(scene, nullptr, (root / "geometry").string());
    ASSERT_FALSE(elsewhere.ok());
    EXPECT_NE(elsewhere.status().message().find("must be a folder that holds"), std::string::npos)
        << elsewhere.status();
}

TEST(SceneRootTest, GltfBuffersInASiblingFolder) {
    // The lit quad, its buffer moved to ../buffers/quad.bin.
    const std::filesystem::path root = testing::ProcessTempDir() / "gltf-project";
    std::string json = testing::GltfJson(testing::LitQuadScene());
    const std::string prefix = "data:application/octet-stream;base64,";
    const size_t begin = json.find(prefix);
    ASSERT_NE(begin, std::string::npos);
    const size_t end = json.find('"', begin);
    std::string bytes;
    ASSERT_TRUE(absl::Base64Unescape(
        json.substr(begin + prefix.size(), end - begin - prefix.size()), &bytes));
    json.replace(begin, end - begin, "../buffers/quad.bin");
    Write(root / "models" / "quad.gltf", json);
    Write(root / "buffers" / "quad.bin", bytes);
    const std::string scene = (root / "models" / "quad.gltf").string();
    const absl::StatusOr<SceneBundle> refused = PackSceneBundle(scene);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.status().message().find("--scene-root"), std::string::npos)
        << refused.status();
    const absl::StatusOr<SceneBundle> bundle = PackSceneBundle(scene, nullptr, root.string());
    ASSERT_TRUE(bundle.ok()) << bundle.status();
    EXPECT_TRUE(bundle->files.contains("buffers/quad.bin"));
    const absl::StatusOr<Scene> loaded = LoadScene(*bundle, scene);
    ASSERT_TRUE(loaded.ok()) << loaded.status();
    EXPECT_EQ(loaded->triangles.size(), 4u);
}

}  // namespace
}  // namespace pf
