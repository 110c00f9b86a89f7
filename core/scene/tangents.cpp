// MikkTSpace-style vertex tangents.
#include "core/scene/tangents.h"

#include <algorithm>
#include <cmath>

#include "core/shared/shading_normal.h"

namespace pf {
namespace {

// The angle at corner `a` of triangle (a, b, c).
float CornerAngle(const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 u = b - a, v = c - a;
    const float lengths = std::sqrt(LengthSquared(u) * LengthSquared(v));
    if (!(lengths > 0)) return 0;
    return std::acos(std::clamp(Dot(u, v) / lengths, -1.0f, 1.0f));
}

}  // namespace

std::vector<Vec3> GenerateTangents(std::span<const Vec3> positions, std::span<const Vec3> normals,
                                   std::span<const Point2> uvs, std::span<const uint32_t> indices) {
    std::vector<Vec3> sums(positions.size(), Vec3(0.0f));
    // The normal a vertex's tangent is made perpendicular to: its own, else the sum of its
    // triangles' (angle-weighted, as the tangents are).
    std::vector<Vec3> reference(positions.size(), Vec3(0.0f));
    for (size_t i = 0; i + 2 < indices.size(); i += 3) {
        const uint32_t corner[3] = {indices[i], indices[i + 1], indices[i + 2]};
        const Vec3 e1 = positions[corner[1]] - positions[corner[0]];
        const Vec3 e2 = positions[corner[2]] - positions[corner[0]];
        const Vec3 face = Cross(e1, e2);
        if (!(LengthSquared(face) > 0)) continue;
        const Vec3 face_normal = Normalize(face);
        const Vec3 dpdu = gpu::TriangleDpDu(e1, e2, uvs[corner[1]] - uvs[corner[0]],
                                            uvs[corner[2]] - uvs[corner[0]]);
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = corner[k];
            const float angle = CornerAngle(positions[v], positions[corner[(k + 1) % 3]],
                                            positions[corner[(k + 2) % 3]]);
            const Vec3 n = LengthSquared(normals[v]) > 0 ? normals[v] : face_normal;
            reference[v] += face_normal * angle;
            const Vec3 t = dpdu - n * Dot(n, dpdu);
            if (LengthSquared(t) > 0) sums[v] += Normalize(t) * angle;
        }
    }
    std::vector<Vec3> tangents(positions.size());
    for (size_t v = 0; v < positions.size(); ++v) {
        Vec3 n = LengthSquared(normals[v]) > 0 ? normals[v] : reference[v];
        n = LengthSquared(n) > 0 ? Normalize(n) : Vec3(0, 0, 1);
        tangents[v] = gpu::PerpendicularTo(n, sums[v]);
    }
    return tangents;
}

}  // namespace pf
