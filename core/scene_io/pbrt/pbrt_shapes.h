// pbrt-v4 shapes as triangle meshes in object space: trianglemesh and bilinearmesh as given,
// sphere and disk tessellated finely enough that their facets stay below a pixel in the
// scenes photonfarm renders (with interpolated normals, so glass spheres refract smoothly);
// and curves as cubic Bezier segments.
#pragma once

#include <vector>

#include "absl/status/statusor.h"
#include "core/scene/mesh_builder.h"
#include "core/scene/scene.h"
#include "core/scene_io/pbrt/pbrt_parameters.h"

namespace pf::pbrt {

// Segments around a full turn, and rings from pole to pole, of a tessellated sphere or disk.
inline constexpr int kQuadricSegments = 128, kSphereRings = 64;

// "point3 P", "integer indices" (optional for exactly 3 vertices), "normal N", "point2 uv".
absl::StatusOr<TriangleMesh> TriangleMeshShape(ParameterList& parameters, const Location& where);
// Bilinear patches given by "point3 P" and 4 "indices" each (p00 p10 p01 p11), two triangles a
// patch.
absl::StatusOr<TriangleMesh> BilinearMeshShape(ParameterList& parameters, const Location& where);
// "radius" (1), "zmin" (-radius), "zmax" (radius), "phimax" (360): normals point outward,
// uv as pbrt's (phi / phimax, (theta - theta_min) / (theta_max - theta_min)).
absl::StatusOr<TriangleMesh> SphereShape(ParameterList& parameters, const Location& where);
// "height" (0), "radius" (1), "innerradius" (0), "phimax" (360): facing +z.
absl::StatusOr<TriangleMesh> DiskShape(ParameterList& parameters, const Location& where);
// "radius" (1), "zmin" (-1), "zmax" (1), "phimax" (360): about the z axis, normals outward,
// open at both ends.
absl::StatusOr<TriangleMesh> CylinderShape(ParameterList& parameters, const Location& where);

// pbrt-v4's "curve": "point3 P" control points, "string basis" ("bezier" or "bspline"),
// "integer degree" (3 or 2), "string type" ("flat", "cylinder" or "ribbon"), "normal N" (a
// ribbon's, one at each segment's ends), "float width" (1), "width0" and "width1" (its ends';
// linear along the curve between), "integer splitdepth" (read and unused: a hint for pbrt's own
// BVH). Its cubic Bezier segments in object space (material 0), each with its share of the
// width and, for a ribbon, its end normals (unit). `ignored_normals` is set where "N" was given
// to a curve that is not a ribbon (pbrt-v4 warns and ignores them).
absl::StatusOr<std::vector<Curve>> CurveShape(ParameterList& parameters, const Location& where,
                                              bool* ignored_normals);

}  // namespace pf::pbrt
