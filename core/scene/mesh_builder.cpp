// Transforming a mesh into the scene, with the front-face rule of its format.
#include "core/scene/mesh_builder.h"

#include <algorithm>
#include <span>

#include "absl/strings/str_cat.h"
#include "core/scene/tangents.h"
#include "core/util/check.h"

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

namespace {

// The tangents of the vertices from `base` on, which AppendMesh has just added with the
// triangles from `first_triangle` on: kept or made where the material has a normal map, zero
// where it has none but another mesh's has; nothing while no material has one.
void AppendTangents(const TriangleMesh& mesh, const MeshPlacement& placement, uint32_t base,
                    uint32_t first_triangle, Scene* scene) {
    const bool needed = scene->NeedsTangents(placement.material);
    if (!needed && scene->tangents.empty()) return;
    scene->tangents.resize(base, Vec3(0.0f));
    const size_t end = scene->positions.size();
    if (!needed) {
        scene->tangents.resize(end, Vec3(0.0f));
    } else if (!mesh.tangents.empty()) {
        for (const Vec3& tangent : mesh.tangents) {
            const Vec3d t = placement.world.ApplyVector(Vec3d(tangent));
            scene->tangents.push_back(LengthSquared(t) > 0 && IsFinite(t) ? Vec3(Normalize(t))
                                                                          : Vec3(0.0f));
        }
    } else {
        std::vector<uint32_t> indices;
        for (size_t t = first_triangle; t < scene->triangles.size(); ++t)
            for (const uint32_t v : scene->triangles[t].vertex) indices.push_back(v - base);
        const auto span = [&](const auto& all) { return std::span(all).subspan(base, end - base); };
        const std::vector<Vec3> made = GenerateTangents(
            span(scene->positions), span(scene->normals), span(scene->uvs), indices);
        scene->tangents.insert(scene->tangents.end(), made.begin(), made.end());
    }
}

}  // namespace

absl::Status AppendMesh(const TriangleMesh& mesh, const MeshPlacement& placement,
                        const SceneLimits& limits, const std::string& element, Scene* scene,
                        std::optional<uint32_t> prototype) {
    PF_CHECK(!prototype || (*prototype + 1 == scene->prototypes.size() &&
                            scene->prototypes[*prototype].first_triangle +
                                    scene->prototypes[*prototype].triangle_count ==
                                scene->triangles.size()));
    Bounds& bounds = prototype ? scene->prototypes[*prototype].bounds : scene->bounds;
    auto error = [&](const std::string& what) {
        return absl::InvalidArgumentError(absl::StrCat(element, ": ", what));
    };
    const size_t vertex_count = mesh.positions.size();
    if (!mesh.normals.empty() && mesh.normals.size() != vertex_count)
        return error("normal and position counts differ");
    if (!mesh.uvs.empty() && mesh.uvs.size() != vertex_count)
        return error("uv and position counts differ");
    if (!mesh.tangents.empty() && mesh.tangents.size() != vertex_count)
        return error("tangent and position counts differ");
    if (!mesh.colors.empty() && mesh.colors.size() != vertex_count)
        return error("colour and position counts differ");
    if (mesh.indices.size() % 3 != 0) return error("index count is not a multiple of 3");
    if (scene->triangles.size() + mesh.indices.size() / 3 > limits.max_triangles)
        return absl::ResourceExhaustedError(
            absl::StrCat(element, ": the scene would hold more than ", limits.max_triangles,
                         " triangles, the loading limit"));
    for (size_t i = 0; i < mesh.indices.size(); ++i)
        if (mesh.indices[i] >= vertex_count)
            return error(absl::StrCat("triangle ", i / 3, " has an index beyond the ", vertex_count,
                                      " vertices"));
    const Transform& world = placement.world;
    const auto base = static_cast<uint32_t>(scene->positions.size());
    const auto first_triangle = static_cast<uint32_t>(scene->triangles.size());
    for (size_t v = 0; v < vertex_count; ++v) {
        const Vec3 p(world.ApplyPoint(Vec3d(mesh.positions[v])));
        if (!IsFinite(p))
            return error(absl::StrCat("vertex ", v, " is not finite after its transform"));
        scene->positions.push_back(p);
        bounds.Extend(p);
        Vec3 n(0.0f);
        if (!mesh.normals.empty()) {
            const Vec3d transformed = world.ApplyNormal(Vec3d(mesh.normals[v]));
            if (LengthSquared(transformed) > 0 && IsFinite(transformed))
                n = Vec3(Normalize(transformed));
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
        uint32_t a = base + mesh.indices[i], b = base + mesh.indices[i + 1],
                 c = base + mesh.indices[i + 2];
        const Vec3d pa(scene->positions[a]), pb(scene->positions[b]), pc(scene->positions[c]);
        const Vec3d cross = Cross(pb - pa, pc - pa);
        // Degenerate, or a sliver thinner than float resolves against its longest edge (a
        // tessellated pole, whose corners a transform may round together): no surface.
        const double longest =
            std::max({LengthSquared(pb - pa), LengthSquared(pc - pb), LengthSquared(pa - pc)});
        if (!(Length(cross) > 1e-7 * longest)) continue;
        Vec3 normal(Normalize(cross));
        bool flip = false;
        switch (placement.front) {
            case FrontFace::kObjectWinding:
                flip = mirrored != placement.reverse;
                break;
            case FrontFace::kWorldWinding:
                flip = placement.reverse;
                break;
            case FrontFace::kVertexNormals: {
                const Vec3 shading = scene->normals[a] + scene->normals[b] + scene->normals[c];
                flip = Dot(shading, normal) < 0;
                break;
            }
        }
        if (flip) std::swap(b, c), normal = -normal;
        scene->triangles.push_back({{a, b, c}, placement.material, smooth, normal});
        if (prototype) ++scene->prototypes[*prototype].triangle_count;
    }
    AppendTangents(mesh, placement, base, first_triangle, scene);
    // Vertex colours, once a mesh has them: white for every other vertex.
    if (!mesh.colors.empty() || !scene->colors.empty()) {
        scene->colors.resize(base);
        if (mesh.colors.empty())
            scene->colors.resize(scene->positions.size());
        else
            scene->colors.insert(scene->colors.end(), mesh.colors.begin(), mesh.colors.end());
    }
    return absl::OkStatus();
}

uint32_t BeginPrototype(Scene* scene) {
    scene->prototypes.push_back({static_cast<uint32_t>(scene->triangles.size()),
                                 0,
                                 static_cast<uint32_t>(scene->curves.size()),
                                 0,
                                 {}});
    return static_cast<uint32_t>(scene->prototypes.size() - 1);
}

absl::Status AddInstance(uint32_t prototype, const Transform& from_object,
                         const SceneLimits& limits, const std::string& element, Scene* scene) {
    PF_CHECK(prototype < scene->prototypes.size());
    const Prototype& placed = scene->prototypes[prototype];
    if (placed.triangle_count == 0 && placed.curve_count == 0) return absl::OkStatus();
    if (scene->instances.size() >= limits.max_instances)
        return absl::ResourceExhaustedError(
            absl::StrCat(element, ": the scene would hold more than ", limits.max_instances,
                         " instances, the loading limit"));
    if (!from_object.IsFinite() || !from_object.Inverse())
        return absl::InvalidArgumentError(
            absl::StrCat(element, ": the instance's transform is singular or not finite"));
    // The world bounds take the prototype's box corners, transformed.
    Bounds bounds = scene->bounds;
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3d p((corner & 1 ? placed.bounds.upper : placed.bounds.lower).x,
                      (corner & 2 ? placed.bounds.upper : placed.bounds.lower).y,
                      (corner & 4 ? placed.bounds.upper : placed.bounds.lower).z);
        const Vec3 world(from_object.ApplyPoint(p));
        if (!IsFinite(world))
            return absl::InvalidArgumentError(
                absl::StrCat(element, ": the instance lies beyond float's range"));
        bounds.Extend(world);
    }
    scene->bounds = bounds;
    scene->instances.push_back(Instance::Make(prototype, from_object));
    return absl::OkStatus();
}

namespace {

// The world's elements (triangles or curves) first, then each prototype's, whose `first` and
// `count` name them.
template <typename T>
void WorldFirst(std::vector<T>& elements, std::vector<Prototype>& prototypes,
                uint32_t Prototype::*first, uint32_t Prototype::*count) {
    std::vector<bool> in_prototype(elements.size(), false);
    for (const Prototype& prototype : prototypes)
        std::fill_n(in_prototype.begin() + prototype.*first, prototype.*count, true);
    std::vector<T> ordered;
    ordered.reserve(elements.size());
    for (size_t e = 0; e < elements.size(); ++e)
        if (!in_prototype[e]) ordered.push_back(elements[e]);
    for (Prototype& prototype : prototypes) {
        const auto begin = elements.begin() + prototype.*first;
        prototype.*first = static_cast<uint32_t>(ordered.size());
        ordered.insert(ordered.end(), begin, begin + prototype.*count);
    }
    elements = std::move(ordered);
}

}  // namespace

void FinishInstancing(Scene* scene) {
    if (scene->prototypes.empty()) return;
    WorldFirst(scene->triangles, scene->prototypes, &Prototype::first_triangle,
               &Prototype::triangle_count);
    WorldFirst(scene->curves, scene->prototypes, &Prototype::first_curve, &Prototype::curve_count);
}

absl::StatusOr<Scene> FlattenInstances(const Scene& scene, uint64_t max_triangles,
                                       uint64_t max_curves) {
    uint64_t total = scene.WorldTriangleCount(), total_curves = scene.WorldCurveCount();
    for (const Instance& instance : scene.instances) {
        total += scene.prototypes[instance.prototype].triangle_count;
        total_curves += scene.prototypes[instance.prototype].curve_count;
    }
    if (total > max_triangles)
        return absl::ResourceExhaustedError(absl::StrCat(
            scene.source, ": its ", scene.instances.size(), " instances expand to ", total,
            " triangles, more than the ", max_triangles, " this backend holds"));
    if (total_curves > max_curves)
        return absl::ResourceExhaustedError(absl::StrCat(
            scene.source, ": its ", scene.instances.size(), " instances expand to ", total_curves,
            " curves, more than the ", max_curves, " this backend holds"));
    // Each prototype's vertices, once, and its triangles over them (AppendMesh gives every mesh
    // vertices of its own: no vertex belongs to two prototypes).
    struct Local {
        std::vector<uint32_t> vertices;   // into Scene::positions
        std::vector<Triangle> triangles;  // vertex: into `vertices`
    };
    std::vector<Local> locals(scene.prototypes.size());
    std::vector<uint32_t> local_index(scene.positions.size(), ~0u);
    for (size_t p = 0; p < scene.prototypes.size(); ++p) {
        const Prototype& prototype = scene.prototypes[p];
        Local& local = locals[p];
        for (uint32_t t = prototype.first_triangle;
             t < prototype.first_triangle + prototype.triangle_count; ++t) {
            Triangle triangle = scene.triangles[t];
            for (uint32_t& v : triangle.vertex) {
                if (local_index[v] == ~0u) {
                    local_index[v] = static_cast<uint32_t>(local.vertices.size());
                    local.vertices.push_back(v);
                }
                v = local_index[v];
            }
            local.triangles.push_back(triangle);
        }
    }
    Scene flat = scene;
    flat.triangles.resize(scene.WorldTriangleCount());
    flat.curves.resize(scene.WorldCurveCount());
    flat.prototypes.clear();
    flat.instances.clear();
    for (uint32_t i = 0; i < scene.instances.size(); ++i) {
        const Prototype& prototype = scene.prototypes[scene.instances[i].prototype];
        for (uint32_t c = prototype.first_curve; c < prototype.first_curve + prototype.curve_count;
             ++c)
            flat.curves.push_back(scene.WorldCurve(c, i));
    }
    for (const Instance& instance : scene.instances) {
        const Local& local = locals[instance.prototype];
        const auto base = static_cast<uint32_t>(flat.positions.size());
        for (uint32_t v : local.vertices) {
            flat.positions.push_back(instance.ApplyPoint(scene.positions[v]));
            const Vec3 n = instance.ApplyNormal(scene.normals[v]);
            flat.normals.push_back(LengthSquared(n) > 0 ? Normalize(n) : n);
            flat.uvs.push_back(scene.uvs[v]);
            if (!scene.tangents.empty()) {
                const Vec3 t = instance.ApplyVector(scene.tangents[v]);
                flat.tangents.push_back(LengthSquared(t) > 0 ? Normalize(t) : t);
            }
            if (!scene.colors.empty()) flat.colors.push_back(scene.colors[v]);
        }
        for (Triangle triangle : local.triangles) {
            for (uint32_t& v : triangle.vertex) v += base;
            triangle.normal = Normalize(instance.ApplyNormal(triangle.normal));
            flat.triangles.push_back(triangle);
        }
    }
    return flat;
}

}  // namespace pf
