// A glTF file's JSON document, taken out of a .gltf or a .glb's JSON chunk and put back, for
// the rewrites made before tinygltf reads a file (Draco's indices, meshopt's buffers).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

namespace pf {

struct GltfJson {
    nlohmann::json document;
    // A .glb's binary chunk (the bytes after the JSON chunk, chunk header included); empty
    // for a .gltf or a .glb without one.
    std::string_view rest;
    std::string_view header;  // a .glb's 12-byte header
};

// The document of `contents` (a .glb when `binary`); nullopt where it is no JSON object or
// the .glb's chunks do not add up (tinygltf then says what is wrong).
std::optional<GltfJson> ParseGltfJson(std::string_view contents, bool binary);

// The file again with `json.document` rewritten: the text, or a .glb with its JSON chunk
// replaced and its lengths updated.
std::string SerializeGltfJson(const GltfJson& json, bool binary);

// The bytes of a .glb's binary chunk (its data, after the chunk's 8-byte header); empty where
// there is none.
std::string_view GlbBinaryChunk(const GltfJson& json);

}  // namespace pf
