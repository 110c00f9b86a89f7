// The checks every scene bundle passes, and its content address.
#include "core/scene/scene_bundle.h"

#include <algorithm>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "core/util/sha256.h"

namespace pf {

uint64_t SceneBundle::TotalBytes() const {
    uint64_t total = 0;
    for (const auto& [path, contents] : files) total += path.size() + contents.size();
    return total;
}

std::string SceneBundle::Digest() const {
    Sha256 hash;
    auto add = [&](std::string_view bytes) {
        const uint64_t size = bytes.size();
        hash.Update(std::string_view(reinterpret_cast<const char*>(&size), sizeof size));
        hash.Update(bytes);
    };
    add(main_file);
    for (const auto& [path, contents] : files) add(path), add(contents);
    return hash.HexDigest();
}

absl::Status CheckBundlePath(std::string_view path) {
    auto refuse = [&](const char* why) {
        return absl::InvalidArgumentError(
            absl::StrCat("scene reference '", std::string(path), "' ", why));
    };
    if (path.empty()) return refuse("is empty");
    if (path.size() > 1024) return refuse("is longer than 1024 characters");
    if (path.find('\0') != std::string_view::npos) return refuse("contains NUL");
    if (path.find('\\') != std::string_view::npos || path.find(':') != std::string_view::npos)
        return refuse("is not a relative '/'-separated path inside the scene's folder");
    if (path.front() == '/')
        return refuse("is absolute; only paths inside the scene's folder are allowed");
    for (size_t begin = 0; begin <= path.size();) {
        const size_t end = std::min(path.find('/', begin), path.size());
        const std::string_view part = path.substr(begin, end - begin);
        if (part.empty() || part == "." || part == "..")
            return refuse("leaves the scene's folder or has an empty component");
        begin = end + 1;
    }
    return absl::OkStatus();
}

absl::Status CheckSceneBundle(const SceneBundle& bundle) {
    if (bundle.files.size() > kMaxBundleFiles)
        return absl::ResourceExhaustedError(absl::StrCat("scene bundle holds ", bundle.files.size(),
                                                         " files, over the limit of ",
                                                         kMaxBundleFiles));
    if (bundle.TotalBytes() > kMaxBundleBytes)
        return absl::ResourceExhaustedError(absl::StrCat("scene bundle holds ", bundle.TotalBytes(),
                                                         " bytes, over the limit of ",
                                                         kMaxBundleBytes));
    for (const auto& [path, contents] : bundle.files)
        if (absl::Status status = CheckBundlePath(path); !status.ok()) return status;
    if (!bundle.files.contains(bundle.main_file))
        return absl::InvalidArgumentError(
            absl::StrCat("scene bundle: main file '", bundle.main_file, "' is missing"));
    return absl::OkStatus();
}

}  // namespace pf
