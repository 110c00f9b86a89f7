// Loop subdivision: what Loop's rules guarantee, checked on meshes whose answer is known: a
// planar mesh stays in its plane (its boundary on its lines), a convex closed mesh shrinks into
// its hull and rounds off, triangles multiply by four a level, winding and normals face out.
#include "core/scene_io/pbrt/loop_subdivision.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace pf {
namespace {

// The octahedron |x| + |y| + |z| = 1, wound counter-clockwise seen from outside.
TriangleMesh Octahedron() {
    TriangleMesh mesh;
    mesh.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    mesh.indices = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    return mesh;
}

TEST(LoopSubdivisionTest, AClosedConvexMeshRoundsOffInsideItsHull) {
    const TriangleMesh control = Octahedron();
    const absl::StatusOr<TriangleMesh> smooth = LoopSubdivide(control, 3, 1 << 20);
    ASSERT_TRUE(smooth.ok()) << smooth.status();
    EXPECT_EQ(smooth->indices.size(), control.indices.size() * 64);
    ASSERT_EQ(smooth->normals.size(), smooth->positions.size());
    EXPECT_TRUE(smooth->uvs.empty());
    float nearest = 1e9f, farthest = 0;
    for (size_t v = 0; v < smooth->positions.size(); ++v) {
        const Vec3& p = smooth->positions[v];
        EXPECT_LE(std::abs(p.x) + std::abs(p.y) + std::abs(p.z), 1.0f + 1e-5f) << "inside the hull";
        EXPECT_GT(Dot(smooth->normals[v], p), 0.0f) << "normals face out";
        nearest = std::min(nearest, Length(p)), farthest = std::max(farthest, Length(p));
    }
    // The control mesh's radius runs from 1/sqrt(3) (face centres) to 1 (corners), a ratio of
    // 1.73; the subdivided one is far rounder.
    EXPECT_LT(farthest / nearest, 1.25f);
    // Winding kept: every face's normal points away from the centre.
    for (size_t i = 0; i < smooth->indices.size(); i += 3) {
        const Vec3 &a = smooth->positions[smooth->indices[i]],
                   &b = smooth->positions[smooth->indices[i + 1]],
                   &c = smooth->positions[smooth->indices[i + 2]];
        EXPECT_GT(Dot(Cross(b - a, c - a), a + b + c), 0.0f);
    }
}

// Where Loop's scheme takes interior vertex v of `mesh` in the limit: (1 - n chi) v + chi times
// the sum of its n neighbours, chi = 1 / (n + 3 / (8 beta)) (Loop 1987; Hoppe et al. 1994).
Vec3 LimitPoint(const TriangleMesh& mesh, uint32_t v) {
    std::vector<uint32_t> ring;
    for (size_t i = 0; i < mesh.indices.size(); i += 3)
        for (int k = 0; k < 3; ++k)
            if (mesh.indices[i + k] == v)
                for (int j = 1; j < 3; ++j) ring.push_back(mesh.indices[i + (k + j) % 3]);
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
    const float n = static_cast<float>(ring.size());
    const float beta = ring.size() == 3 ? 3.0f / 16.0f : 3.0f / (8.0f * n);
    const float chi = 1.0f / (n + 3.0f / (8.0f * beta));
    Vec3 sum(0.0f);
    for (const uint32_t u : ring) sum += mesh.positions[u];
    return mesh.positions[v] * (1.0f - n * chi) + sum * chi;
}

TEST(LoopSubdivisionTest, EveryVertexLiesOnTheLimitSurface) {
    // A vertex's limit point does not move as the mesh is subdivided, and the result's vertices
    // are their limit points (as pbrt-v4 places them): the octahedron's corner (valence 4:
    // chi = 1/8, its neighbours summing to zero) is at (1/2, 0, 0) at every level.
    for (int levels = 0; levels <= 4; ++levels) {
        const absl::StatusOr<TriangleMesh> mesh = LoopSubdivide(Octahedron(), levels, 1 << 20);
        ASSERT_TRUE(mesh.ok()) << mesh.status();
        EXPECT_NEAR(Length(mesh->positions[0] - Vec3(0.5f, 0, 0)), 0.0f, 1e-5f) << levels;
    }
    // An irregular mesh (a square pyramid: valences 3 and 4) likewise, vertex by vertex: each
    // control vertex ends at its limit point, whatever the level.
    TriangleMesh pyramid;
    pyramid.positions = {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0.3f}};
    pyramid.indices = {0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 1, 1, 4, 3, 1, 3, 2};
    for (int levels = 0; levels <= 2; ++levels) {
        const absl::StatusOr<TriangleMesh> finer = LoopSubdivide(pyramid, levels, 1 << 20);
        ASSERT_TRUE(finer.ok());
        for (uint32_t v = 0; v < pyramid.positions.size(); ++v)
            EXPECT_NEAR(Length(finer->positions[v] - LimitPoint(pyramid, v)), 0.0f, 1e-5f)
                << levels << " " << v;
    }
}

TEST(LoopSubdivisionTest, APlanarMeshStaysPlanarAndKeepsItsBoundary) {
    // Two triangles of the unit square in z = 0.
    TriangleMesh square;
    square.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    square.indices = {0, 1, 2, 0, 2, 3};
    const absl::StatusOr<TriangleMesh> smooth = LoopSubdivide(square, 2, 1 << 20);
    ASSERT_TRUE(smooth.ok()) << smooth.status();
    EXPECT_EQ(smooth->indices.size(), square.indices.size() * 16);
    for (const Vec3& p : smooth->positions) {
        EXPECT_EQ(p.z, 0.0f);
        EXPECT_TRUE(p.x >= 0 && p.x <= 1 && p.y >= 0 && p.y <= 1);
    }
    for (const Vec3& n : smooth->normals) EXPECT_NEAR(n.z, 1.0f, 1e-6f);
    // Boundary vertices stay on the square's edges (the boundary rules use boundary
    // neighbours only), and the corners, of valence 2 on the boundary, move along it.
    for (const Vec3& p : smooth->positions) {
        const bool on_edge = p.x == 0 || p.x == 1 || p.y == 0 || p.y == 1;
        const bool inside = p.x > 0 && p.x < 1 && p.y > 0 && p.y < 1;
        EXPECT_TRUE(on_edge || inside);
    }
}

TEST(LoopSubdivisionTest, RefusesWhatWouldExceedTheLimit) {
    const absl::StatusOr<TriangleMesh> big = LoopSubdivide(Octahedron(), 6, 10000);
    ASSERT_FALSE(big.ok());
    EXPECT_NE(big.status().message().find("would exceed the limit of 10000"), std::string::npos);
    EXPECT_FALSE(LoopSubdivide(Octahedron(), -1, 1 << 20).ok());
    // Level 0: the control mesh's triangles, its vertices at their limit points (pbrt-v4's).
    const absl::StatusOr<TriangleMesh> same = LoopSubdivide(Octahedron(), 0, 1 << 20);
    ASSERT_TRUE(same.ok());
    EXPECT_EQ(same->indices, Octahedron().indices);
    for (uint32_t v = 0; v < 6; ++v)
        EXPECT_NEAR(Length(same->positions[v] - LimitPoint(Octahedron(), v)), 0.0f, 1e-6f);
}

}  // namespace
}  // namespace pf
