// Loop subdivision (Loop 1987), for pbrt's "loopsubdiv" shape.
#pragma once

#include <cstdint>

#include "absl/status/statusor.h"
#include "core/scene/mesh_builder.h"

namespace pf {

// `levels` rounds of splitting every triangle of `control` in four, with Loop's weights: an
// edge's new vertex is 3/8 of its ends and 1/8 of the two opposite vertices (the mean of its
// ends on a boundary), an old vertex of valence n keeps 1 - n beta of itself and beta of each
// neighbour (beta = 3/16 for n = 3, else 3 / 8n; a boundary vertex 3/4 of itself and 1/8 of each
// boundary neighbour); then every vertex is moved onto the limit surface, as pbrt-v4 moves it
// (interior: 1 - n gamma of itself and gamma of each neighbour, gamma = 1 / (n + 3 / 8 beta);
// boundary: 3/5 of itself and 1/5 of each boundary neighbour). Winding is kept; the result
// carries vertex normals averaged from its faces by area, and no texture coordinates
// (pbrt-v4's loopsubdiv has none). Refused where the result would exceed `max_triangles`.
absl::StatusOr<TriangleMesh> LoopSubdivide(const TriangleMesh& control, int levels,
                                           uint64_t max_triangles);

}  // namespace pf
