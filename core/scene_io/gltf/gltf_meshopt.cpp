// meshoptimizer-compressed glTF buffer views.
#include "core/scene_io/gltf/gltf_meshopt.h"

#include <meshoptimizer.h>

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "absl/strings/escaping.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "core/scene_io/gltf/gltf_json.h"
#include "core/scene_io/scene_files.h"

namespace pf {
namespace {

// The extension and its ratified name (whose files may also use the vertex codec's version 1,
// which Debian 12's meshoptimizer 0.18 does not decode: refused saying so).
constexpr const char* kExtensions[] = {"EXT_meshopt_compression", "KHR_meshopt_compression"};
// What a file may decode to in all, and how far beyond its stream's size one view may grow
// (the codecs reach a few hundred to one on constant data): a hostile count is refused
// before anything is allocated.
constexpr uint64_t kMaxDecodedBytes = uint64_t{1} << 31;
constexpr uint64_t kMaxExpansion = 1024;

absl::Status Invalid(const std::string& what) { return absl::InvalidArgumentError(what); }

// A non-negative integer member of `object`, or `fallback` where it is absent; nullopt where
// it is present and no such integer.
std::optional<uint64_t> Unsigned(const nlohmann::json& object, const char* name,
                                 std::optional<uint64_t> fallback = std::nullopt) {
    if (!object.contains(name)) return fallback;
    const nlohmann::json& value = object[name];
    if (!value.is_number_unsigned()) return std::nullopt;
    return value.get<uint64_t>();
}

// The bytes of buffer `index`: its data URI, its file in the bundle, or a .glb's binary chunk.
absl::StatusOr<std::string> BufferBytes(const nlohmann::json& buffers, uint64_t index,
                                        const GltfJson& json, const std::string& folder,
                                        const BundleFileReader& read) {
    const std::string where = absl::StrCat("buffers[", index, "]");
    if (!buffers.is_array() || index >= buffers.size() || !buffers[index].is_object())
        return Invalid(absl::StrCat(where, " does not exist"));
    const nlohmann::json& buffer = buffers[index];
    if (!buffer.contains("uri")) {
        if (index == 0 && !json.rest.empty()) return std::string(GlbBinaryChunk(json));
        return Invalid(absl::StrCat(where, " has no data"));
    }
    if (!buffer["uri"].is_string()) return Invalid(absl::StrCat(where, ": uri is no string"));
    const std::string uri = buffer["uri"].get<std::string>();
    if (absl::StartsWith(uri, "data:")) {
        const size_t comma = uri.find(',');
        std::string bytes;
        if (comma == std::string::npos ||
            uri.substr(0, comma).find(";base64") == std::string::npos ||
            !absl::Base64Unescape(uri.substr(comma + 1), &bytes))
            return Invalid(absl::StrCat(where, ": not a base64 data URI"));
        return bytes;
    }
    const absl::StatusOr<std::string> path = ResolveReference(uri, folder);
    if (!path.ok()) return Invalid(absl::StrCat(where, ": ", path.status().message()));
    const absl::StatusOr<std::string_view> file = read(*path);
    if (!file.ok())
        return absl::Status(file.status().code(),
                            absl::StrCat(where, ": ", file.status().message()));
    return std::string(*file);
}

}  // namespace

absl::StatusOr<std::string> DecodeMeshoptStream(std::string_view compressed,
                                                const MeshoptStream& stream) {
    const uint64_t count = stream.count, stride = stream.stride;
    const bool attributes = stream.mode == "ATTRIBUTES";
    const bool triangles = stream.mode == "TRIANGLES", indices = stream.mode == "INDICES";
    if (!attributes && !triangles && !indices)
        return Invalid(absl::StrCat("mode \"", stream.mode, "\" is unknown"));
    if (attributes ? (stride == 0 || stride % 4 != 0 || stride > 256)
                   : (stride != 2 && stride != 4))
        return Invalid(absl::StrCat("byteStride ", stride, " is not allowed for ", stream.mode));
    if (triangles && count % 3 != 0)
        return Invalid(absl::StrCat("count ", count, " of TRIANGLES is no multiple of 3"));
    if (!attributes && stream.filter != "NONE")
        return Invalid(absl::StrCat("filter \"", stream.filter, "\" applies to ATTRIBUTES only"));
    if (count > kMaxDecodedBytes / stride ||
        count * stride > kMaxExpansion * compressed.size() + 65536)
        return Invalid(absl::StrCat(count, " elements of ", stride, " bytes from a stream of ",
                                    compressed.size(), " bytes"));
    std::string out(count * stride, '\0');
    const auto* source = reinterpret_cast<const unsigned char*>(compressed.data());
    int error = 0;
    if (attributes)
        error = meshopt_decodeVertexBuffer(out.data(), count, stride, source, compressed.size());
    else if (triangles)
        error = meshopt_decodeIndexBuffer(out.data(), count, stride, source, compressed.size());
    else
        error = meshopt_decodeIndexSequence(out.data(), count, stride, source, compressed.size());
    if (error != 0 && attributes && !compressed.empty() &&
        static_cast<unsigned char>(compressed[0]) == 0xa1)
        return Invalid(
            "the stream is in meshoptimizer's vertex codec version 1, which the meshoptimizer "
            "of this system (0.18, Debian 12) does not decode; re-encode it with version 0 "
            "(gltfpack -cc 0 or EXT_meshopt_compression)");
    if (error != 0)
        return Invalid(
            absl::StrCat("the ", stream.mode, " stream is malformed (error ", error, ")"));
    if (stream.filter == "OCTAHEDRAL") {
        if (stride != 4 && stride != 8) return Invalid("OCTAHEDRAL needs byteStride 4 or 8");
        meshopt_decodeFilterOct(out.data(), count, stride);
    } else if (stream.filter == "QUATERNION") {
        if (stride != 8) return Invalid("QUATERNION needs byteStride 8");
        meshopt_decodeFilterQuat(out.data(), count, stride);
    } else if (stream.filter == "EXPONENTIAL") {
        meshopt_decodeFilterExp(out.data(), count, stride);
    } else if (stream.filter != "NONE") {
        return Invalid(absl::StrCat("filter \"", stream.filter, "\" is unknown"));
    }
    return out;
}

absl::StatusOr<std::string> DecodeMeshoptBuffers(const std::string& contents, bool binary,
                                                 const std::string& folder,
                                                 const BundleFileReader& read) {
    if (contents.find("_meshopt_compression") == std::string::npos) return contents;
    std::optional<GltfJson> json = ParseGltfJson(contents, binary);
    if (!json || !json->document.contains("bufferViews") ||
        !json->document["bufferViews"].is_array())
        return contents;
    nlohmann::json& document = json->document;
    nlohmann::json& buffers = document["buffers"];
    // Fallback buffers (no data of their own) -> the bytes decoded into them so far.
    std::map<uint64_t, std::string> decoded;
    std::map<uint64_t, std::string> sources;  // compressed buffers read, by index
    uint64_t total = 0;
    for (size_t v = 0; v < document["bufferViews"].size(); ++v) {
        const nlohmann::json& view = document["bufferViews"][v];
        if (!view.is_object() || !view.contains("extensions") || !view["extensions"].is_object())
            continue;
        const char* name = nullptr;
        for (const char* known : kExtensions)
            if (view["extensions"].contains(known)) name = known;
        if (name == nullptr) continue;
        const std::string where = absl::StrCat("bufferViews[", v, "]: ", name);
        const nlohmann::json& extension = view["extensions"][name];
        const std::optional<uint64_t> parent = Unsigned(view, "buffer"),
                                      parent_offset = Unsigned(view, "byteOffset", 0),
                                      parent_length = Unsigned(view, "byteLength");
        if (!parent || !parent_offset || !parent_length)
            return Invalid(absl::StrCat("bufferViews[", v,
                                        "]: buffer, byteOffset or byteLength is malformed"));
        if (!buffers.is_array() || *parent >= buffers.size() || !buffers[*parent].is_object())
            return Invalid(absl::StrCat(where, ": buffers[", *parent, "] does not exist"));
        // A parent buffer with data holds the view uncompressed: tinygltf reads that.
        if (buffers[*parent].contains("uri") || (*parent == 0 && !json->rest.empty())) continue;
        if (!extension.is_object()) return Invalid(absl::StrCat(where, " is no object"));
        const std::optional<uint64_t> buffer = Unsigned(extension, "buffer"),
                                      offset = Unsigned(extension, "byteOffset", 0),
                                      length = Unsigned(extension, "byteLength"),
                                      stride = Unsigned(extension, "byteStride"),
                                      count = Unsigned(extension, "count");
        if (!buffer || !offset || !length || !stride || !count || !extension.contains("mode") ||
            !extension["mode"].is_string() ||
            (extension.contains("filter") && !extension["filter"].is_string()))
            return Invalid(absl::StrCat(where,
                                        ": buffer, byteOffset, byteLength, byteStride, "
                                        "count or mode is missing or malformed"));
        if (!sources.contains(*buffer)) {
            absl::StatusOr<std::string> bytes = BufferBytes(buffers, *buffer, *json, folder, read);
            if (!bytes.ok())
                return absl::Status(bytes.status().code(),
                                    absl::StrCat(where, ": ", bytes.status().message()));
            sources[*buffer] = std::move(*bytes);
        }
        const std::string& source = sources[*buffer];
        if (*offset > source.size() || *length > source.size() - *offset)
            return Invalid(absl::StrCat(where, ": bytes ", *offset, " + ", *length,
                                        " lie outside buffers[", *buffer, "] (", source.size(),
                                        " bytes)"));
        MeshoptStream stream{*count, *stride, extension["mode"].get<std::string>()};
        if (extension.contains("filter")) stream.filter = extension["filter"].get<std::string>();
        absl::StatusOr<std::string> bytes =
            DecodeMeshoptStream(std::string_view(source).substr(*offset, *length), stream);
        if (!bytes.ok()) return Invalid(absl::StrCat(where, ": ", bytes.status().message()));
        if (bytes->size() > *parent_length)
            return Invalid(absl::StrCat(where, ": ", bytes->size(),
                                        " decoded bytes overflow the view's byteLength ",
                                        *parent_length));
        // The fallback buffer grows to hold what was decoded into it, no further: an offset
        // far past what the streams could hold is refused before anything is allocated.
        const uint64_t end = *parent_offset + bytes->size();
        total += bytes->size();
        if (*parent_offset > kMaxDecodedBytes || total > kMaxDecodedBytes ||
            end > kMaxExpansion * source.size() + 65536)
            return Invalid(absl::StrCat(where, ": decoding to bytes ", *parent_offset, " to ", end,
                                        " of buffers[", *parent, "] is more than its streams ",
                                        "could hold"));
        std::string& target = decoded[*parent];
        if (target.size() < end) target.resize(end, '\0');
        target.replace(*parent_offset, bytes->size(), *bytes);
    }
    if (decoded.empty()) return contents;
    for (auto& [index, bytes] : decoded) {
        nlohmann::json& buffer = buffers[index];
        buffer["byteLength"] = bytes.size();
        buffer["uri"] = "data:application/octet-stream;base64," + absl::Base64Escape(bytes);
        buffer.erase("extensions");
    }
    return SerializeGltfJson(*json, binary);
}

}  // namespace pf
