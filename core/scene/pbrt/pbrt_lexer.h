// Tokens of the pbrt-v4 scene format (https://pbrt.org/fileformat-v4), each with the file,
// line and column it starts at, so every message about a scene can point at its source.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "absl/status/statusor.h"

namespace pf::pbrt {

// Where a token starts: `file` is the bundle path of the file it came from.
struct Location {
    std::string_view file;
    int line = 1, column = 1;

    std::string ToString() const;  // "file:line:column"
};

enum class TokenKind : uint8_t {
    kWord,          // a directive name or a bare keyword (true/false inside brackets)
    kString,        // "quoted", text without the quotes, escapes resolved
    kNumber,        // text as written
    kOpenBracket,   // [
    kCloseBracket,  // ]
};

struct Token {
    TokenKind kind;
    std::string text;
    Location where;
};

// Splits `contents` (the text of bundle file `file`, which must outlive the tokens) into
// tokens; '#' starts a comment to the end of the line. An unterminated string or a stray
// character is an INVALID_ARGUMENT naming file:line:column.
absl::StatusOr<std::vector<Token>> Tokenize(std::string_view file, std::string_view contents);

// The token's text for messages: strings quoted, as the user wrote them.
std::string Describe(const Token& token);

}  // namespace pf::pbrt
