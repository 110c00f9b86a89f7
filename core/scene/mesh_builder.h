// Appending a triangle mesh, given in its own space, to a Scene (its world, or a prototype that
// instances place): one place for what every scene format needs (transform, winding,
// degenerate triangles, instancing, limits).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/math/transform.h"
#include "core/scene/scene.h"

namespace pf {

struct TriangleMesh {
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;        // empty, or one per position
    std::vector<Point2> uvs;          // empty, or one per position
    std::vector<uint32_t> indices;    // 3 per triangle, each below positions.size()
    std::vector<Vec3> tangents;       // empty, or one per position (glTF's TANGENT): along +u
    std::vector<VertexColor> colors;  // empty, or one per position (glTF's COLOR_0), in [0, 1]
};

// Which side of a triangle is its front (where emission leaves and what "outside" is for glass).
enum class FrontFace {
    kObjectWinding,  // counter-clockwise in the mesh's own space, kept under a mirroring transform
                     // (glTF, pbrt meshes)
    kWorldWinding,   // counter-clockwise after the transform (pbrt's quadrics, which a mirror turns
                     // inside out)
    kVertexNormals,  // the side the interpolated vertex normals point to (pbrt meshes with "N")
};

// An affine map of texture coordinates: u' = m[0] u + m[1] v + m[2], v' = m[3] u + m[4] v + m[5]
// (glTF's KHR_texture_transform, pbrt's uscale/udelta and its v axis pointing up). Applied to
// the vertices when a mesh is added, so lookups pay nothing for it.
struct UvTransform {
    double m[6] = {1, 0, 0, 0, 1, 0};
    Point2 Apply(const Point2& uv) const {
        return {static_cast<float>(m[0] * uv.x + m[1] * uv.y + m[2]),
                static_cast<float>(m[3] * uv.x + m[4] * uv.y + m[5])};
    }
    UvTransform Then(const UvTransform& next) const;  // next after this
};

// Limits on what loading a scene may build, so a small hostile file cannot exhaust memory.
struct SceneLimits {
    uint64_t max_triangles = uint64_t{1}
                             << 26;  // 64 M stored (a prototype's once): ~5 GiB of scene
    uint64_t max_instances = uint64_t{1} << 24;     // 16 M: ~1.3 GiB
    uint64_t max_curves = uint64_t{1} << 24;        // 16 M Bezier segments: ~1.4 GiB
    uint64_t max_image_pixels = uint64_t{1} << 26;  // per image: 8192 x 8192
    int max_include_depth = 32;
};

struct MeshPlacement {
    Transform world;        // object to world
    uint32_t material = 0;  // index into Scene::materials
    FrontFace front = FrontFace::kObjectWinding;
    bool reverse = false;  // flip the front (pbrt's ReverseOrientation)
    UvTransform uv;
};

// Appends `mesh` placed by `placement` to the world or, given `prototype`, to that prototype,
// which must be the last begun (placement.world then maps into the prototype's space).
// Triangles with no area are dropped. Where its material has a normal map
// (Scene::NeedsTangents), its tangents are kept, or made where it has none (tangents.h).
// Errors name `element`: a vertex not finite after the
// transform, an index out of range, the triangle limit exceeded (RESOURCE_EXHAUSTED).
absl::Status AppendMesh(const TriangleMesh& mesh, const MeshPlacement& placement,
                        const SceneLimits& limits, const std::string& element, Scene* scene,
                        std::optional<uint32_t> prototype = std::nullopt);

// Starts a prototype, empty until meshes are appended to it; returns its index.
uint32_t BeginPrototype(Scene* scene);

// Places `prototype` in the world by `from_object` (a prototype without triangles or curves
// places nothing). Errors name `element`: a transform that is singular or not finite, the instance
// limit exceeded (RESOURCE_EXHAUSTED).
absl::Status AddInstance(uint32_t prototype, const Transform& from_object,
                         const SceneLimits& limits, const std::string& element, Scene* scene);

// Puts the world's triangles and curves before the prototypes' (Scene::WorldTriangleCount,
// WorldCurveCount), as loaders build them in file order; each loader calls it once, when done.
void FinishInstancing(Scene* scene);

// The scene with every instance expanded into world triangles and curves, no prototypes left
// (for a backend without instancing). RESOURCE_EXHAUSTED beyond `max_triangles` triangles or
// `max_curves` curves in all.
absl::StatusOr<Scene> FlattenInstances(const Scene& scene, uint64_t max_triangles,
                                       uint64_t max_curves = SceneLimits{}.max_curves);

}  // namespace pf
