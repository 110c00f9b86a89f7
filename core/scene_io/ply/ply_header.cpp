// Parsing a PLY header: line by line, every count checked against the bytes that follow.
#include "core/scene_io/ply/ply_header.h"

#include <algorithm>
#include <charconv>
#include <optional>
#include <utility>

#include "absl/strings/escaping.h"
#include "absl/strings/str_cat.h"

namespace pf {
namespace {

constexpr std::pair<std::string_view, PlyScalar> kScalarNames[] = {
    {"char", PlyScalar::kInt8},      {"int8", PlyScalar::kInt8},
    {"uchar", PlyScalar::kUint8},    {"uint8", PlyScalar::kUint8},
    {"short", PlyScalar::kInt16},    {"int16", PlyScalar::kInt16},
    {"ushort", PlyScalar::kUint16},  {"uint16", PlyScalar::kUint16},
    {"int", PlyScalar::kInt32},      {"int32", PlyScalar::kInt32},
    {"uint", PlyScalar::kUint32},    {"uint32", PlyScalar::kUint32},
    {"float", PlyScalar::kFloat32},  {"float32", PlyScalar::kFloat32},
    {"double", PlyScalar::kFloat64}, {"float64", PlyScalar::kFloat64},
};

std::optional<PlyScalar> ScalarNamed(std::string_view name) {
    for (const auto& [known, type] : kScalarNames)
        if (name == known) return type;
    return std::nullopt;
}

// The words of a header line, separated by white space.
std::vector<std::string> Words(std::string_view line) {
    std::vector<std::string> words;
    size_t start = 0;
    while (true) {
        start = line.find_first_not_of(" \t\r\f\v", start);
        if (start == std::string_view::npos) return words;
        const size_t end = std::min(line.find_first_of(" \t\r\f\v", start), line.size());
        words.emplace_back(line.substr(start, end - start));
        start = end;
    }
}

bool IsInteger(PlyScalar type) {
    return type != PlyScalar::kFloat32 && type != PlyScalar::kFloat64;
}

// The header's lines, each without its terminator: LF, CRLF, or a lone CR where the first line
// ends in one (old Mac files). The terminator is settled by the first line, so that "end_header"
// followed by CR and then data beginning with LF is read right in a file of either kind.
class HeaderLines {
public:
    explicit HeaderLines(std::string_view bytes) : bytes_(bytes) {
        const size_t first = bytes.find_first_of("\r\n");
        lone_cr_ = first != std::string_view::npos && bytes[first] == '\r' &&
                   (first + 1 == bytes.size() || bytes[first + 1] != '\n');
    }
    // The next line, or nullopt where the bytes end before a terminator.
    std::optional<std::string_view> Next() {
        const size_t end = bytes_.find(lone_cr_ ? '\r' : '\n', position_);
        if (end == std::string_view::npos) return std::nullopt;
        std::string_view line = bytes_.substr(position_, end - position_);
        if (!lone_cr_ && !line.empty() && line.back() == '\r') line.remove_suffix(1);
        position_ = end + 1;
        ++number_;
        return line;
    }
    size_t position() const { return position_; }
    int number() const { return number_; }

private:
    std::string_view bytes_;
    size_t position_ = 0;
    int number_ = 0;
    bool lone_cr_ = false;
};

// Bytes one instance of `element` takes in the data at least.
uint64_t MinInstanceSize(const PlyElement& element, PlyEncoding encoding) {
    // ASCII: one number a scalar (a list's count at least), each a digit and a separator.
    return encoding == PlyEncoding::kAscii ? 2 * element.properties.size()
                                           : element.MinBinarySize();
}

}  // namespace

std::string PlyQuoted(std::string_view text) {
    const std::string shown(text.substr(0, 64));
    return absl::StrCat("\"", absl::CHexEscape(shown), text.size() > 64 ? "...\"" : "\"");
}

int PlyElement::Find(std::string_view property) const {
    for (size_t i = 0; i < properties.size(); ++i)
        if (properties[i].name == property) return static_cast<int>(i);
    return -1;
}

uint64_t PlyElement::MinBinarySize() const {
    uint64_t size = 0;
    for (const PlyProperty& property : properties)
        size += PlyScalarSize(property.is_list ? property.count_type : property.type);
    return size;
}

bool PlyElement::HasList() const {
    for (const PlyProperty& property : properties)
        if (property.is_list) return true;
    return false;
}

absl::StatusOr<PlyHeader> ParsePlyHeader(std::string_view bytes, const std::string& name) {
    HeaderLines lines(bytes);
    std::optional<std::string_view> line = lines.Next();
    if (!line || Words(*line) != std::vector<std::string>{"ply"}) {
        const bool gzip = bytes.size() >= 2 && bytes[0] == '\x1f' && bytes[1] == '\x8b';
        return absl::InvalidArgumentError(absl::StrCat(
            name, gzip ? ": is gzip-compressed but not named .gz (a PLY mesh begins \"ply\")"
                       : ": not a PLY file (its first line is not \"ply\")"));
    }
    PlyHeader header;
    bool has_format = false;
    const auto error = [&](const std::string& what) {
        return absl::InvalidArgumentError(
            absl::StrCat(name, ": PLY header line ", lines.number(), ": ", what));
    };
    while (true) {
        line = lines.Next();
        if (!line)
            return absl::InvalidArgumentError(
                absl::StrCat(name, ": PLY header has no end_header line"));
        // Comments are passed over unsplit (they may be long).
        const size_t first = line->find_first_not_of(" \t\r\f\v");
        if (first == std::string_view::npos || line->substr(first, 7) == "comment" ||
            line->substr(first, 8) == "obj_info")
            continue;
        const std::vector<std::string> words = Words(*line);
        const std::string& keyword = words[0];
        if (keyword == "end_header") break;
        if (keyword == "format") {
            if (words.size() != 3) return error("\"format\" needs an encoding and a version");
            if (words[1] == "ascii") {
                header.encoding = PlyEncoding::kAscii;
            } else if (words[1] == "binary_little_endian") {
                header.encoding = PlyEncoding::kBinaryLittleEndian;
            } else if (words[1] == "binary_big_endian") {
                header.encoding = PlyEncoding::kBinaryBigEndian;
            } else {
                return error(absl::StrCat("unknown format ", PlyQuoted(words[1]),
                                          " (ascii, binary_little_endian or binary_big_endian)"));
            }
            if (words[2] != "1.0" && words[2] != "1")
                return error(absl::StrCat("version ", PlyQuoted(words[2]), " is not 1.0"));
            has_format = true;
        } else if (keyword == "element") {
            PlyElement element;
            if (words.size() != 3) return error("\"element\" needs a name and a count");
            element.name = words[1];
            const std::string& count = words[2];
            const auto [end, problem] =
                std::from_chars(count.data(), count.data() + count.size(), element.count);
            if (problem != std::errc() || end != count.data() + count.size())
                return error(absl::StrCat("element ", PlyQuoted(words[1]), " has count ",
                                          PlyQuoted(count), ", not a whole number below 2^64"));
            for (const PlyElement& other : header.elements)
                if (other.name == element.name &&
                    (element.name == "vertex" || element.name == "face"))
                    return error(absl::StrCat("a second element ", PlyQuoted(element.name)));
            element.line = lines.number();
            header.elements.push_back(std::move(element));
        } else if (keyword == "property") {
            if (header.elements.empty()) return error("\"property\" before any \"element\"");
            PlyProperty property;
            const bool list = words.size() >= 2 && words[1] == "list";
            if (words.size() != (list ? 5u : 3u))
                return error(list ? "\"property list\" needs a count type, an item type and a name"
                                  : "\"property\" needs a type and a name");
            for (size_t i = list ? 2 : 1; i + 1 < words.size(); ++i)
                if (!ScalarNamed(words[i]))
                    return error(absl::StrCat("unknown type ", PlyQuoted(words[i])));
            property.is_list = list;
            if (list) {
                property.count_type = *ScalarNamed(words[2]);
                if (!IsInteger(property.count_type))
                    return error(absl::StrCat("a list's count type must be an integer, not ",
                                              PlyQuoted(words[2])));
            }
            property.type = *ScalarNamed(words[words.size() - 2]);
            property.name = words.back();
            header.elements.back().properties.push_back(std::move(property));
        }
        // Any other line is passed over, as comments are: Blender 2.4 wrote its "Created by"
        // line without the keyword.
    }
    if (!has_format) return error("end_header before any \"format\" line");
    header.data_offset = lines.position();
    header.lines = lines.number();
    return header;
}

absl::Status CheckPlyCounts(const PlyHeader& header, size_t data_size, const std::string& name) {
    // Each element's instances must fit in what follows the header (the last ASCII number
    // needs no separator after it, hence the slack of a byte).
    const uint64_t available = data_size + (header.encoding == PlyEncoding::kAscii ? 1 : 0);
    uint64_t needed = 0;
    for (const PlyElement& element : header.elements) {
        const uint64_t size = MinInstanceSize(element, header.encoding);
        if (size != 0 && element.count > (available - needed) / size)
            return absl::InvalidArgumentError(
                absl::StrCat(name, ": PLY element ", PlyQuoted(element.name), " (header line ",
                             element.line, ") declares ", element.count,
                             " instances, more than the ", data_size, " bytes of data can hold"));
        needed += element.count * size;
    }
    return absl::OkStatus();
}

}  // namespace pf
