// Loop subdivision: one round at a time over an edge map.
#include "core/scene_io/pbrt/loop_subdivision.h"

#include <unordered_map>
#include <vector>

#include "absl/strings/str_cat.h"

namespace pf {
namespace {

struct EdgeInfo {
    uint32_t odd = 0;               // the new vertex on the edge
    uint32_t faces = 0;             // faces sharing it: 1 on a boundary
    uint32_t opposite[2] = {0, 0};  // the vertex across the edge in its first two faces
};

uint64_t EdgeKey(uint32_t a, uint32_t b) {
    return a < b ? (uint64_t{a} << 32) | b : (uint64_t{b} << 32) | a;
}

using EdgeMap = std::unordered_map<uint64_t, EdgeInfo>;

// Every edge of the mesh, with its faces and opposite vertices.
EdgeMap Edges(const TriangleMesh& mesh) {
    const size_t triangles = mesh.indices.size() / 3;
    EdgeMap edges;
    edges.reserve(3 * triangles);
    for (size_t t = 0; t < triangles; ++t)
        for (int e = 0; e < 3; ++e) {
            const uint32_t a = mesh.indices[3 * t + e], b = mesh.indices[3 * t + (e + 1) % 3];
            EdgeInfo& edge = edges[EdgeKey(a, b)];
            if (edge.faces < 2) edge.opposite[edge.faces] = mesh.indices[3 * t + (e + 2) % 3];
            ++edge.faces;
        }
    return edges;
}

// Each vertex's neighbours (their sum and count), and those along boundary edges.
struct Rings {
    std::vector<Vec3> ring_sum, boundary_sum;
    std::vector<uint32_t> valence, boundary;
};
Rings RingsOf(const TriangleMesh& mesh, const EdgeMap& edges) {
    const size_t vertices = mesh.positions.size();
    Rings rings{std::vector<Vec3>(vertices, Vec3(0.0f)), std::vector<Vec3>(vertices, Vec3(0.0f)),
                std::vector<uint32_t>(vertices, 0), std::vector<uint32_t>(vertices, 0)};
    for (const auto& [key, edge] : edges) {
        const auto a = static_cast<uint32_t>(key >> 32), b = static_cast<uint32_t>(key);
        const Vec3 &pa = mesh.positions[a], &pb = mesh.positions[b];
        rings.ring_sum[a] += pb, rings.ring_sum[b] += pa, ++rings.valence[a], ++rings.valence[b];
        if (edge.faces != 2)
            rings.boundary_sum[a] += pb, rings.boundary_sum[b] += pa, ++rings.boundary[a],
                ++rings.boundary[b];
    }
    return rings;
}

// Loop's weight of each neighbour of an interior vertex of valence n.
float Beta(uint32_t n) { return n == 3 ? 3.0f / 16.0f : 3.0f / (8.0f * static_cast<float>(n)); }

TriangleMesh Round(const TriangleMesh& mesh) {
    const size_t vertices = mesh.positions.size(), triangles = mesh.indices.size() / 3;
    EdgeMap edges = Edges(mesh);
    const Rings rings = RingsOf(mesh, edges);
    TriangleMesh out;
    out.positions.resize(vertices + edges.size());
    uint32_t next = static_cast<uint32_t>(vertices);
    for (auto& [key, edge] : edges) {
        const auto a = static_cast<uint32_t>(key >> 32), b = static_cast<uint32_t>(key);
        const Vec3 &pa = mesh.positions[a], &pb = mesh.positions[b];
        edge.odd = next++;
        if (edge.faces == 2) {
            out.positions[edge.odd] =
                (pa + pb) * 0.375f +
                (mesh.positions[edge.opposite[0]] + mesh.positions[edge.opposite[1]]) * 0.125f;
        } else {  // a boundary (or an edge of more than two faces): the midpoint
            out.positions[edge.odd] = (pa + pb) * 0.5f;
        }
    }
    const std::vector<Vec3>&ring_sum = rings.ring_sum, &boundary_sum = rings.boundary_sum;
    const std::vector<uint32_t>&valence = rings.valence, &boundary = rings.boundary;
    for (size_t v = 0; v < vertices; ++v) {
        const Vec3& p = mesh.positions[v];
        if (boundary[v] == 2) {
            out.positions[v] = p * 0.75f + boundary_sum[v] * 0.125f;
        } else if (boundary[v] == 0 && valence[v] > 0) {
            const float n = static_cast<float>(valence[v]), beta = Beta(valence[v]);
            out.positions[v] = p * (1.0f - n * beta) + ring_sum[v] * beta;
        } else {
            out.positions[v] = p;  // a corner or a non-manifold vertex stays
        }
    }
    out.indices.reserve(4 * mesh.indices.size());
    for (size_t t = 0; t < triangles; ++t) {
        const uint32_t* v = &mesh.indices[3 * t];
        const uint32_t e01 = edges[EdgeKey(v[0], v[1])].odd, e12 = edges[EdgeKey(v[1], v[2])].odd,
                       e20 = edges[EdgeKey(v[2], v[0])].odd;
        for (const uint32_t index : {v[0], e01, e20, v[1], e12, e01, v[2], e20, e12, e01, e12, e20})
            out.indices.push_back(index);
    }
    return out;
}

// Every vertex moved to where infinitely many rounds would take it, as pbrt-v4 moves them
// (Loop's limit masks): an interior vertex of valence n to (1 - n gamma) p + gamma sum of its
// neighbours, gamma = 1 / (n + 3 / (8 beta)); a boundary vertex to 3/5 p + 1/5 of each
// boundary neighbour; corners and non-manifold vertices stay.
void ProjectToLimit(TriangleMesh& mesh) {
    const Rings rings = RingsOf(mesh, Edges(mesh));
    std::vector<Vec3> limit = mesh.positions;
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
        const Vec3& p = mesh.positions[v];
        if (rings.boundary[v] == 2) {
            limit[v] = p * 0.6f + rings.boundary_sum[v] * 0.2f;
        } else if (rings.boundary[v] == 0 && rings.valence[v] > 0) {
            const float n = static_cast<float>(rings.valence[v]);
            const float gamma = 1.0f / (n + 3.0f / (8.0f * Beta(rings.valence[v])));
            limit[v] = p * (1.0f - n * gamma) + rings.ring_sum[v] * gamma;
        }
    }
    mesh.positions = std::move(limit);
}

}  // namespace

absl::StatusOr<TriangleMesh> LoopSubdivide(const TriangleMesh& control, int levels,
                                           uint64_t max_triangles) {
    if (levels < 0 || levels > 10)
        return absl::InvalidArgumentError(
            absl::StrCat("loopsubdiv: levels ", levels, " is not in [0, 10]"));
    const uint64_t triangles = control.indices.size() / 3;
    if (triangles << (2 * levels) > max_triangles)
        return absl::ResourceExhaustedError(
            absl::StrCat("loopsubdiv: ", triangles, " triangles subdivided ", levels,
                         " times would exceed the limit of ", max_triangles));
    TriangleMesh mesh{control.positions, {}, {}, control.indices};
    for (int level = 0; level < levels; ++level) mesh = Round(mesh);
    ProjectToLimit(mesh);
    mesh.normals.assign(mesh.positions.size(), Vec3(0.0f));
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        const uint32_t a = mesh.indices[i], b = mesh.indices[i + 1], c = mesh.indices[i + 2];
        // The cross product's length is twice the area: an area-weighted sum.
        const Vec3 n =
            Cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
        mesh.normals[a] += n, mesh.normals[b] += n, mesh.normals[c] += n;
    }
    for (Vec3& n : mesh.normals) {
        const float length = Length(n);
        n = length > 0 ? n / length : Vec3(0.0f, 0.0f, 1.0f);
    }
    return mesh;
}

}  // namespace pf
