// Output checks and writes.
#include "client/output_files.h"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <filesystem>

#include "absl/strings/str_cat.h"
#include "core/film/png_writer.h"

namespace pf {
namespace {

// INVALID_ARGUMENT naming the path unless its folder exists and is writable ("" is fine).
absl::Status CheckWritable(const std::string& path) {
    if (path.empty()) return absl::OkStatus();
    const std::filesystem::path parent = std::filesystem::absolute(path).parent_path();
    if (!std::filesystem::is_directory(parent) || access(parent.c_str(), W_OK) != 0)
        return absl::InvalidArgumentError(absl::StrCat(
            path, ": cannot write here (", parent.string(), " is not a writable directory)"));
    return absl::OkStatus();
}

// INVALID_ARGUMENT unless `dir` exists or can be created ("" is fine).
absl::Status MakeDirectory(const std::string& dir) {
    if (dir.empty()) return absl::OkStatus();
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    if (error)
        return absl::InvalidArgumentError(
            absl::StrCat(dir, ": cannot create directory: ", error.message()));
    return absl::OkStatus();
}

}  // namespace

absl::Status PrepareOutputs(const std::string& exr, const std::string& png,
                            const std::string& snapshot_dir) {
    for (const std::string* path : {&exr, &png})
        if (absl::Status status = CheckWritable(*path); !status.ok()) return status;
    return MakeDirectory(snapshot_dir);
}

absl::Status WriteImageFiles(const Image& image, const ImageMetadata& metadata,
                             const std::string& exr, const std::string& png, float exposure) {
    if (absl::Status status = WriteExr(exr, image, metadata); !status.ok()) return status;
    spdlog::info("wrote {}", exr);
    if (!png.empty()) {
        if (absl::Status status = WritePng(png, image, exposure); !status.ok()) return status;
        spdlog::info("wrote {}", png);
    }
    return absl::OkStatus();
}

}  // namespace pf
