// Reading PLY meshes (ASCII and binary of either byte order) held in memory, by our own parser.
#pragma once

#include <string>
#include <string_view>

#include "absl/status/statusor.h"
#include "core/scene/mesh_builder.h"

namespace pf {

// The triangles of PLY file `name` with its contents `bytes` (decompressed already: a .ply.gz
// goes through Gunzip first): the "vertex" element's x y z, its normals nx ny nz where it has
// all three, its texture coordinates under the first pair it has of u v, s t, texture_u
// texture_v, texture_s texture_t; the "face" element's list "vertex_indices" (or
// "vertex_index"), polygons of 3 or more vertices split into a fan of triangles from their first
// vertex, faces of fewer dropped. Every other element and property is skipped.
// Errors are one line naming `name` and where (element and index; the line in ASCII data):
// a malformed header, truncated data, an index outside the vertices, a position that is not
// finite, a file without a polygon (points and lines only): INVALID_ARGUMENT; more triangles
// than `limits.max_triangles`: RESOURCE_EXHAUSTED. Nothing is read past `bytes`, and nothing is
// allocated for more instances than the bytes can hold.
absl::StatusOr<TriangleMesh> ReadPly(std::string_view bytes, const std::string& name,
                                     const SceneLimits& limits);

}  // namespace pf
