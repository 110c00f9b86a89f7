// glTF JSON documents in and out of their files.
#include "core/scene_io/gltf/gltf_json.h"

#include <cstdint>
#include <cstring>

namespace pf {
namespace {

uint32_t Word(std::string_view bytes, size_t at) {
    uint32_t value = 0;
    std::memcpy(&value, bytes.data() + at, 4);
    return value;
}

}  // namespace

std::optional<GltfJson> ParseGltfJson(std::string_view contents, bool binary) {
    GltfJson json;
    std::string_view text = contents;
    if (binary) {
        // A 12-byte header, then the JSON chunk (length, type, text), then the binary chunk.
        if (contents.size() < 20) return std::nullopt;
        const uint32_t chunk_size = Word(contents, 12);
        if (chunk_size > contents.size() - 20) return std::nullopt;
        json.header = contents.substr(0, 12);
        text = contents.substr(20, chunk_size);
        json.rest = contents.substr(20 + chunk_size);
    }
    json.document = nlohmann::json::parse(text, nullptr, false);
    if (json.document.is_discarded() || !json.document.is_object()) return std::nullopt;
    return json;
}

std::string SerializeGltfJson(const GltfJson& json, bool binary) {
    std::string text = json.document.dump();
    if (!binary) return text;
    text.resize((text.size() + 3) / 4 * 4, ' ');  // chunks are 4-byte aligned
    std::string out(json.header);
    const auto chunk_size = static_cast<uint32_t>(text.size());
    out.append(reinterpret_cast<const char*>(&chunk_size), 4);
    out += "JSON";
    out += text;
    out.append(json.rest);
    const auto total = static_cast<uint32_t>(out.size());
    std::memcpy(out.data() + 8, &total, 4);
    return out;
}

std::string_view GlbBinaryChunk(const GltfJson& json) {
    if (json.rest.size() < 8) return {};
    const uint32_t size = Word(json.rest, 0);
    if (std::memcmp(json.rest.data() + 4, "BIN\0", 4) != 0 || size > json.rest.size() - 8)
        return {};
    return json.rest.substr(8, size);
}

}  // namespace pf
