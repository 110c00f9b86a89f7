// Scene file access confined to a bundle.
#include "core/scene_io/scene_files.h"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"

namespace pf {

absl::StatusOr<std::string> ReadWholeFile(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return absl::NotFoundError(absl::StrCat(path.string(), ": cannot open file"));
    std::ostringstream contents;
    contents << in.rdbuf();
    if (!in && !in.eof()) return absl::DataLossError(absl::StrCat(path.string(), ": read failed"));
    return std::move(contents).str();
}

absl::StatusOr<std::string_view> BundleFiles::Read(const std::string& path) {
    if (absl::Status status = CheckBundlePath(path); !status.ok()) return status;
    const auto it = bundle_.files.find(path);
    if (it == bundle_.files.end())
        return absl::NotFoundError(absl::StrCat("'", path, "' is not in the scene bundle"));
    return std::string_view(it->second);
}

absl::StatusOr<std::string_view> PackingFiles::Read(const std::string& path) {
    if (absl::Status status = CheckBundlePath(path); !status.ok()) return status;
    if (const auto it = bundle_->files.find(path); it != bundle_->files.end())
        return std::string_view(it->second);
    const std::filesystem::path file = root_ / path;
    if (!std::filesystem::is_regular_file(file))
        return absl::NotFoundError(
            absl::StrCat("'", path, "' is not a file in the scene's folder"));
    absl::StatusOr<std::string> contents = ReadWholeFile(file);
    if (!contents.ok()) return contents.status();
    if (bundle_->TotalBytes() + contents->size() > kMaxBundleBytes)
        return absl::ResourceExhaustedError(absl::StrCat(
            "'", path, "' makes the scene bundle larger than ", kMaxBundleBytes, " bytes"));
    return std::string_view(bundle_->files.emplace(path, std::move(*contents)).first->second);
}

std::string BundleFolder(const std::string& path) {
    const size_t slash = path.rfind('/');
    return slash == std::string::npos ? std::string() : path.substr(0, slash);
}

absl::StatusOr<std::string> ResolveReference(std::string_view reference, std::string_view base) {
    auto refuse = [&](const char* why) {
        return absl::InvalidArgumentError(
            absl::StrCat("scene reference '", std::string(reference), "' ", why));
    };
    if (reference.find("://") != std::string_view::npos)
        return refuse("is a URL; only files inside the scene's folder are allowed");
    if (!reference.empty() && reference.front() == '/')
        return refuse("is absolute; only paths inside the scene's folder are allowed");
    std::vector<std::string> parts;
    const std::string joined = base.empty()
                                   ? std::string(reference)
                                   : absl::StrCat(std::string(base), "/", std::string(reference));
    for (size_t begin = 0; begin <= joined.size();) {
        const size_t end = std::min(joined.find('/', begin), joined.size());
        const std::string part = joined.substr(begin, end - begin);
        begin = end + 1;
        if (part.empty() || part == ".") continue;
        if (part == "..") {
            if (parts.empty())
                return refuse(
                    "leaves the scene's folder (where the scene's files lie beside it, give "
                    "--scene-root with the folder that holds them all)");
            parts.pop_back();
        } else {
            parts.push_back(part);
        }
    }
    std::string path = absl::StrJoin(parts, "/");
    if (absl::Status status = CheckBundlePath(path); !status.ok()) return status;
    return path;
}

}  // namespace pf
