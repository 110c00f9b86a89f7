// The hit-point hash grid finds exactly the hit points a brute-force search finds.
#include "core/ppm/hash_grid.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/sampling/rng.h"
#include "core/sampling/sampling.h"
#include "core/shared/surface_edges.h"

namespace pf {
namespace {

// Whether a hit point of normal n and `edges` gathers a photon at `offset` from it, within its
// sphere, that landed on a surface of normal `landed`, worked out apart from
// gpu::WithinSurfaceEdges: the octant by the angle from s toward t.
bool WithinEdges(uint64_t edges, const Vec3& n, const Vec3& landed, const Vec3& offset,
                 float radius_sq) {
    if (edges == gpu::kUnboundedEdges) return true;
    if (Dot(n, landed) < 0.5f) return false;
    Vec3 s, t;
    gpu::OrthonormalBasis(n, s, t);
    const double x = Dot(offset, s), y = Dot(offset, t);
    double angle = std::atan2(y, x);
    if (angle < 0) angle += 2 * kPiD;
    const int octant = std::min(7, int(angle / (kPiD / 4)));
    const double reach = double((edges >> (8 * octant)) & 255) / 255;
    return x * x + y * y <= reach * reach * radius_sq;
}

TEST(HashGridTest, MatchesBruteForceForMixedRadiiAndEdges) {
    Rng rng(5);
    std::vector<HitPoint> hit_points(3000);
    std::vector<float> radius_sq(hit_points.size());
    std::vector<uint64_t> edges(hit_points.size(), gpu::kUnboundedEdges);
    for (size_t i = 0; i < hit_points.size(); ++i) {
        hit_points[i] = {
            Vec3(rng.NextFloat(), rng.NextFloat(), rng.NextFloat()) * 4.0f - Vec3(2.0f),
            SampleUniformSphere(rng.NextFloat(), rng.NextFloat()), Rgb(0.5f), uint32_t(i)};
        const float r = 0.02f + 0.2f * rng.NextFloat();
        radius_sq[i] = i % 17 == 0 ? 0.0f : r * r;  // some hit points have no radius at all
        if (i % 3 == 0)                             // a third end within their radius somewhere
            for (int j = 0; j < 8; ++j) edges[i] ^= uint64_t(rng.NextUint() % 256) << (8 * j);
    }
    HashGrid grid;
    grid.Build(hit_points, radius_sq, edges);
    for (int query = 0; query < 5000; ++query) {
        const Vec3 p = Vec3(rng.NextFloat(), rng.NextFloat(), rng.NextFloat()) * 4.4f - Vec3(2.2f);
        const Vec3 direction = SampleUniformSphere(rng.NextFloat(), rng.NextFloat());
        // The surface it landed on, some facing its way, some not.
        Vec3 landed = SampleUniformSphere(rng.NextFloat(), rng.NextFloat());
        if (query % 2 == 0) landed = Normalize(landed - direction * 2.0f);
        // Each found hit point with whether p lies in its inner disc (R / sqrt(2)).
        std::vector<std::pair<uint32_t, bool>> found, expected;
        grid.ForEachGathering(
            p, direction, landed, kScatteredPhotons,
            [&](uint32_t i, bool inner, const Vec3&) { found.emplace_back(i, inner); });
        for (uint32_t i = 0; i < hit_points.size(); ++i) {
            const float distance_sq = LengthSquared(hit_points[i].position - p);
            if (radius_sq[i] > 0 && distance_sq <= radius_sq[i] &&
                Dot(hit_points[i].normal, direction) < 0 &&
                WithinEdges(edges[i],
                            Normalize(DecodeOctahedral(EncodeOctahedral(hit_points[i].normal))),
                            landed, p - hit_points[i].position, radius_sq[i]))
                expected.emplace_back(i, 2 * distance_sq <= radius_sq[i]);
        }
        std::sort(found.begin(), found.end());
        ASSERT_EQ(found, expected) << "query " << query;
    }
}

TEST(HashGridTest, VisitsInIndexOrderWhateverTheThreadsThatBuiltIt) {
    // The gather sums in visit order, so the order is part of the image: ascending hit point
    // index, from a grid built on one thread or on several.
    Rng rng(9);
    std::vector<HitPoint> hit_points(40000);
    std::vector<float> radius_sq(hit_points.size());
    for (size_t i = 0; i < hit_points.size(); ++i) {
        hit_points[i] = {Vec3(rng.NextFloat(), rng.NextFloat(), rng.NextFloat()), Vec3(0, 0, 1),
                         Rgb(0.5f), uint32_t(i)};
        radius_sq[i] = 0.004f * rng.NextFloat();
    }
    HashGrid one, four;
    tbb::task_arena(1).execute([&] { one.Build(hit_points, radius_sq); });
    tbb::task_arena(4).execute([&] { four.Build(hit_points, radius_sq); });
    int nonempty = 0;
    for (int query = 0; query < 2000; ++query) {
        const Vec3 p(rng.NextFloat(), rng.NextFloat(), rng.NextFloat());
        std::vector<uint32_t> from_one, from_four;
        one.ForEachGathering(p, Vec3(0, 0, -1), Vec3(0, 0, 1), kScatteredPhotons,
                             [&](uint32_t i, bool, const Vec3&) { from_one.push_back(i); });
        four.ForEachGathering(p, Vec3(0, 0, -1), Vec3(0, 0, 1), kScatteredPhotons,
                              [&](uint32_t i, bool, const Vec3&) { from_four.push_back(i); });
        ASSERT_EQ(from_one, from_four) << "query " << query;
        ASSERT_TRUE(std::is_sorted(from_one.begin(), from_one.end())) << "query " << query;
        nonempty += from_one.size() > 1;
    }
    EXPECT_GT(nonempty, 1000);  // most queries find several hit points
}

TEST(HashGridTest, RadiiFarBelowTheCoordinatesStillFindTheirPhotons) {
    // Radii shrinking toward zero far from the origin: cell indices would overflow without the
    // clamp. A photon exactly at a hit point must still be found, and a neighbour not.
    const std::vector<HitPoint> hit_points = {
        {Vec3(1e4f, -1e4f, 3e3f), Vec3(0, 0, 1), Rgb(0.5f), 0},
        {Vec3(1e4f, -1e4f + 1.0f, 3e3f), Vec3(0, 0, 1), Rgb(0.5f), 1}};
    const std::vector<float> radius_sq = {1e-30f, 1e-30f};
    HashGrid grid;
    grid.Build(hit_points, radius_sq);
    std::vector<uint32_t> found;
    grid.ForEachGathering(hit_points[0].position, Vec3(0, 0, -1), Vec3(0, 0, 1), kScatteredPhotons,
                          [&](uint32_t i, bool, const Vec3&) { found.push_back(i); });
    EXPECT_EQ(found, std::vector<uint32_t>{0});
}

TEST(HashGridTest, EmptyAndBlackHitPointsAreLeftOut) {
    HashGrid grid;
    grid.Build({}, {});
    int visits = 0;
    grid.ForEachGathering(Vec3(0.0f), Vec3(0, 0, -1), Vec3(0, 0, 1), kScatteredPhotons,
                          [&](uint32_t, bool, const Vec3&) { ++visits; });
    const std::vector<HitPoint> black = {{Vec3(0.0f), Vec3(0, 0, 1), Rgb(0.0f), 0}};
    const std::vector<float> radius_sq = {1.0f};
    grid.Build(black, radius_sq);
    grid.ForEachGathering(Vec3(0.0f), Vec3(0, 0, -1), Vec3(0, 0, 1), kScatteredPhotons,
                          [&](uint32_t, bool, const Vec3&) { ++visits; });
    EXPECT_EQ(visits, 0);
}

TEST(HashGridTest, EachHitPointGathersTheKindsOfPhotonItNames) {
    // Three hit points at one place: ppm's (every scattered photon), rpm's camera hit point
    // (caustics alone) and its gather hit (every photon, direct light's included).
    const std::vector<HitPoint> hit_points = {
        {Vec3(0.0f), Vec3(0, 0, 1), Rgb(0.5f), 0, kNoCoat, kScatteredPhotons},
        {Vec3(0.0f), Vec3(0, 0, 1), Rgb(0.5f), 0, kNoCoat, kCausticPhoton},
        {Vec3(0.0f), Vec3(0, 0, 1), Rgb(0.5f), 0, kNoCoat, kAllPhotons}};
    const std::vector<float> radius_sq(3, 1.0f);
    HashGrid grid;
    grid.Build(hit_points, radius_sq);
    const auto gathering = [&](uint32_t kind) {
        std::vector<uint32_t> found;
        grid.ForEachGathering(Vec3(0.1f, 0, 0), Vec3(0, 0, -1), Vec3(0, 0, 1), kind,
                              [&](uint32_t i, bool, const Vec3&) { found.push_back(i); });
        EXPECT_EQ(grid.Gathers(Vec3(0.1f, 0, 0), Vec3(0, 0, -1), Vec3(0, 0, 1), kind),
                  !found.empty());
        return found;
    };
    EXPECT_EQ(gathering(kDirectPhoton), (std::vector<uint32_t>{2}));
    EXPECT_EQ(gathering(kCausticPhoton), (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_EQ(gathering(kDiffusePhoton), (std::vector<uint32_t>{0, 2}));
}

}  // namespace
}  // namespace pf
