// Packing a scene and what it references into a bundle, and the checks every bundle passes.
#include "core/scene/scene_bundle.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "core/util/sha256.h"

namespace pf {
namespace {

absl::StatusOr<std::string> ReadFile(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return absl::NotFoundError(absl::StrCat(path.string(), ": cannot open file"));
    std::ostringstream contents;
    contents << in.rdbuf();
    if (!in && !in.eof()) return absl::DataLossError(absl::StrCat(path.string(), ": read failed"));
    return std::move(contents).str();
}

// tinygltf's file callbacks while packing: files are read from the scene's folder and
// recorded; a path that would leave the folder is refused and remembered as the error.
struct PackState {
    std::filesystem::path root;
    SceneBundle* bundle;
    absl::Status error;
};

bool PackFileExists(const std::string& path, void* user) {
    auto* state = static_cast<PackState*>(user);
    if (absl::Status status = CheckBundlePath(path); !status.ok()) {
        if (state->error.ok()) state->error = status;
        return false;
    }
    return std::filesystem::is_regular_file(state->root / path);
}

std::string PackExpandFilePath(const std::string& path, void*) { return path; }

bool PackReadWholeFile(std::vector<unsigned char>* out, std::string* error, const std::string& path, void* user) {
    auto* state = static_cast<PackState*>(user);
    if (!PackFileExists(path, user)) return false;
    absl::StatusOr<std::string> contents = ReadFile(state->root / path);
    if (!contents.ok()) {
        if (error) *error = std::string(contents.status().message());
        return false;
    }
    out->assign(contents->begin(), contents->end());
    state->bundle->files[path] = std::move(*contents);
    return true;
}

bool NoWrite(std::string*, const std::string&, const std::vector<unsigned char>&, void*) { return false; }

// Packing only needs to know which files the scene reads; images are decoded once, by the load.
bool SkipImageDecoding(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int,
                       void*) {
    return true;
}

}  // namespace

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
        return absl::InvalidArgumentError(absl::StrCat("scene reference '", std::string(path), "' ", why));
    };
    if (path.empty()) return refuse("is empty");
    if (path.size() > 1024) return refuse("is longer than 1024 characters");
    if (path.find('\0') != std::string_view::npos) return refuse("contains NUL");
    if (path.find('\\') != std::string_view::npos || path.find(':') != std::string_view::npos)
        return refuse("is not a relative '/'-separated path inside the scene's folder");
    if (path.front() == '/') return refuse("is absolute; only paths inside the scene's folder are allowed");
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
        return absl::ResourceExhaustedError(
            absl::StrCat("scene bundle holds ", bundle.files.size(), " files, over the limit of ", kMaxBundleFiles));
    if (bundle.TotalBytes() > kMaxBundleBytes)
        return absl::ResourceExhaustedError(
            absl::StrCat("scene bundle holds ", bundle.TotalBytes(), " bytes, over the limit of ", kMaxBundleBytes));
    for (const auto& [path, contents] : bundle.files)
        if (absl::Status status = CheckBundlePath(path); !status.ok()) return status;
    if (!bundle.files.contains(bundle.main_file))
        return absl::InvalidArgumentError(absl::StrCat("scene bundle: main file '", bundle.main_file, "' is missing"));
    return absl::OkStatus();
}

absl::StatusOr<SceneBundle> PackSceneBundle(const std::string& scene_path) {
    const std::filesystem::path path(scene_path);
    SceneBundle bundle;
    bundle.main_file = path.filename().string();
    absl::StatusOr<std::string> main = ReadFile(path);
    if (!main.ok()) return main.status();
    PackState state{path.parent_path(), &bundle, absl::OkStatus()};
    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks({PackFileExists, PackExpandFilePath, PackReadWholeFile, NoWrite, &state});
    loader.SetImageLoader(SkipImageDecoding, nullptr);
    tinygltf::Model model;
    std::string error, warning;
    const auto* bytes = reinterpret_cast<const unsigned char*>(main->data());
    const bool loaded = absl::EndsWithIgnoreCase(scene_path, ".glb")
                            ? loader.LoadBinaryFromMemory(&model, &error, &warning, bytes, main->size(), "")
                            : loader.LoadASCIIFromString(&model, &error, &warning, main->data(), main->size(), "");
    if (!state.error.ok()) return absl::InvalidArgumentError(absl::StrCat(scene_path, ": ", state.error.message()));
    if (!loaded) {
        const std::string first_line = error.substr(0, error.find('\n'));
        return absl::InvalidArgumentError(
            absl::StrCat(scene_path, ": not a valid glTF file: ", first_line.empty() ? "parse failed" : first_line));
    }
    bundle.files[bundle.main_file] = std::move(*main);
    if (absl::Status status = CheckSceneBundle(bundle); !status.ok())
        return absl::Status(status.code(), absl::StrCat(scene_path, ": ", status.message()));
    return bundle;
}

}  // namespace pf
