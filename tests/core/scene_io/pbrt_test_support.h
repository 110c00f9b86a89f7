// Helpers of the pbrt importer's tests: a small scene around a world block, loaded from a
// bundle, and checks on its errors and warnings.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/film/exr_io.h"
#include "core/scene_io/scene_files.h"
#include "core/scene_io/scene_loader.h"
#include "tests/support/png_fixture.h"
#include "tests/support/test_env.h"

namespace pf::pbrt_test {

using testing::TwoTexelPng;

// A scene.pbrt with a camera and a light around `world`, plus other files.
inline SceneBundle Bundle(const std::string& world, std::map<std::string, std::string> files = {}) {
    SceneBundle bundle;
    bundle.main_file = "scene.pbrt";
    files["scene.pbrt"] =
        "LookAt 0 0 -5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 40\n"
        "Film \"rgb\" \"integer xresolution\" 200 \"integer yresolution\" 100\nWorldBegin\n"
        "LightSource \"point\" \"rgb I\" [1 1 1]\n" +
        world;
    bundle.files = std::move(files);
    return bundle;
}

inline absl::StatusOr<Scene> Load(const SceneBundle& bundle,
                                  std::vector<std::string>* warnings = nullptr) {
    SceneLoadOptions options;
    options.warnings = warnings;
    return LoadScene(bundle, "scenes/" + bundle.main_file, options);
}

inline void ExpectError(const absl::StatusOr<Scene>& scene, const std::string& fragment) {
    ASSERT_FALSE(scene.ok()) << "loaded, expected an error with: " << fragment;
    const std::string message(scene.status().message());
    EXPECT_NE(message.find(fragment), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "error must be one line: " << message;
}

inline bool Contains(const std::vector<std::string>& lines, const std::string& fragment) {
    for (const std::string& line : lines)
        if (line.find(fragment) != std::string::npos) return true;
    return false;
}

inline constexpr char kQuad[] =
    "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0] \"integer indices\" [0 1 "
    "2 3]\n";

// An EXR of `width` x `height` texels, texel i = (i, 1, 2) x value, as a bundle file's bytes.
inline std::string ExrBytes(int width, int height, float value, bool ramp = true) {
    Image image(width, height);
    for (int i = 0; i < width * height; ++i)
        image.pixels[i] = Rgb(ramp ? float(i) : 1.0f, 1.0f, 2.0f) * value;
    const std::string path = testing::TempPath("pbrt-image.exr");
    EXPECT_TRUE(WriteExr(path, image).ok());
    absl::StatusOr<std::string> bytes = ReadWholeFile(path);
    EXPECT_TRUE(bytes.ok());
    std::filesystem::remove(path);
    return bytes.ok() ? *bytes : std::string();
}

}  // namespace pf::pbrt_test
