// Whether a mesh encloses a volume, for the surfaces whose back faces can never be seen (glTF's
// single-sided meshes are culled only where they are open: gltf_loader.cpp).
#pragma once

#include <vector>

#include "core/scene/mesh_builder.h"

namespace pf {

// Whether the meshes' triangles, taken together with vertices welded where their positions are
// equal (a mesh's split seams joined), form a closed, consistently wound surface: every edge is
// crossed by exactly two triangles, in opposite directions (edge-manifold and oriented).
// Triangles with two corners at one position are left out; no triangles at all is not closed.
bool IsClosedSurface(const std::vector<const TriangleMesh*>& meshes);

}  // namespace pf
