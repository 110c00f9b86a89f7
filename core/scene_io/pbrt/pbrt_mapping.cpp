// pbrt-v4's texture mappings, as textures.h defines them.
#include "core/scene_io/pbrt/pbrt_mapping.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"

namespace pf::pbrt {
namespace {

// Spherical and cylindrical: (s, t) of point q in the texture's frame.
Point2 AboutTheAxis(TextureMapping::Kind kind, const Vec3d& q) {
    const double length = Length(q);
    if (!(length > 0)) return {0.5f, 0.5f};  // the mapping's centre: no direction
    const Vec3d v = q / length;
    const double phi = std::atan2(v.y, v.x);  // in (-pi, pi]
    if (kind == TextureMapping::Kind::kCylindrical)
        return {static_cast<float>((kPiD + phi) / (2 * kPiD)), static_cast<float>(v.z)};
    // pbrt's SphericalTheta / pi and SphericalPhi / 2 pi (phi in [0, 2 pi)).
    const double theta = std::acos(std::clamp(v.z, -1.0, 1.0));
    return {static_cast<float>(theta / kPiD),
            static_cast<float>((phi < 0 ? phi + 2 * kPiD : phi) / (2 * kPiD))};
}

}  // namespace

bool TextureMapping::operator==(const TextureMapping& other) const {
    return kind == other.kind && std::equal(std::begin(uv.m), std::end(uv.m), other.uv.m) &&
           texture_from_world.m == other.texture_from_world.m && vs == other.vs && vt == other.vt &&
           ds == other.ds && dt == other.dt;
}

absl::StatusOr<TextureMapping> ParseMapping(ParameterList& parameters,
                                            const Transform& world_from_texture) {
    TextureMapping mapping;
    const std::string kind = parameters.String("mapping", "uv");
    if (kind == "uv") {
        const double su = parameters.Float("uscale", 1), sv = parameters.Float("vscale", 1);
        const double du = parameters.Float("udelta", 0), dv = parameters.Float("vdelta", 0);
        mapping.uv.m[0] = su, mapping.uv.m[2] = du, mapping.uv.m[4] = sv, mapping.uv.m[5] = dv;
        return mapping;
    }
    if (kind == "planar") {
        mapping.kind = TextureMapping::Kind::kPlanar;
        mapping.vs = parameters.Vector3("v1").value_or(Vec3d(1, 0, 0));
        mapping.vt = parameters.Vector3("v2").value_or(Vec3d(0, 1, 0));
        mapping.ds = parameters.Float("udelta", 0), mapping.dt = parameters.Float("vdelta", 0);
    } else if (kind == "spherical" || kind == "cylindrical") {
        mapping.kind = kind == "spherical" ? TextureMapping::Kind::kSpherical
                                           : TextureMapping::Kind::kCylindrical;
    } else {
        return absl::InvalidArgumentError(
            absl::StrCat("mapping \"", kind,
                         "\" is unknown (\"uv\", \"planar\", \"spherical\", \"cylindrical\")"));
    }
    const std::optional<Transform> inverse = world_from_texture.Inverse();
    if (!inverse) return absl::InvalidArgumentError("the texture's transform is singular");
    mapping.texture_from_world = *inverse;
    return mapping;
}

TriangleMesh MapTextureCoordinates(const TriangleMesh& mesh, const Transform& world,
                                   const TextureMapping& mapping) {
    TriangleMesh out = mesh;
    out.uvs.clear();
    if (mapping.kind == TextureMapping::Kind::kPlanar) {
        for (const Vec3& position : mesh.positions) {
            const Vec3d d =
                mapping.texture_from_world.ApplyPoint(world.ApplyPoint(Vec3d(position)));
            out.uvs.push_back({static_cast<float>(mapping.ds + Dot(d, mapping.vs)),
                               static_cast<float>(mapping.dt + Dot(d, mapping.vt))});
        }
        return out;
    }
    // Spherical and cylindrical: each triangle's corners of its own.
    out.positions.clear(), out.normals.clear(), out.tangents.clear(), out.indices.clear();
    const bool spherical = mapping.kind == TextureMapping::Kind::kSpherical;
    for (size_t first = 0; first + 2 < mesh.indices.size(); first += 3) {
        Point2 st[3];
        bool on_axis[3];
        int reference = -1;  // a corner off the axis
        for (int c = 0; c < 3; ++c) {
            const uint32_t v = mesh.indices[first + c];
            out.positions.push_back(mesh.positions[v]);
            if (!mesh.normals.empty()) out.normals.push_back(mesh.normals[v]);
            if (!mesh.tangents.empty()) out.tangents.push_back(mesh.tangents[v]);
            out.indices.push_back(static_cast<uint32_t>(first + c));
            const Vec3d q =
                mapping.texture_from_world.ApplyPoint(world.ApplyPoint(Vec3d(mesh.positions[v])));
            st[c] = AboutTheAxis(mapping.kind, q);
            on_axis[c] = q.x * q.x + q.y * q.y <= 1e-12 * Dot(q, q);
            if (!on_axis[c] && reference < 0) reference = c;
        }
        // The angle about the axis (phi / 2 pi: t of the sphere, s of the cylinder) within
        // half a turn of the reference corner's, where a repeating image reads the same; a
        // corner on the axis, where it has none, takes the mean of the others'.
        const auto turn = [&](Point2& uv) -> float& { return spherical ? uv.y : uv.x; };
        if (reference >= 0) {
            float sum = 0;
            int count = 0;
            for (int c = 0; c < 3; ++c) {
                if (on_axis[c]) continue;
                turn(st[c]) += std::round(turn(st[reference]) - turn(st[c]));
                sum += turn(st[c]), ++count;
            }
            for (int c = 0; c < 3; ++c)
                if (on_axis[c]) turn(st[c]) = sum / static_cast<float>(count);
        }
        for (const Point2& uv : st) out.uvs.push_back(uv);
    }
    return out;
}

}  // namespace pf::pbrt
