// Transforming a mesh into the scene, with the front-face rule of its format.
#include "core/scene/mesh_builder.h"

#include "absl/strings/str_cat.h"

namespace pf {

UvTransform UvTransform::Then(const UvTransform& next) const {
    const double* a = next.m;
    UvTransform out;
    out.m[0] = a[0] * m[0] + a[1] * m[3];
    out.m[1] = a[0] * m[1] + a[1] * m[4];
    out.m[2] = a[0] * m[2] + a[1] * m[5] + a[2];
    out.m[3] = a[3] * m[0] + a[4] * m[3];
    out.m[4] = a[3] * m[1] + a[4] * m[4];
    out.m[5] = a[3] * m[2] + a[4] * m[5] + a[5];
    return out;
}

absl::Status AppendMesh(const TriangleMesh& mesh, const MeshPlacement& placement, const SceneLimits& limits,
                        const std::string& element, Scene* scene) {
    auto error = [&](const std::string& what) { return absl::InvalidArgumentError(absl::StrCat(element, ": ", what)); };
    const size_t vertex_count = mesh.positions.size();
    if (!mesh.normals.empty() && mesh.normals.size() != vertex_count) return error("normal and position counts differ");
    if (!mesh.uvs.empty() && mesh.uvs.size() != vertex_count) return error("uv and position counts differ");
    if (mesh.indices.size() % 3 != 0) return error("index count is not a multiple of 3");
    if (scene->triangles.size() + mesh.indices.size() / 3 > limits.max_triangles)
        return absl::ResourceExhaustedError(absl::StrCat(element, ": the scene would hold more than ",
                                                         limits.max_triangles, " triangles, the loading limit"));
    for (size_t i = 0; i < mesh.indices.size(); ++i)
        if (mesh.indices[i] >= vertex_count)
            return error(absl::StrCat("triangle ", i / 3, " has an index beyond the ", vertex_count, " vertices"));
    const Transform& world = placement.world;
    const auto base = static_cast<uint32_t>(scene->positions.size());
    for (size_t v = 0; v < vertex_count; ++v) {
        const Vec3 p(world.ApplyPoint(Vec3d(mesh.positions[v])));
        if (!IsFinite(p)) return error(absl::StrCat("vertex ", v, " is not finite after its transform"));
        scene->positions.push_back(p);
        scene->bounds.Extend(p);
        Vec3 n(0.0f);
        if (!mesh.normals.empty()) {
            const Vec3d transformed = world.ApplyNormal(Vec3d(mesh.normals[v]));
            if (LengthSquared(transformed) > 0 && IsFinite(transformed)) n = Vec3(Normalize(transformed));
            if (placement.reverse) n = -n;
        }
        scene->normals.push_back(n);
        scene->uvs.push_back(mesh.uvs.empty() ? Point2{} : placement.uv.Apply(mesh.uvs[v]));
    }
    // World-space counter-clockwise winding is what Triangle::normal follows; swap two
    // vertices where the format's front is the other side.
    const bool mirrored = world.Determinant() < 0;
    const bool smooth = !mesh.normals.empty();
    for (size_t i = 0; i < mesh.indices.size(); i += 3) {
        uint32_t a = base + mesh.indices[i], b = base + mesh.indices[i + 1], c = base + mesh.indices[i + 2];
        Vec3 normal = Normalize(Cross(scene->positions[b] - scene->positions[a], scene->positions[c] - scene->positions[a]));
        if (!IsFinite(normal)) continue;  // degenerate: has no surface
        bool flip = false;
        switch (placement.front) {
            case FrontFace::kObjectWinding: flip = mirrored != placement.reverse; break;
            case FrontFace::kWorldWinding: flip = placement.reverse; break;
            case FrontFace::kVertexNormals: {
                const Vec3 shading = scene->normals[a] + scene->normals[b] + scene->normals[c];
                flip = Dot(shading, normal) < 0;
                break;
            }
        }
        if (flip) std::swap(b, c), normal = -normal;
        scene->triangles.push_back({{a, b, c}, placement.material, smooth, normal});
    }
    return absl::OkStatus();
}

}  // namespace pf
