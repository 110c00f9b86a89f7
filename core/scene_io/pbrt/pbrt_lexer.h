// Tokens of the pbrt-v4 scene format (https://pbrt.org/fileformat-v4), each with the file,
// line and column it starts at, so every message about a scene can point at its source.
#pragma once

#include <cstdint>
#include <functional>
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

// The tokens of a file and the files it includes, as one stream: `Include "f"` and `Import
// "f"` are replaced where they stand by f's tokens, so a parameter list may go on after an
// include, as pbrt reads it. An error (a file that cannot be read, an include without a file)
// ends the stream and is kept in status().
class TokenStream {
public:
    // The tokens of the file that `include` (the directive's token) names in `file`, read at
    // `depth` includes deep (1 for the main file's).
    using Opener = std::function<absl::StatusOr<std::vector<Token>>(const Token& include,
                                                                    const Token& file, int depth)>;

    TokenStream(std::vector<Token> tokens, Opener opener);

    // The next token, null at the end (or after an error). Valid until the next call.
    const Token* Peek();
    bool NextIs(TokenKind kind) {
        const Token* next = Peek();
        return next != nullptr && next->kind == kind;
    }
    // The token Peek gives, which must not be null, and past it.
    Token Next();
    void Skip() { ++frames_.back().next; }  // past the token Peek gave, which must not be null
    const absl::Status& status() const { return status_; }

private:
    struct Frame {
        std::vector<Token> tokens;
        size_t next = 0;
    };
    std::vector<Frame> frames_;
    Opener opener_;
    absl::Status status_;
};

}  // namespace pf::pbrt
