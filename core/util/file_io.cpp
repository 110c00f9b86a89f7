#include "core/util/file_io.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "absl/strings/str_cat.h"
#include "core/util/sha256.h"

namespace pf {

absl::Status WriteFileAtomically(const std::string& path, std::string_view contents) {
    const std::string partial = path + ".partial";
    std::FILE* file = std::fopen(partial.c_str(), "wb");
    if (file == nullptr)
        return absl::UnavailableError(absl::StrCat(path, ": cannot write: ", std::strerror(errno)));
    const bool written = std::fwrite(contents.data(), 1, contents.size(), file) == contents.size();
    const int error = errno;
    if (std::fclose(file) != 0 || !written) {
        std::remove(partial.c_str());
        return absl::UnavailableError(
            absl::StrCat(path, ": cannot write: ", std::strerror(written ? errno : error)));
    }
    if (std::rename(partial.c_str(), path.c_str()) != 0) {
        const int rename_error = errno;
        std::remove(partial.c_str());
        return absl::UnavailableError(
            absl::StrCat(path, ": cannot replace the file: ", std::strerror(rename_error)));
    }
    return absl::OkStatus();
}

namespace {

// Ends every checksummed file, after the 64 hex digits of its SHA-256.
constexpr std::string_view kChecksumMarker = "\nphotonfarm-sha256\n";
constexpr size_t kDigestChars = 64;

absl::Status WriteAll(int fd, std::string_view bytes) {
    while (!bytes.empty()) {
        const ssize_t written = ::write(fd, bytes.data(), bytes.size());
        if (written < 0 && errno == EINTR) continue;
        if (written <= 0) return absl::UnavailableError(std::strerror(errno));
        bytes.remove_prefix(static_cast<size_t>(written));
    }
    return absl::OkStatus();
}

absl::Status SyncFolder(const std::string& path) {
    std::string folder = std::filesystem::path(path).parent_path().string();
    if (folder.empty()) folder.assign(1, '.');  // (= "." trips GCC 12's false -Wrestrict)
    const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0)
        return absl::UnavailableError(
            absl::StrCat(folder, ": cannot open: ", std::strerror(errno)));
    const int result = ::fsync(fd);
    const int error = errno;
    ::close(fd);
    if (result != 0)
        return absl::UnavailableError(
            absl::StrCat(folder, ": cannot flush: ", std::strerror(error)));
    return absl::OkStatus();
}

}  // namespace

absl::Status WriteChecksummedFile(const std::string& path,
                                  std::initializer_list<std::string_view> pieces) {
    const std::string partial = path + ".partial";
    const int fd = ::open(partial.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0)
        return absl::UnavailableError(absl::StrCat(path, ": cannot write: ", std::strerror(errno)));
    Sha256 digest;
    absl::Status status;
    for (std::string_view piece : pieces) {
        digest.Update(piece);
        if (status.ok()) status = WriteAll(fd, piece);
    }
    if (status.ok()) status = WriteAll(fd, digest.HexDigest());
    if (status.ok()) status = WriteAll(fd, kChecksumMarker);
    if (status.ok() && ::fsync(fd) != 0) status = absl::UnavailableError(std::strerror(errno));
    if (::close(fd) != 0 && status.ok()) status = absl::UnavailableError(std::strerror(errno));
    if (status.ok() && std::rename(partial.c_str(), path.c_str()) != 0)
        status = absl::UnavailableError(std::strerror(errno));
    if (!status.ok()) {
        std::remove(partial.c_str());
        return absl::UnavailableError(absl::StrCat(path, ": cannot write: ", status.message()));
    }
    return SyncFolder(path);
}

absl::StatusOr<std::string> ReadChecksummedFile(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) return absl::NotFoundError(absl::StrCat(path, ": cannot open"));
    std::ostringstream content;
    content << file.rdbuf();
    std::string bytes = std::move(content).str();
    const size_t trailer = kDigestChars + kChecksumMarker.size();
    if (bytes.size() < trailer ||
        std::string_view(bytes).substr(bytes.size() - kChecksumMarker.size()) != kChecksumMarker)
        return absl::DataLossError(
            absl::StrCat(path, ": truncated (", bytes.size(), " bytes, no checksum at the end)"));
    const std::string stored = bytes.substr(bytes.size() - trailer, kDigestChars);
    bytes.resize(bytes.size() - trailer);
    if (Sha256Hex(bytes) != stored)
        return absl::DataLossError(absl::StrCat(path, ": corrupt (its checksum does not match)"));
    return bytes;
}

}  // namespace pf
