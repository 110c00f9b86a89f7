#include "core/util/file_io.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "absl/strings/str_cat.h"

namespace pf {

absl::Status WriteFileAtomically(const std::string& path, std::string_view contents) {
    const std::string partial = path + ".partial";
    std::FILE* file = std::fopen(partial.c_str(), "wb");
    if (file == nullptr) return absl::UnavailableError(absl::StrCat(path, ": cannot write: ", std::strerror(errno)));
    const bool written = std::fwrite(contents.data(), 1, contents.size(), file) == contents.size();
    const int error = errno;
    if (std::fclose(file) != 0 || !written) {
        std::remove(partial.c_str());
        return absl::UnavailableError(absl::StrCat(path, ": cannot write: ", std::strerror(written ? errno : error)));
    }
    if (std::rename(partial.c_str(), path.c_str()) != 0) {
        const int rename_error = errno;
        std::remove(partial.c_str());
        return absl::UnavailableError(absl::StrCat(path, ": cannot replace the file: ", std::strerror(rename_error)));
    }
    return absl::OkStatus();
}

}  // namespace pf
