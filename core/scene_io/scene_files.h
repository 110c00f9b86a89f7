// Where a scene loader reads the files a scene references: a bundle already in memory, or,
// while a bundle is being packed, the disk under the scene's folder. Either way, only paths
// CheckBundlePath accepts are read.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "absl/status/statusor.h"
#include "core/scene/scene_bundle.h"

namespace pf {

class SceneFiles {
public:
    virtual ~SceneFiles() = default;
    // The contents of bundle path `path` (relative to the scene's folder). The view stays
    // valid as long as this object. Errors name the path.
    virtual absl::StatusOr<std::string_view> Read(const std::string& path) = 0;
};

// A bundle's files.
class BundleFiles : public SceneFiles {
public:
    explicit BundleFiles(const SceneBundle& bundle) : bundle_(bundle) {}
    absl::StatusOr<std::string_view> Read(const std::string& path) override;

private:
    const SceneBundle& bundle_;
};

// Files under `root` on disk, each recorded into `bundle` as it is read.
class PackingFiles : public SceneFiles {
public:
    PackingFiles(std::filesystem::path root, SceneBundle* bundle)
        : root_(std::move(root)), bundle_(bundle) {}
    absl::StatusOr<std::string_view> Read(const std::string& path) override;

private:
    std::filesystem::path root_;
    SceneBundle* bundle_;
};

// Reads a whole file from disk.
absl::StatusOr<std::string> ReadWholeFile(const std::filesystem::path& path);

// `reference` made a bundle path: relative to bundle folder `base` (the main file's folder:
// pbrt-v4 resolves every relative name against it, glTF against the file's own), with "."
// components dropped and ".." resolved; refused if it leaves the bundle's root (saying that
// --scene-root takes a wider one), is absolute or is a URL.
absl::StatusOr<std::string> ResolveReference(std::string_view reference,
                                             std::string_view base = {});
// The folder of bundle path `path` ("" at the root).
std::string BundleFolder(const std::string& path);

}  // namespace pf
