// Loop subdivision: one round at a time over an edge map.
#include "core/scene/loop_subdivision.h"

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

TriangleMesh Round(const TriangleMesh& mesh) {
    const size_t vertices = mesh.positions.size(), triangles = mesh.indices.size() / 3;
    std::unordered_map<uint64_t, EdgeInfo> edges;
    edges.reserve(3 * triangles);
    for (size_t t = 0; t < triangles; ++t)
        for (int e = 0; e < 3; ++e) {
            const uint32_t a = mesh.indices[3 * t + e], b = mesh.indices[3 * t + (e + 1) % 3];
            EdgeInfo& edge = edges[EdgeKey(a, b)];
            if (edge.faces < 2) edge.opposite[edge.faces] = mesh.indices[3 * t + (e + 2) % 3];
            ++edge.faces;
        }
    // Each vertex's neighbours, and those along boundary edges.
    std::vector<Vec3> ring_sum(vertices, Vec3(0.0f)), boundary_sum(vertices, Vec3(0.0f));
    std::vector<uint32_t> valence(vertices, 0), boundary(vertices, 0);
    TriangleMesh out;
    out.positions.resize(vertices + edges.size());
    uint32_t next = static_cast<uint32_t>(vertices);
    for (auto& [key, edge] : edges) {
        const auto a = static_cast<uint32_t>(key >> 32), b = static_cast<uint32_t>(key);
        const Vec3 &pa = mesh.positions[a], &pb = mesh.positions[b];
        ring_sum[a] += pb, ring_sum[b] += pa, ++valence[a], ++valence[b];
        edge.odd = next++;
        if (edge.faces == 2) {
            out.positions[edge.odd] =
                (pa + pb) * 0.375f +
                (mesh.positions[edge.opposite[0]] + mesh.positions[edge.opposite[1]]) * 0.125f;
        } else {  // a boundary (or an edge of more than two faces): the midpoint
            out.positions[edge.odd] = (pa + pb) * 0.5f;
            boundary_sum[a] += pb, boundary_sum[b] += pa, ++boundary[a], ++boundary[b];
        }
    }
    for (size_t v = 0; v < vertices; ++v) {
        const Vec3& p = mesh.positions[v];
        if (boundary[v] == 2) {
            out.positions[v] = p * 0.75f + boundary_sum[v] * 0.125f;
        } else if (boundary[v] == 0 && valence[v] > 0) {
            const float n = static_cast<float>(valence[v]);
            const float beta = valence[v] == 3 ? 3.0f / 16.0f : 3.0f / (8.0f * n);
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
