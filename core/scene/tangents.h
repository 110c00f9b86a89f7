// Vertex tangents for normal maps where a mesh has none, with MikkTSpace's semantics (the
// tangents glTF asks for and tools bake normal maps against): each triangle's dP/du, from its
// texture coordinates, made perpendicular to each corner's normal and weighted by the corner's
// angle, summed per vertex and made perpendicular to the vertex normal. Where MikkTSpace splits
// a vertex between triangles of opposite texture orientation (a mirrored seam), one tangent
// serves both; the bitangent's side is taken per triangle where it is used
// (gpu::BitangentSign, core/shared/shading_normal.h).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/math/point2.h"
#include "core/math/vec3.h"

namespace pf {

// One unit tangent per vertex of `positions` (normals: one per vertex, zero where a vertex has
// none and its triangles' normals serve; uvs: one per vertex; indices: three per triangle).
// A vertex no triangle with texture-coordinate area touches gets a tangent perpendicular to
// its normal, chosen as gpu::OrthonormalBasis does.
std::vector<Vec3> GenerateTangents(std::span<const Vec3> positions, std::span<const Vec3> normals,
                                   std::span<const Point2> uvs, std::span<const uint32_t> indices);

}  // namespace pf
