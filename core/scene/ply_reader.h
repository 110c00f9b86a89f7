// Reading PLY meshes (ASCII and binary) held in memory, through Assimp.
#pragma once

#include <string>
#include <string_view>

#include "absl/status/statusor.h"
#include "core/scene/mesh_builder.h"

namespace pf {

// The triangles of PLY file `name` with its contents `bytes`: positions, and normals and
// texture coordinates where every vertex has them. Polygons are triangulated; points and
// lines are dropped. Errors name `name`; over `limits.max_triangles`: RESOURCE_EXHAUSTED.
absl::StatusOr<TriangleMesh> ReadPly(std::string_view bytes, const std::string& name,
                                     const SceneLimits& limits);

}  // namespace pf
