// A scene as a self-contained bundle: the main scene file and every file it references, held
// in memory under paths relative to the bundle's root. The farm ships scenes this way, and
// every scene is loaded from one, so nothing outside a bundle is ever read.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>

#include "absl/status/status.h"
#include "absl/status/statusor.h"

namespace pf {

struct SceneBundle {
    std::string main_file;                     // a key of `files`
    std::map<std::string, std::string> files;  // relative path -> contents

    uint64_t TotalBytes() const;
    // SHA-256 (hex) over the paths and contents in order: the bundle's content address.
    std::string Digest() const;
};

// Limits on what a bundle may hold, checked on every bundle received.
inline constexpr uint64_t kMaxBundleBytes = uint64_t{1} << 30;
inline constexpr size_t kMaxBundleFiles = 4096;

// A path is acceptable inside a bundle when it is relative, '/'-separated, without '.' or
// '..' components, empty components or NUL: it cannot name anything outside the bundle.
absl::Status CheckBundlePath(std::string_view path);
// The main file present, every path acceptable, within the limits.
absl::Status CheckSceneBundle(const SceneBundle& bundle);

}  // namespace pf
