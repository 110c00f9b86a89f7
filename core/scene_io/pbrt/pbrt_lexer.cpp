// The pbrt-v4 tokenizer: words, quoted strings, numbers, brackets and comments.
#include "core/scene_io/pbrt/pbrt_lexer.h"

#include <cctype>

#include "absl/strings/str_cat.h"
#include "core/util/check.h"

namespace pf::pbrt {
namespace {

bool IsWordCharacter(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool StartsNumber(char c) {
    return std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.';
}

}  // namespace

std::string Location::ToString() const {
    return absl::StrCat(std::string(file), ":", line, ":", column);
}

std::string Describe(const Token& token) {
    return token.kind == TokenKind::kString ? absl::StrCat("\"", token.text, "\"") : token.text;
}

absl::StatusOr<std::vector<Token>> Tokenize(std::string_view file, std::string_view contents) {
    std::vector<Token> tokens;
    Location here{file, 1, 1};
    size_t i = 0;
    auto advance = [&] {
        if (contents[i] == '\n') {
            ++here.line;
            here.column = 1;
        } else {
            ++here.column;
        }
        ++i;
    };
    auto error = [&](const Location& where, const std::string& what) {
        return absl::InvalidArgumentError(absl::StrCat(where.ToString(), ": ", what));
    };
    while (i < contents.size()) {
        const char c = contents[i];
        if (c == ' ' || c == '\t' || c == '\r' || c == '\n') {
            advance();
        } else if (c == '#') {
            while (i < contents.size() && contents[i] != '\n') advance();
        } else if (c == '[' || c == ']') {
            tokens.push_back({c == '[' ? TokenKind::kOpenBracket : TokenKind::kCloseBracket,
                              std::string(1, c), here});
            advance();
        } else if (c == '"') {
            const Location start = here;
            std::string text;
            advance();
            while (true) {
                if (i >= contents.size() || contents[i] == '\n')
                    return error(start, "string is not closed on its line");
                if (contents[i] == '"') break;
                if (contents[i] == '\\') {
                    advance();
                    if (i >= contents.size())
                        return error(start, "string is not closed on its line");
                    switch (contents[i]) {
                        case 'n':
                            text += '\n';
                            break;
                        case 't':
                            text += '\t';
                            break;
                        case '\\':
                            text += '\\';
                            break;
                        case '"':
                            text += '"';
                            break;
                        default:
                            return error(
                                here, absl::StrCat("unknown escape '\\",
                                                   std::string(1, contents[i]), "' in a string"));
                    }
                } else {
                    text += contents[i];
                }
                advance();
            }
            advance();  // the closing quote
            tokens.push_back({TokenKind::kString, std::move(text), start});
        } else if (StartsNumber(c)) {
            const Location start = here;
            const size_t begin = i;
            while (i < contents.size() && (IsWordCharacter(contents[i]) || contents[i] == '.' ||
                                           contents[i] == '-' || contents[i] == '+'))
                advance();
            tokens.push_back(
                {TokenKind::kNumber, std::string(contents.substr(begin, i - begin)), start});
        } else if (IsWordCharacter(c)) {
            const Location start = here;
            const size_t begin = i;
            while (i < contents.size() && IsWordCharacter(contents[i])) advance();
            tokens.push_back(
                {TokenKind::kWord, std::string(contents.substr(begin, i - begin)), start});
        } else {
            const unsigned char byte = static_cast<unsigned char>(c);
            return error(here, std::isprint(byte)
                                   ? absl::StrCat("unexpected character '", std::string(1, c), "'")
                                   : absl::StrCat("unexpected byte 0x", absl::Hex(byte)));
        }
    }
    return tokens;
}

TokenStream::TokenStream(std::vector<Token> tokens, Opener opener) : opener_(std::move(opener)) {
    frames_.push_back({std::move(tokens), 0});
}

const Token* TokenStream::Peek() {
    while (!frames_.empty()) {
        Frame& frame = frames_.back();
        if (frame.next == frame.tokens.size()) {
            frames_.pop_back();
            continue;
        }
        const Token& token = frame.tokens[frame.next];
        if (token.kind != TokenKind::kWord || (token.text != "Include" && token.text != "Import"))
            return &token;
        // The file is the next token of the same file.
        if (frame.next + 1 == frame.tokens.size() ||
            frame.tokens[frame.next + 1].kind != TokenKind::kString) {
            status_ = absl::InvalidArgumentError(absl::StrCat(
                token.where.ToString(), ": ", token.text, " needs a quoted file name after it"));
            frames_.clear();
            return nullptr;
        }
        const Token include = token, file = frame.tokens[frame.next + 1];
        frame.next += 2;
        absl::StatusOr<std::vector<Token>> included =
            opener_(include, file, static_cast<int>(frames_.size()));
        if (!included.ok()) {
            status_ = included.status();
            frames_.clear();
            return nullptr;
        }
        frames_.push_back({std::move(*included), 0});
    }
    return nullptr;
}

Token TokenStream::Next() {
    const Token* next = Peek();
    PF_CHECK(next != nullptr);
    Token token = *next;
    Skip();
    return token;
}

}  // namespace pf::pbrt
