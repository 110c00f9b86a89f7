// Closed surfaces: positions welded, directed edges counted.
#include "core/scene/closed_surface.h"

#include <bit>
#include <cstdint>
#include <unordered_map>

namespace pf {
namespace {

struct PositionKey {
    uint32_t x, y, z;
    bool operator==(const PositionKey&) const = default;
};
struct PositionHash {
    size_t operator()(const PositionKey& k) const {
        uint64_t h = k.x * 0x9e3779b97f4a7c15ull;
        h ^= (h >> 29) ^ (uint64_t(k.y) * 0xbf58476d1ce4e5b9ull);
        h ^= (h >> 31) ^ (uint64_t(k.z) * 0x94d049bb133111ebull);
        return static_cast<size_t>(h ^ (h >> 32));
    }
};

}  // namespace

bool IsClosedSurface(const std::vector<const TriangleMesh*>& meshes) {
    std::unordered_map<PositionKey, uint32_t, PositionHash> welded;
    // Adding 0 makes -0 and +0 one position.
    const auto key = [](const Vec3& p) {
        return PositionKey{std::bit_cast<uint32_t>(p.x + 0.0f), std::bit_cast<uint32_t>(p.y + 0.0f),
                           std::bit_cast<uint32_t>(p.z + 0.0f)};
    };
    std::unordered_map<uint64_t, uint32_t> edges;  // directed edge (from << 32 | to) -> uses
    for (const TriangleMesh* mesh : meshes) {
        std::vector<uint32_t> ids(mesh->positions.size());
        for (size_t v = 0; v < ids.size(); ++v)
            ids[v] =
                welded.try_emplace(key(mesh->positions[v]), uint32_t(welded.size())).first->second;
        for (size_t i = 0; i + 2 < mesh->indices.size(); i += 3) {
            const uint32_t a = ids[mesh->indices[i]], b = ids[mesh->indices[i + 1]],
                           c = ids[mesh->indices[i + 2]];
            if (a == b || b == c || c == a) continue;
            for (const auto& [from, to] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}})
                ++edges[uint64_t(from) << 32 | to];
        }
    }
    if (edges.empty()) return false;
    for (const auto& [edge, uses] : edges) {
        const auto reverse = edges.find(edge << 32 | edge >> 32);
        if (uses != 1 || reverse == edges.end() || reverse->second != 1) return false;
    }
    return true;
}

}  // namespace pf
