// pbrt-v4's texture mappings (TextureMapping2D): how a texture's (s, t) come from a surface
// point. "uv" reads the mesh's own coordinates, scaled and offset; "planar", "spherical" and
// "cylindrical" compute them from the point's position, which photonfarm does once per vertex
// when a shape is added, so lookups pay nothing for them.
#pragma once

#include "absl/status/statusor.h"
#include "core/math/transform.h"
#include "core/scene/mesh_builder.h"
#include "core/scene_io/pbrt/pbrt_parameters.h"

namespace pf::pbrt {

struct TextureMapping {
    enum class Kind { kUv, kPlanar, kSpherical, kCylindrical };
    Kind kind = Kind::kUv;
    // From (u, v) (kUv) or (s, t) (the others) to the image's coordinates: the uv mapping's
    // scales and offsets, pbrt's t pointing up the image, a baked texture's period.
    UvTransform uv;
    // Planar, spherical and cylindrical: from world space into the texture's, the inverse of
    // the transform current at the Texture directive (pbrt-v4's textureFromRender: its render
    // space's offset from the world cancels).
    Transform texture_from_world;
    // Planar: s = ds + q . vs, t = dt + q . vt, q the point in the texture's space.
    Vec3d vs{1, 0, 0}, vt{0, 1, 0};
    double ds = 0, dt = 0;

    bool FromMesh() const { return kind == Kind::kUv; }
    bool operator==(const TextureMapping& other) const;
};

// The mapping a Texture directive's parameters give ("mapping", "uscale" ... for uv; "v1",
// "v2", "udelta", "vdelta" for planar), `world_from_texture` the transform current there. Its
// `uv` maps to pbrt's (s, t), t up; the caller composes the image's own. An unknown mapping or
// a singular transform is an error.
absl::StatusOr<TextureMapping> ParseMapping(ParameterList& parameters,
                                            const Transform& world_from_texture);

// `mesh` with its texture coordinates computed by `mapping` (not kUv) from its vertices placed
// in the world by `world`: (s, t) at each corner. Planar coordinates are affine in the
// position, so a triangle's are exact between its corners; spherical and cylindrical ones are
// interpolated from the corners, each triangle's own (corners unshared), the angle about the
// axis taken within half a turn of the other corners' so that a triangle across the seam does
// not span the image, and at a corner on the axis (a pole), where it has none, their mean.
TriangleMesh MapTextureCoordinates(const TriangleMesh& mesh, const Transform& world,
                                   const TextureMapping& mapping);

}  // namespace pf::pbrt
