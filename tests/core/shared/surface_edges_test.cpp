// A hit point's gather region (core/shared/surface_edges.h), worked out by hand.
#include "core/shared/surface_edges.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pf {
namespace {

TEST(SurfaceEdgesTest, OctantsCountFromSTowardT) {
    for (uint32_t j = 0; j < gpu::kEdgeSectors; ++j) {
        const double middle = (j + 0.5) * kPiD / 4;  // each octant's middle
        EXPECT_EQ(gpu::EdgeSector(float(std::cos(middle)), float(std::sin(middle))), j);
    }
    // Either side of each quarter turn.
    EXPECT_EQ(gpu::EdgeSector(1, 1e-3f), 0u);
    EXPECT_EQ(gpu::EdgeSector(1, -1e-3f), 7u);
    EXPECT_EQ(gpu::EdgeSector(1e-3f, 1), 1u);
    EXPECT_EQ(gpu::EdgeSector(-1e-3f, 1), 2u);
    EXPECT_EQ(gpu::EdgeSector(-1, 1e-3f), 3u);
    EXPECT_EQ(gpu::EdgeSector(-1, -1e-3f), 4u);
    EXPECT_EQ(gpu::EdgeSector(-1e-3f, -1), 5u);
    EXPECT_EQ(gpu::EdgeSector(1e-3f, -1), 6u);
}

TEST(SurfaceEdgesTest, TheSameSurfaceIsWithinSixtyDegrees) {
    const Vec3 n(0, 0, 2);  // any length
    const auto tilted = [](double degrees) {
        const double a = degrees * kPiD / 180;
        return Vec3(float(std::sin(a)), 0, float(std::cos(a)));
    };
    EXPECT_TRUE(gpu::SameSurface(n, tilted(0)));
    EXPECT_TRUE(gpu::SameSurface(n, tilted(59)));  // a bump map's tilt, a curved surface's
    EXPECT_FALSE(gpu::SameSurface(n, tilted(61)));
    EXPECT_FALSE(gpu::SameSurface(n, tilted(90)));   // the next wall
    EXPECT_FALSE(gpu::SameSurface(n, tilted(180)));  // the other side
}

TEST(SurfaceEdgesTest, APhotonCountsWithinItsOctantsReach) {
    // A hit point on the floor (normal +z): octant 0 reaches half the radius, the rest all of it.
    const Vec3 n(0, 0, 1), up(0, 0, 1);
    Vec3 s, t;
    gpu::OrthonormalBasis(n, s, t);
    const uint64_t edges = (gpu::kUnboundedEdges << 8) | 127u;  // 127 / 255 of R in octant 0
    const float radius_sq = 4;                                  // R = 2
    const Vec3 in_octant_0 = Normalize(s * 2.0f + t);           // 26.6 degrees from s
    EXPECT_TRUE(gpu::WithinSurfaceEdges(edges, n, up, in_octant_0 * 0.99f, radius_sq));
    EXPECT_FALSE(gpu::WithinSurfaceEdges(edges, n, up, in_octant_0 * 1.01f, radius_sq));
    EXPECT_TRUE(gpu::WithinSurfaceEdges(edges, n, up, t * 1.9f, radius_sq));  // octant 2
    // A photon on another surface counts only where no edge bounds the region.
    const Vec3 wall(1, 0, 0);
    EXPECT_FALSE(gpu::WithinSurfaceEdges(edges, n, wall, t * 0.5f, radius_sq));
    EXPECT_TRUE(gpu::WithinSurfaceEdges(gpu::kUnboundedEdges, n, wall, t * 0.5f, radius_sq));
}

}  // namespace
}  // namespace pf
