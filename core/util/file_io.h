// Whole files written so that a reader never sees half of one.
#pragma once

#include <initializer_list>
#include <string>
#include <string_view>

#include "absl/status/status.h"
#include "absl/status/statusor.h"

namespace pf {

// Writes `contents` to `path` + ".partial" and renames it over `path`. UNAVAILABLE, naming
// the path, when either step fails (the partial file is removed).
absl::Status WriteFileAtomically(const std::string& path, std::string_view contents);

// Files that survive a crash and show when they did not: the pieces, then their SHA-256 and a
// marker, written to a temporary file, flushed to disk (fsync), renamed over `path`, and the
// folder flushed, so that after a crash at any moment `path` holds the old file or the new
// one, whole. UNAVAILABLE naming the path when a step fails.
absl::Status WriteChecksummedFile(const std::string& path,
                                  std::initializer_list<std::string_view> pieces);
// The pieces of such a file, joined. DATA_LOSS naming the path when it is truncated or its
// contents do not match their checksum; NOT_FOUND when it does not exist.
absl::StatusOr<std::string> ReadChecksummedFile(const std::string& path);

}  // namespace pf
