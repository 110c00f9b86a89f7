// tinygltf's file access, confined to a scene bundle.
#include "core/scene/gltf_bundle_files.h"

#include <vector>

#include "absl/strings/str_cat.h"
#include "core/scene/scene_files.h"

namespace pf {
namespace {

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

}  // namespace pf
