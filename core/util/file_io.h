// Whole files written so that a reader never sees half of one.
#pragma once

#include <string>
#include <string_view>

#include "absl/status/status.h"

namespace pf {

// Writes `contents` to `path` + ".partial" and renames it over `path`. UNAVAILABLE, naming
// the path, when either step fails (the partial file is removed).
absl::Status WriteFileAtomically(const std::string& path, std::string_view contents);

}  // namespace pf
