// tinygltf's file access, confined to a scene bundle, and its images kept encoded.
#include "core/scene_io/gltf/gltf_bundle_files.h"

#include <cstring>
#include <vector>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "core/scene_io/scene_files.h"

namespace pf {
namespace {

// The extension OpenImageIO needs to pick a reader: from the bytes' signature, else the URI's.
std::string ImageName(int index, const tinygltf::Image& image, const unsigned char* bytes,
                      int size) {
    const std::string label = image.uri.empty() || absl::StartsWith(image.uri, "data:")
                                  ? absl::StrCat("image #", index)
                                  : image.uri;
    const char* extension = "";
    if (size >= 8 && std::memcmp(bytes, "\x89PNG", 4) == 0) extension = ".png";
    if (size >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) extension = ".jpg";
    if (size >= 12 && std::memcmp(bytes, "RIFF", 4) == 0 && std::memcmp(bytes + 8, "WEBP", 4) == 0)
        extension = ".webp";
    return absl::EndsWithIgnoreCase(label, extension) ? label : absl::StrCat(label, extension);
}

bool BundleFileExists(const std::string& path, void* user) {
    return CheckBundlePath(path).ok() &&
           static_cast<const SceneBundle*>(user)->files.contains(path);
}
std::string BundleExpandFilePath(const std::string& path, void*) {
    return ResolveReference(path).value_or(path);  // ".." within the bundle resolved
}
bool BundleReadWholeFile(std::vector<unsigned char>* out, std::string* error,
                         const std::string& path, void* user) {
    if (!BundleFileExists(path, user)) {
        if (error) *error = absl::StrCat(path, ": not in the scene bundle");
        return false;
    }
    const std::string& contents = static_cast<const SceneBundle*>(user)->files.at(path);
    out->assign(contents.begin(), contents.end());
    return true;
}
bool BundleWriteWholeFile(std::string*, const std::string&, const std::vector<unsigned char>&,
                          void*) {
    return false;
}

}  // namespace

tinygltf::FsCallbacks BundleFsCallbacks(const SceneBundle& bundle) {
    return {BundleFileExists, BundleExpandFilePath, BundleReadWholeFile, BundleWriteWholeFile,
            const_cast<SceneBundle*>(&bundle)};
}

absl::StatusOr<std::string_view> ReadBundleFile(const SceneBundle& bundle,
                                                const std::string& path) {
    const auto file = bundle.files.find(path);
    if (file == bundle.files.end())
        return absl::NotFoundError(absl::StrCat(path, ": not in the scene bundle"));
    return std::string_view(file->second);
}

bool KeepEncodedImage(tinygltf::Image* image, int index, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void* user) {
    auto* images = static_cast<GltfImages*>(user);
    (*images)[index] = {std::string(reinterpret_cast<const char*>(bytes), size),
                        ImageName(index, *image, bytes, size)};
    return true;
}

}  // namespace pf
