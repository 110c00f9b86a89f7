// Probing a hit point's surface for where it ends.
#include "core/camera/surface_extent.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/sampling/frame.h"
#include "core/util/check.h"

namespace pf {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();
// The probes' directions: the octants' sides and middles, every 22.5 degrees from s; octant j
// spans probes 2j to 2j + 2.
constexpr int kProbes = 2 * gpu::kEdgeSectors;
// Halvings that place a falling edge between the last distance the surface held and the
// first it did not: to 1/16 of the span.
constexpr int kEdgeSteps = 4;

// Where each active ray first meets a surface that the hit point of normal `n` would not take
// for its own (gpu::SameSurface, the surface's normal turned toward the ray): its distance,
// kInfinity where it meets none or its own surface first (`own`, where given, tells which).
// The active rays go in packets, as few as they fill.
void ProbeRays(const Scene& scene, const Tracer& tracer, const Vec3& n, const Ray* rays,
               const bool* active, float* distance, bool* own) {
    int next = 0;
    while (true) {
        Ray packet[Tracer::kPacketSize];
        int index[Tracer::kPacketSize];
        bool on[Tracer::kPacketSize] = {}, found[Tracer::kPacketSize];
        RayHit hits[Tracer::kPacketSize];
        int count = 0;
        for (; next < kProbes && count < Tracer::kPacketSize; ++next)
            if (active[next]) {
                packet[count] = rays[next];
                index[count] = next;
                on[count++] = true;
            }
        if (count == 0) return;
        tracer.IntersectPacket(packet, on, hits, found);
        for (int k = 0; k < count; ++k) {
            float& d = distance[index[k]];
            d = kInfinity;
            if (own != nullptr) own[index[k]] = false;
            if (!found[k]) continue;
            Vec3 facing = scene.Surface(hits[k]).geometric_normal;
            if (Dot(facing, packet[k].direction) > 0) facing = -facing;
            const bool same = gpu::SameSurface(n, facing);
            if (own != nullptr) own[index[k]] = same;
            if (!same) d = hits[k].t;
        }
    }
}

}  // namespace

SurfaceExtent SurfaceExtent::Unbounded() {
    SurfaceExtent extent;
    extent.reach.fill(kInfinity);
    return extent;
}

uint64_t SurfaceExtent::Edges(double radius) const {
    uint64_t edges = 0;
    for (uint32_t j = 0; j < gpu::kEdgeSectors; ++j) {
        const double share = radius > 0 ? std::min(1.0, double(reach[j]) / radius) : 1.0;
        edges |= uint64_t(std::floor(share * gpu::kEdgeReachFull)) << (8 * j);
    }
    return edges;
}

double SurfaceExtent::AreaFraction(double radius) const {
    const uint64_t edges = Edges(radius);
    if (edges == gpu::kUnboundedEdges) return 1.0;
    double sum = 0;
    for (uint32_t j = 0; j < gpu::kEdgeSectors; ++j) {
        const double share = double((edges >> (8 * j)) & 255) / gpu::kEdgeReachFull;
        sum += share * share;
    }
    return std::max(sum / gpu::kEdgeSectors, 1.0 / 2040);
}

SurfaceExtent ProbeSurfaceExtent(const Scene& scene, const Tracer& tracer,
                                 const HitPoint& hit_point, float length) {
    PF_CHECK(length > 0);
    // The octants are the gather's, in the tangent plane of the hit point's shading normal
    // (gpu::WithinSurfaceEdges); the probes run in its surface's own plane, of the geometric
    // normal under it, so that a bump map's tilt of the shading normal is no edge.
    const Frame frame = FrameFromNormal(hit_point.normal);
    const float scale = scene.bounds.Magnitude();
    // Off the surface by a little of the probe, so that rays along the plane clear the
    // surface's own unevenness (its facets).
    const float lift = 0.02f * length;
    Vec3 n = frame.n;
    if (RayHit under; tracer.Intersect(
            {OffsetRayOrigin(hit_point.position + n * lift, n, scale), -n, 2 * lift}, &under)) {
        Vec3 geometric = scene.Surface(under).geometric_normal;
        if (Dot(geometric, n) < 0) geometric = -geometric;
        if (gpu::SameSurface(n, geometric)) n = geometric;
    }
    const Vec3 origin = OffsetRayOrigin(hit_point.position + n * lift, n, scale);
    Vec3 direction[kProbes];
    Ray rays[kProbes];
    bool active[kProbes];
    float rise[kProbes], span[kProbes];
    for (int k = 0; k < kProbes; ++k) {
        const float phi = 2 * kPi * float(k) / kProbes;
        const Vec3 along = ToWorld(frame, {std::cos(phi), std::sin(phi), 0.0f});
        direction[k] = Normalize(along - n * Dot(along, n));
        rays[k] = {origin, direction[k], length};
    }
    // Whether the surface is still there at distance s along probe k: a short ray down from
    // above it meets the hit point's own surface first. Its reach (0.6 s each way) finds a
    // curved surface as far as its normal turns within SameSurface's 60 degrees (a sphere of
    // radius r drops r / 2 over the 0.87 r from its pole to there), and not the ground under a
    // platform's rim, lower than that.
    const auto down = [&](int k, float s) {
        const float reach = 0.6f * s + lift;
        return Ray{hit_point.position + direction[k] * s + n * reach, -n, 2 * reach};
    };
    float below[kProbes];
    bool own[kProbes];
    // Most hit points lie far from any edge: the octants' middles first, one packet each way,
    // and where nothing rises and the surface holds to the end of every one, it goes on.
    for (int k = 0; k < kProbes; ++k) active[k] = k % 2 == 1;
    ProbeRays(scene, tracer, n, rays, active, rise, nullptr);
    for (int k = 1; k < kProbes; k += 2) rays[k] = down(k, length);
    ProbeRays(scene, tracer, n, rays, active, below, own);
    bool clear = true;
    for (int k = 1; k < kProbes; k += 2) clear = clear && !std::isfinite(rise[k]) && own[k];
    if (clear) return SurfaceExtent::Unbounded();
    // A surface rising from this one (a wall from the floor) ends it where the ray meets it.
    for (int k = 0; k < kProbes; ++k) {
        rays[k] = {origin, direction[k], length};
        active[k] = true;
    }
    ProbeRays(scene, tracer, n, rays, active, rise, nullptr);
    for (int k = 0; k < kProbes; ++k) {
        // Short of a rising surface, whose foot a ray down along it would graze.
        span[k] = std::isfinite(rise[k]) ? rise[k] : length;
        rays[k] = down(k, std::isfinite(rise[k]) ? 0.9f * span[k] : span[k]);
    }
    ProbeRays(scene, tracer, n, rays, active, below, own);
    // Where it falls away first (a block's rim), find the edge: halving [held, lost], and
    // keeping the last distance it held, so that the region stays on the surface.
    bool falls[kProbes];
    float held[kProbes], lost[kProbes];
    for (int k = 0; k < kProbes; ++k) {
        falls[k] = active[k] = !own[k];
        held[k] = 0;
        lost[k] = span[k];
    }
    for (int step = 0; step < kEdgeSteps; ++step) {
        for (int k = 0; k < kProbes; ++k)
            if (active[k]) rays[k] = down(k, 0.5f * (held[k] + lost[k]));
        ProbeRays(scene, tracer, n, rays, active, below, own);
        for (int k = 0; k < kProbes; ++k)
            if (active[k]) (own[k] ? held[k] : lost[k]) = 0.5f * (held[k] + lost[k]);
    }
    float free[kProbes];
    for (int k = 0; k < kProbes; ++k) free[k] = falls[k] ? held[k] : rise[k];
    SurfaceExtent extent;
    for (uint32_t j = 0; j < gpu::kEdgeSectors; ++j)
        extent.reach[j] = std::min({free[2 * j], free[2 * j + 1], free[(2 * j + 2) % kProbes]});
    return extent;
}

std::vector<SurfaceExtent> ProbeSurfaceExtents(const Scene& scene, const Tracer& tracer,
                                               std::span<const HitPoint> hit_points,
                                               std::span<const float> length) {
    PF_CHECK(length.size() == hit_points.size());
    std::vector<SurfaceExtent> extents(hit_points.size(), SurfaceExtent::Unbounded());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, hit_points.size(), 256),
                      [&](const tbb::blocked_range<size_t>& range) {
                          for (size_t i = range.begin(); i < range.end(); ++i)
                              if (length[i] > 0 && !IsBlack(hit_points[i].weight))
                                  extents[i] =
                                      ProbeSurfaceExtent(scene, tracer, hit_points[i], length[i]);
                      });
    return extents;
}

}  // namespace pf
