// pbrt-v4 shape parameters to triangle meshes.
#include "core/scene_io/pbrt/pbrt_shapes.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "core/math/vec3.h"

namespace pf::pbrt {
namespace {

// A bilinear patch is drawn as a grid of cells fine enough that its triangles lie within this
// fraction of its size from its surface (a cell twisted by t out of its plane lies within t/4
// of it: a patch twisted by under 0.5% of its size is two triangles, as the Cornell box's
// measured walls, 0.4%, are), and at most kMaxPatchGrid cells a side.
constexpr double kPatchTolerance = 1.25e-3;
constexpr int kMaxPatchGrid = 32;

absl::Status Invalid(const Location& where, const std::string& what) {
    return absl::InvalidArgumentError(absl::StrCat(where.ToString(), ": ", what));
}

// P, N and uv shared by the two mesh shapes.
absl::Status ReadVertices(ParameterList& parameters, const Location& where, TriangleMesh* mesh) {
    for (const Vec3d& p : parameters.Point3s("P")) mesh->positions.emplace_back(p);
    if (mesh->positions.empty()) return Invalid(where, "shape needs \"point3 P\"");
    for (const Vec3d& n : parameters.Normals("N")) mesh->normals.emplace_back(n);
    const std::vector<double> uv = parameters.Point2s("uv");
    for (size_t i = 0; i + 1 < uv.size(); i += 2)
        mesh->uvs.push_back({static_cast<float>(uv[i]), static_cast<float>(uv[i + 1])});
    if (!mesh->normals.empty() && mesh->normals.size() != mesh->positions.size())
        return Invalid(where, absl::StrCat("\"normal N\" has ", mesh->normals.size(),
                                           " normals for ", mesh->positions.size(), " points"));
    if (!mesh->uvs.empty() && mesh->uvs.size() != mesh->positions.size())
        return Invalid(where, absl::StrCat("\"point2 uv\" has ", mesh->uvs.size(), " values for ",
                                           mesh->positions.size(), " points"));
    for (size_t v = 0; v < mesh->positions.size(); ++v)
        if (!IsFinite(mesh->positions[v]))
            return Invalid(where, absl::StrCat("point ", v, " of \"point3 P\" is not finite"));
    return parameters.status();
}

absl::Status ReadIndices(ParameterList& parameters, const Location& where, size_t per_face,
                         TriangleMesh* mesh, std::vector<uint32_t>* indices) {
    const std::vector<int> given = parameters.Integers("indices");
    if (given.empty()) {
        if (mesh->positions.size() != per_face)
            return Invalid(where, absl::StrCat("shape needs \"integer indices\" (it has ",
                                               mesh->positions.size(), " points)"));
        for (uint32_t i = 0; i < per_face; ++i) indices->push_back(i);
        return absl::OkStatus();
    }
    if (given.size() % per_face != 0)
        return Invalid(where, absl::StrCat("\"integer indices\" has ", given.size(),
                                           " values, not a multiple of ", per_face));
    for (size_t i = 0; i < given.size(); ++i) {
        if (given[i] < 0 || static_cast<size_t>(given[i]) >= mesh->positions.size())
            return Invalid(where, absl::StrCat("index ", i, " (", given[i], ") is outside the ",
                                               mesh->positions.size(), " points"));
        indices->push_back(static_cast<uint32_t>(given[i]));
    }
    return absl::OkStatus();
}

// A full-turn angle parameter in degrees, in (0, 360].
absl::StatusOr<double> PhiMax(ParameterList& parameters, const Location& where) {
    const double degrees = parameters.Float("phimax", 360.0);
    if (!(degrees > 0 && degrees <= 360))
        return Invalid(where, "\"float phimax\" must lie in (0, 360]");
    return degrees * kPiD / 180.0;
}

}  // namespace

absl::StatusOr<TriangleMesh> TriangleMeshShape(ParameterList& parameters, const Location& where) {
    TriangleMesh mesh;
    if (absl::Status status = ReadVertices(parameters, where, &mesh); !status.ok()) return status;
    if (absl::Status status = ReadIndices(parameters, where, 3, &mesh, &mesh.indices); !status.ok())
        return status;
    return mesh;
}

absl::StatusOr<TriangleMesh> BilinearMeshShape(ParameterList& parameters, const Location& where) {
    TriangleMesh mesh;
    if (absl::Status status = ReadVertices(parameters, where, &mesh); !status.ok()) return status;
    std::vector<uint32_t> patches;
    if (absl::Status status = ReadIndices(parameters, where, 4, &mesh, &patches); !status.ok())
        return status;
    if (mesh.uvs.empty()) {
        // pbrt-v4 gives each patch without "uv" the unit square, p00 at (0, 0) and p11 at
        // (1, 1) (what an image area light or texture on a card reads): the patches' corners
        // are unshared for that.
        TriangleMesh unshared;
        const bool normals = !mesh.normals.empty();
        for (size_t i = 0; i < patches.size(); ++i) {
            unshared.positions.push_back(mesh.positions[patches[i]]);
            if (normals) unshared.normals.push_back(mesh.normals[patches[i]]);
            unshared.uvs.push_back({i % 2 == 0 ? 0.0f : 1.0f, (i / 2) % 2 == 0 ? 0.0f : 1.0f});
            patches[i] = static_cast<uint32_t>(i);
        }
        mesh = std::move(unshared);
    }
    // Corners p00 p10 p01 p11: around the patch they run p00, p10, p11, p01. A planar patch (or
    // one nearly so) is two triangles; a curved one a grid of cells on its bilinear surface,
    // with its normals, cross(dP/du, dP/dv) (or "N" interpolated).
    const auto cells = [&](size_t i) {
        const Vec3d p00(mesh.positions[patches[i]]), p10(mesh.positions[patches[i + 1]]),
            p01(mesh.positions[patches[i + 2]]), p11(mesh.positions[patches[i + 3]]);
        const Vec3d n = Cross(p10 - p00, p01 - p00);
        const double size = std::max({Length(p10 - p00), Length(p01 - p00), Length(p11 - p00)});
        const double twist = std::abs(Dot(p11 - p00, n)) / std::max(Length(n), 1e-300);
        const double grid = std::ceil(std::sqrt(twist / (4 * kPatchTolerance * size)));
        return std::isfinite(grid) ? std::clamp(static_cast<int>(grid), 1, kMaxPatchGrid) : 1;
    };
    bool curved = false;
    for (size_t i = 0; i < patches.size(); i += 4) curved |= cells(i) > 1;
    const bool normals = !mesh.normals.empty();
    if (curved && !normals) {  // every vertex gets one: each planar patch its own plane's
        TriangleMesh unshared;
        for (size_t i = 0; i < patches.size(); ++i) {
            const size_t first = i - i % 4;
            const Vec3 p00 = mesh.positions[patches[first]];
            unshared.positions.push_back(mesh.positions[patches[i]]);
            unshared.uvs.push_back(mesh.uvs[patches[i]]);
            unshared.normals.push_back(Normalize(Cross(mesh.positions[patches[first + 1]] - p00,
                                                       mesh.positions[patches[first + 2]] - p00)));
        }
        for (size_t i = 0; i < patches.size(); ++i) patches[i] = static_cast<uint32_t>(i);
        mesh = std::move(unshared);
    }
    for (size_t i = 0; i < patches.size(); i += 4) {
        const uint32_t p00 = patches[i], p10 = patches[i + 1], p01 = patches[i + 2],
                       p11 = patches[i + 3];
        const int grid = curved ? cells(i) : 1;
        if (grid == 1) {
            mesh.indices.insert(mesh.indices.end(), {p00, p10, p11, p00, p11, p01});
            continue;
        }
        const auto first = static_cast<uint32_t>(mesh.positions.size());
        const auto lerp = [&](const auto& a, const auto& b, const auto& c, const auto& d, float u,
                              float v) {
            return (a * (1 - u) + b * u) * (1 - v) + (c * (1 - u) + d * u) * v;
        };
        const Vec3 q00 = mesh.positions[p00], q10 = mesh.positions[p10], q01 = mesh.positions[p01],
                   q11 = mesh.positions[p11];
        for (int y = 0; y <= grid; ++y)
            for (int x = 0; x <= grid; ++x) {
                const float u = float(x) / grid, v = float(y) / grid;
                mesh.positions.push_back(lerp(q00, q10, q01, q11, u, v));
                const auto uv = [&](uint32_t corner) {
                    return Vec3(mesh.uvs[corner].x, mesh.uvs[corner].y, 0.0f);
                };
                const Vec3 st = lerp(uv(p00), uv(p10), uv(p01), uv(p11), u, v);
                mesh.uvs.push_back({st.x, st.y});
                const Vec3 dpdu = lerp(q10 - q00, q10 - q00, q11 - q01, q11 - q01, u, v);
                const Vec3 dpdv = lerp(q01 - q00, q11 - q10, q01 - q00, q11 - q10, u, v);
                mesh.normals.push_back(
                    normals ? Normalize(lerp(mesh.normals[p00], mesh.normals[p10],
                                             mesh.normals[p01], mesh.normals[p11], u, v))
                            : Normalize(Cross(dpdu, dpdv)));
            }
        const auto at = [&](int x, int y) { return first + uint32_t(y * (grid + 1) + x); };
        for (int y = 0; y < grid; ++y)
            for (int x = 0; x < grid; ++x)
                mesh.indices.insert(mesh.indices.end(), {at(x, y), at(x + 1, y), at(x + 1, y + 1),
                                                         at(x, y), at(x + 1, y + 1), at(x, y + 1)});
    }
    return mesh;
}

absl::StatusOr<TriangleMesh> SphereShape(ParameterList& parameters, const Location& where) {
    const double radius = parameters.Float("radius", 1.0);
    const double z_min = std::clamp(parameters.Float("zmin", -radius), -radius, radius);
    const double z_max = std::clamp(parameters.Float("zmax", radius), -radius, radius);
    const absl::StatusOr<double> phi_max = PhiMax(parameters, where);
    if (!parameters.status().ok()) return parameters.status();
    if (!phi_max.ok()) return phi_max.status();
    if (!(radius > 0 && std::isfinite(radius)))
        return Invalid(where, "\"float radius\" must be positive and finite");
    if (!(z_min < z_max)) return Invalid(where, "\"float zmin\" must be below \"float zmax\"");
    const double theta_min = std::acos(z_max / radius),
                 theta_max = std::acos(z_min / radius);  // from +z
    const int rings =
        std::max(2, static_cast<int>(std::ceil(kSphereRings * (theta_max - theta_min) / kPiD)));
    const int segments =
        std::max(3, static_cast<int>(std::ceil(kQuadricSegments * *phi_max / (2 * kPiD))));
    TriangleMesh mesh;
    for (int i = 0; i <= rings; ++i) {
        const double v = double(i) / rings, theta = theta_min + v * (theta_max - theta_min);
        for (int j = 0; j <= segments; ++j) {
            const double u = double(j) / segments, phi = u * *phi_max;
            const Vec3d n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                          std::cos(theta));
            mesh.positions.emplace_back(n * radius);
            mesh.normals.emplace_back(n);
            // pbrt's v runs from z_min up: theta_max down to theta_min.
            mesh.uvs.push_back({static_cast<float>(u), static_cast<float>(1.0 - v)});
        }
    }
    // Counter-clockwise seen from outside: phi grows counter-clockwise about +z, theta downward.
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const uint32_t a = i * (segments + 1) + j, b = (i + 1) * (segments + 1) + j;
            mesh.indices.insert(mesh.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
        }
    return mesh;
}

absl::StatusOr<TriangleMesh> DiskShape(ParameterList& parameters, const Location& where) {
    const double height = parameters.Float("height", 0.0);
    const double radius = parameters.Float("radius", 1.0);
    const double inner = parameters.Float("innerradius", 0.0);
    const absl::StatusOr<double> phi_max = PhiMax(parameters, where);
    if (!parameters.status().ok()) return parameters.status();
    if (!phi_max.ok()) return phi_max.status();
    if (!(radius > 0 && std::isfinite(radius) && inner >= 0 && inner < radius &&
          std::isfinite(height)))
        return Invalid(where, "disk needs 0 <= innerradius < radius, all finite");
    const int segments =
        std::max(3, static_cast<int>(std::ceil(kQuadricSegments * *phi_max / (2 * kPiD))));
    TriangleMesh mesh;
    for (int j = 0; j <= segments; ++j) {
        const double u = double(j) / segments, phi = u * *phi_max;
        const double c = std::cos(phi), s = std::sin(phi);
        // pbrt's v is 0 on the outer edge, 1 on the inner.
        mesh.positions.emplace_back(Vec3d(radius * c, radius * s, height));
        mesh.uvs.push_back({static_cast<float>(u), 0.0f});
        mesh.positions.emplace_back(Vec3d(inner * c, inner * s, height));
        mesh.uvs.push_back({static_cast<float>(u), 1.0f});
    }
    for (int j = 0; j < segments; ++j) {
        const uint32_t outer0 = 2 * j, inner0 = 2 * j + 1, outer1 = 2 * j + 2, inner1 = 2 * j + 3;
        mesh.indices.insert(mesh.indices.end(), {outer0, outer1, inner1, outer0, inner1, inner0});
    }
    return mesh;
}

absl::StatusOr<TriangleMesh> CylinderShape(ParameterList& parameters, const Location& where) {
    const double radius = parameters.Float("radius", 1.0);
    const double z_min = parameters.Float("zmin", -1.0), z_max = parameters.Float("zmax", 1.0);
    const absl::StatusOr<double> phi_max = PhiMax(parameters, where);
    if (!parameters.status().ok()) return parameters.status();
    if (!phi_max.ok()) return phi_max.status();
    if (!(radius > 0 && std::isfinite(radius) && std::isfinite(z_min) && std::isfinite(z_max) &&
          z_min != z_max))
        return Invalid(where, "cylinder needs a positive radius and zmin != zmax, all finite");
    const int segments =
        std::max(3, static_cast<int>(std::ceil(kQuadricSegments * *phi_max / (2 * kPiD))));
    TriangleMesh mesh;
    for (int j = 0; j <= segments; ++j) {
        const double u = double(j) / segments, phi = u * *phi_max;
        const Vec3d n(std::cos(phi), std::sin(phi), 0);
        for (const double v : {0.0, 1.0}) {
            mesh.positions.emplace_back(
                Vec3d(radius * n.x, radius * n.y, z_min + v * (z_max - z_min)));
            mesh.normals.emplace_back(n);
            mesh.uvs.push_back({static_cast<float>(u), static_cast<float>(v)});
        }
    }
    // Counter-clockwise seen from outside when z grows from zmin to zmax; pbrt's normal is
    // dp/du x dp/dv, which points inward when zmax < zmin: the winding follows it.
    const bool upward = z_max > z_min;
    for (int j = 0; j < segments; ++j) {
        const uint32_t bottom0 = 2 * j, top0 = 2 * j + 1, bottom1 = 2 * j + 2, top1 = 2 * j + 3;
        if (upward)
            mesh.indices.insert(mesh.indices.end(), {bottom0, bottom1, top1, bottom0, top1, top0});
        else
            mesh.indices.insert(mesh.indices.end(), {bottom0, top1, bottom1, bottom0, top0, top1});
    }
    if (!upward)
        for (Vec3& n : mesh.normals) n = -n;
    return mesh;
}

namespace {

Vec3d Lerp(double t, const Vec3d& a, const Vec3d& b) { return a + (b - a) * t; }

// One segment's cubic Bezier control points from `degree` + 1 of the curve's, `first` on.
std::array<Vec3d, 4> BezierSegment(const std::vector<Vec3d>& p, size_t first, int degree,
                                   bool bspline) {
    const Vec3d* c = p.data() + first;
    if (bspline && degree == 3)  // a uniform cubic B-spline's span, blossomed
        return {(c[0] + c[1] * 4.0 + c[2]) / 6.0, Lerp(1.0 / 3.0, c[1], c[2]),
                Lerp(2.0 / 3.0, c[1], c[2]), (c[1] + c[2] * 4.0 + c[3]) / 6.0};
    if (degree == 3) return {c[0], c[1], c[2], c[3]};
    // Quadratic: a B-spline's span as a Bezier's, then raised to a cubic (the same curve).
    const Vec3d q0 = bspline ? Lerp(0.5, c[0], c[1]) : c[0];
    const Vec3d q2 = bspline ? Lerp(0.5, c[1], c[2]) : c[2];
    return {q0, Lerp(2.0 / 3.0, q0, c[1]), Lerp(1.0 / 3.0, c[1], q2), q2};
}

}  // namespace

absl::StatusOr<std::vector<Curve>> CurveShape(ParameterList& parameters, const Location& where,
                                              bool* ignored_normals) {
    *ignored_normals = false;
    const auto invalid = [&](const std::string& what) -> absl::Status {
        return Invalid(where, absl::StrCat("Shape \"curve\": ", what));
    };
    const std::vector<Vec3d> points = parameters.Point3s("P");
    const std::string basis = parameters.String("basis", "bezier");
    const int degree = parameters.Integer("degree", 3);
    const std::string type_name = parameters.String("type", "flat");
    const std::vector<Vec3d> normals = parameters.Normals("N");
    const double width = parameters.Float("width", 1.0);
    const double width0 = parameters.Float("width0", width);
    const double width1 = parameters.Float("width1", width);
    parameters.Integer("splitdepth", 3);
    if (!parameters.status().ok()) return parameters.status();
    if (basis != "bezier" && basis != "bspline")
        return invalid(
            absl::StrCat("\"basis\" \"", basis, "\" is unknown (\"bezier\" or \"bspline\")"));
    if (degree != 2 && degree != 3)
        return invalid(absl::StrCat("\"degree\" ", degree, " is neither 2 nor 3"));
    CurveType type = CurveType::kFlat;
    if (type_name == "cylinder")
        type = CurveType::kCylinder;
    else if (type_name == "ribbon")
        type = CurveType::kRibbon;
    else if (type_name != "flat")
        return invalid(absl::StrCat("\"type\" \"", type_name,
                                    "\" is unknown (\"flat\", \"cylinder\" or "
                                    "\"ribbon\")"));
    const size_t count = points.size();
    const auto unsigned_degree = static_cast<size_t>(degree);
    const bool bspline = basis == "bspline";
    // A Bezier curve's segments share their ends: degree + 1 points, then degree a segment.
    if (count < unsigned_degree + 1 || (!bspline && (count - 1) % unsigned_degree != 0))
        return invalid(absl::StrCat("\"point3 P\" has ", count, " points: a degree ", degree, " ",
                                    basis, " curve needs ", degree + 1,
                                    bspline ? " or more" : absl::StrCat(" + n x ", degree)));
    for (size_t i = 0; i < count; ++i)
        if (!IsFinite(points[i]))
            return invalid(absl::StrCat("point ", i, " of \"point3 P\" is not finite"));
    if (!(std::isfinite(width0) && std::isfinite(width1) && width0 >= 0 && width1 >= 0))
        return invalid("its widths must be finite and not negative");
    const size_t segments = bspline ? count - unsigned_degree : (count - 1) / unsigned_degree;
    if (type != CurveType::kRibbon) {
        *ignored_normals = !normals.empty();
    } else if (normals.size() != segments + 1) {
        return invalid(absl::StrCat("a ribbon of ", segments, " segments needs ", segments + 1,
                                    " \"normal N\", not ", normals.size()));
    }
    std::vector<Curve> curves;
    curves.reserve(segments);
    for (size_t s = 0; s < segments; ++s) {
        Curve curve;
        const std::array<Vec3d, 4> control =
            BezierSegment(points, bspline ? s : s * unsigned_degree, degree, bspline);
        for (int i = 0; i < 4; ++i) curve.control[i] = Vec3(control[i]);
        const double t0 = double(s) / double(segments), t1 = double(s + 1) / double(segments);
        curve.width = {static_cast<float>(width0 + (width1 - width0) * t0),
                       static_cast<float>(width0 + (width1 - width0) * t1)};
        curve.normal = {Vec3(0.0f), Vec3(0.0f)};
        if (type == CurveType::kRibbon)
            for (int e = 0; e < 2; ++e) {
                const Vec3d& n = normals[s + e];
                if (!(IsFinite(n) && LengthSquared(n) > 0))
                    return invalid(absl::StrCat("\"normal N\" ", s + e, " is zero or not finite"));
                curve.normal[e] = Vec3(Normalize(n));
            }
        curve.type = type;
        curves.push_back(curve);
    }
    return curves;
}

}  // namespace pf::pbrt
