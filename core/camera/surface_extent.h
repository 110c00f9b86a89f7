// How far a hit point's own surface reaches about it, probed with rays once per hit point, for
// a gather that keeps to that surface (core/shared/surface_edges.h): the reach per octant of its
// tangent plane, which the estimate turns into the epoch's edges (SurfaceExtent::Edges) and the
// area it divides by (SurfaceExtent::AreaFraction).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/geometry/tracer.h"
#include "core/job/hit_point.h"
#include "core/scene/scene.h"
#include "core/shared/surface_edges.h"

namespace pf {

struct SurfaceExtent {
    // Per octant of the hit point's tangent plane (gpu::EdgeSector), the distance within which
    // its surface goes on every way through the octant (world units): to a surface of another
    // facing rising from it, or to where it falls away; infinite where it goes on past the probe.
    std::array<float, gpu::kEdgeSectors> reach;

    // A surface that goes on every way.
    static SurfaceExtent Unbounded();
    // The edges the gather tests for search radius `radius` (gpu::WithinSurfaceEdges): each
    // octant's reach in 255ths of the radius, rounded down, so the region stays on the surface.
    uint64_t Edges(double radius) const;
    // The area of that region (each octant's sector to its reach, as Edges rounds it) over
    // pi radius^2; at least 1/2040 (a region with none holds no photons either).
    double AreaFraction(double radius) const;
};

// The extent of `hit_point`'s surface within `length` (> 0, world units). Each octant is
// probed along its middle and its two sides (a straight edge is nearest along one of them, or
// along its normal, at most 1/cos(11.25 deg), 2%, nearer than the probes saw), in the plane of
// the surface's geometric normal under the hit point (a bump map's tilt is no edge), with rays
// along that plane for a surface rising from it and rays down onto it for where it falls away.
SurfaceExtent ProbeSurfaceExtent(const Scene& scene, const Tracer& tracer,
                                 const HitPoint& hit_point, float length);

// Each hit point's extent within its `length` (Unbounded where that is 0, or the hit point is
// black: an empty slot). In parallel on the calling TBB arena; the result does not depend on
// the thread count.
std::vector<SurfaceExtent> ProbeSurfaceExtents(const Scene& scene, const Tracer& tracer,
                                               std::span<const HitPoint> hit_points,
                                               std::span<const float> length);

}  // namespace pf
