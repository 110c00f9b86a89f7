// Embree 3 device, scenes (the world's triangles and curves, and one per prototype, placed by
// instance geometries) and queries. Errors reach us through one device error callback.
#include "embree/embree_tracer.h"

#include <embree3/rtcore.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <deque>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "core/shared/alpha.h"
#include "core/shared/curve.h"
#include "embree/device.h"

namespace pf::embree {
namespace {

RTCRay ToRtcRay(const Ray& ray) {
    RTCRay r{};
    r.org_x = ray.origin.x, r.org_y = ray.origin.y, r.org_z = ray.origin.z;
    r.dir_x = ray.direction.x, r.dir_y = ray.direction.y, r.dir_z = ray.direction.z;
    r.tnear = 0.0f;
    r.tfar = ray.t_max;
    r.mask = std::numeric_limits<unsigned>::max();
    r.flags = 0;
    return r;
}

// Fills an 8-wide packet; inactive lanes are masked off by `valid`.
void ToRtcRays(const Ray (&rays)[Tracer::kPacketSize], const bool (&active)[Tracer::kPacketSize],
               int (&valid)[Tracer::kPacketSize], RTCRay8* packet) {
    static_assert(Tracer::kPacketSize == 8, "packets map onto Embree's 8-wide calls");
    for (int i = 0; i < Tracer::kPacketSize; ++i) {
        valid[i] = active[i] ? -1 : 0;
        const Ray& ray = rays[i];
        packet->org_x[i] = ray.origin.x, packet->org_y[i] = ray.origin.y,
        packet->org_z[i] = ray.origin.z;
        packet->dir_x[i] = ray.direction.x, packet->dir_y[i] = ray.direction.y,
        packet->dir_z[i] = ray.direction.z;
        packet->tnear[i] = 0.0f;
        packet->tfar[i] = active[i] ? ray.t_max : 0.0f;
        packet->time[i] = 0.0f;
        packet->mask[i] = std::numeric_limits<unsigned>::max();
        packet->id[i] = 0;
        packet->flags[i] = 0;
    }
}

// What the cut-out filter of one geometry reads: the scene's alpha (a copy of what Scene::Alpha
// and Scene::CurveAlpha read, owned by the tracer) and the geometry's triangles in it, or for a
// curve geometry, the curves its primitives are.
struct CutOutGeometry {
    const Scene* alpha = nullptr;
    const std::vector<uint32_t>* triangles = nullptr;
    const std::vector<uint32_t>* curves = nullptr;
    uint32_t pieces = 1;  // Embree primitives a curve (Pieces)
};

// Embree primitives a curve of `type` is drawn as: a ribbon's 4, so that the turn of Embree's
// band between its pieces' end normals follows the curve's own (spherically interpolated)
// normals closely; a band facing the ray needs one.
uint32_t Pieces(CurveType type) { return type == CurveType::kRibbon ? 4 : 1; }

// Embree's geometry types for ours: flat and cylinder curves are bands facing the ray (pbrt-v4
// intersects both so, a cylinder differing only in its shading normal); ribbons follow their
// normals.
RTCGeometryType CurveGeometryType(CurveType type) {
    return type == CurveType::kRibbon ? RTC_GEOMETRY_TYPE_NORMAL_ORIENTED_BEZIER_CURVE
                                      : RTC_GEOMETRY_TYPE_FLAT_BEZIER_CURVE;
}

// The triangles of one Embree scene (the world's, or a prototype's), as one geometry, or, where
// some have cut-outs, two: geometry 0 the others, which runs no filter, and geometry 1 those,
// which runs the cut-out filter, so that only the triangles with cut-outs pay for it.
struct TriangleGroup {
    uint32_t first = 0;  // not split: geometry 0's primitive i is Scene::triangles[first + i]
    bool split = false;
    std::vector<uint32_t> triangles[2];  // split: each geometry's Scene::triangles, in order
    uint32_t Triangle(unsigned geometry, unsigned primitive) const {
        return split ? triangles[geometry][primitive] : first + primitive;
    }
};

// The top scene's geometry ids: the world's two triangle geometries, then the instances', then
// the world's curves, a geometry a type (their number added). A prototype's scene: its two
// triangle geometries, then its curves likewise.
constexpr unsigned kFirstInstanceGeometry = 2;
constexpr unsigned kPrototypeFirstCurveGeometry = 2;

// Embree's intersection and occlusion filter for geometries with cut-outs: a hit the ray
// passes through (core/shared/alpha.h) is rejected, and traversal goes on past it. Within an
// instance Embree hands the filter the ray in the prototype's space, where the triangle's
// normal is too.
void CutOutFilter(const RTCFilterFunctionNArguments* args) {
    const auto* geometry = static_cast<const CutOutGeometry*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const uint32_t triangle = (*geometry->triangles)[RTCHitN_primID(args->hit, args->N, i)];
        const Triangle& hit = geometry->alpha->triangles[triangle];
        const Material& material = geometry->alpha->materials[hit.material];
        if (!material.HasCutOuts()) continue;
        const Vec3 direction(RTCRayN_dir_x(args->ray, args->N, i),
                             RTCRayN_dir_y(args->ray, args->N, i),
                             RTCRayN_dir_z(args->ray, args->N, i));
        if (gpu::PassesBackFace(material.surface_flags, Dot(direction, hit.normal))) {
            args->valid[i] = 0;
            continue;
        }
        const float alpha = geometry->alpha->Alpha(triangle, RTCHitN_u(args->hit, args->N, i),
                                                   RTCHitN_v(args->hit, args->N, i));
        if (alpha >= 1.0f) continue;
        const Vec3 origin(RTCRayN_org_x(args->ray, args->N, i),
                          RTCRayN_org_y(args->ray, args->N, i),
                          RTCRayN_org_z(args->ray, args->N, i));
        if (!gpu::AlphaMeets(alpha, material.alpha_cutoff,
                             gpu::AlphaHash(origin, direction, triangle)))
            args->valid[i] = 0;
    }
}

// The same for curves: the alpha at the hit's (u, v), v from where the ray meets the curve
// (the ray and the curve both in the curve's own space, an instance's or the world).
void CurveCutOutFilter(const RTCFilterFunctionNArguments* args) {
    const auto* geometry = static_cast<const CutOutGeometry*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const uint32_t primitive = RTCHitN_primID(args->hit, args->N, i);
        const uint32_t index = (*geometry->curves)[primitive / geometry->pieces];
        const Curve& curve = geometry->alpha->curves[index];
        const Material& material = geometry->alpha->materials[curve.material];
        if (!material.HasCutOuts()) continue;
        const Vec3 origin(RTCRayN_org_x(args->ray, args->N, i),
                          RTCRayN_org_y(args->ray, args->N, i),
                          RTCRayN_org_z(args->ray, args->N, i));
        const Vec3 direction(RTCRayN_dir_x(args->ray, args->N, i),
                             RTCRayN_dir_y(args->ray, args->N, i),
                             RTCRayN_dir_z(args->ray, args->N, i));
        const float t = RTCRayN_tfar(args->ray, args->N, i);
        const float u =
            (static_cast<float>(primitive % geometry->pieces) + RTCHitN_u(args->hit, args->N, i)) /
            static_cast<float>(geometry->pieces);
        const std::array<Vec3, 4>& p = curve.control;
        const float v =
            gpu::CurveAcross(p[0], p[1], p[2], p[3], curve.width[0], curve.width[1],
                             static_cast<uint32_t>(curve.type), curve.normal[0], curve.normal[1], u,
                             origin + direction * t, Normalize(direction));
        if (!gpu::AlphaMeets(geometry->alpha->CurveAlpha(index, u, v), material.alpha_cutoff,
                             gpu::AlphaHash(origin, direction, gpu::kCurveBit | index)))
            args->valid[i] = 0;
    }
}

}  // namespace

struct EmbreeTracer::Handles {
    explicit Handles(Device device_in) : device(std::move(device_in)) {}
    Device device;  // released last: declared first
    RTCBuffer vertices =
        nullptr;  // every position, shared by the world's and prototypes' geometries
    std::vector<RTCScene> prototypes;  // one scene per Scene::prototypes entry
    // Geometries 0 and 1: the world's triangles; kFirstInstanceGeometry + i: instance i; then
    // the world's curves (kFirstInstanceGeometry's comment).
    RTCScene scene = nullptr;
    // The world's triangles, then each prototype's (stable addresses: reserved before any is
    // attached, as the filters point into them).
    std::vector<TriangleGroup> groups;
    std::vector<uint32_t> instance_group;  // per instance: its prototype's group
    // The Scene::curves each curve geometry's primitives are: [group][type], as `groups`
    // (sized before any is attached: stable addresses).
    std::vector<std::array<std::vector<uint32_t>, 3>> curves;
    // With cut-outs: what their filter reads, and one entry per filtered geometry (a deque:
    // stable addresses).
    std::unique_ptr<Scene> alpha;
    std::deque<CutOutGeometry> cut_out_geometries;
    ~Handles() {
        if (scene) rtcReleaseScene(scene);
        for (RTCScene prototype : prototypes) rtcReleaseScene(prototype);
        if (vertices) rtcReleaseBuffer(vertices);
    }

    // Attaches `count` triangles, the i-th Scene::triangles[triangle(i)], as geometry `id` of
    // `target`; with the cut-out filter over them where `filtered` lists them.
    template <typename TriangleOf>
    bool AttachTriangles(RTCScene target, const std::vector<Triangle>& triangles,
                         TriangleOf triangle, uint32_t count, size_t vertex_count, unsigned id,
                         const std::vector<uint32_t>* filtered) {
        RTCGeometry geometry = rtcNewGeometry(device.Handle(), RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, vertices, 0,
                             sizeof(float) * 3, vertex_count);
        auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, sizeof(unsigned) * 3, count));
        if (indices == nullptr) {
            rtcReleaseGeometry(geometry);
            return false;
        }
        for (uint32_t t = 0; t < count; ++t)
            for (int k = 0; k < 3; ++k) indices[3 * t + k] = triangles[triangle(t)].vertex[k];
        if (filtered != nullptr) {
            cut_out_geometries.push_back({alpha.get(), filtered});
            rtcSetGeometryUserData(geometry, &cut_out_geometries.back());
            rtcSetGeometryIntersectFilterFunction(geometry, CutOutFilter);
            rtcSetGeometryOccludedFilterFunction(geometry, CutOutFilter);
        }
        rtcCommitGeometry(geometry);
        rtcAttachGeometryByID(target, geometry, id);
        rtcReleaseGeometry(geometry);
        return true;
    }

    // Attaches triangles [first, first + count) of `model` to `target` as geometry 0 and,
    // those with cut-outs, geometry 1 (TriangleGroup), described in `group`.
    bool AttachGroup(RTCScene target, const Scene& model, uint32_t first, uint32_t count,
                     size_t vertex_count, TriangleGroup* group) {
        group->first = first;
        const auto cut_out = [&](uint32_t t) {
            return model.materials[model.triangles[t].material].HasCutOuts();
        };
        bool any = false;
        for (uint32_t t = first; alpha && !any && t < first + count; ++t) any = cut_out(t);
        if (!any)
            return AttachTriangles(
                target, model.triangles, [first](uint32_t i) { return first + i; }, count,
                vertex_count, 0, nullptr);
        group->split = true;
        for (uint32_t t = first; t < first + count; ++t)
            group->triangles[cut_out(t) ? 1 : 0].push_back(t);
        for (unsigned id = 0; id < 2; ++id) {
            const std::vector<uint32_t>& part = group->triangles[id];
            if (!part.empty() &&
                !AttachTriangles(
                    target, model.triangles, [&part](uint32_t i) { return part[i]; },
                    static_cast<uint32_t>(part.size()), vertex_count, id,
                    id == 1 ? &part : nullptr))
                return false;
        }
        return true;
    }

    // Attaches the curves `indices` of `scene_curves` (all of one type) as geometry `id` of
    // `target`, each as Pieces(type) Embree primitives (its pieces over equal spans of u, their
    // control points blossomed): 4 control points a piece, with radii whose Bezier blend is half
    // the width, linear along the curve; a ribbon's normals its own at the pieces' thirds.
    bool AttachCurves(RTCScene target, const std::vector<Curve>& scene_curves,
                      const std::vector<uint32_t>& indices, unsigned id) {
        const CurveType type = scene_curves[indices.front()].type;
        const uint32_t pieces = Pieces(type);
        RTCGeometry geometry = rtcNewGeometry(device.Handle(), CurveGeometryType(type));
        const size_t count = indices.size() * pieces;
        auto* points = static_cast<float*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, sizeof(float) * 4, 4 * count));
        auto* starts = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(unsigned), count));
        float* normals = nullptr;
        if (type == CurveType::kRibbon)
            normals = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_NORMAL,
                                                                  0, RTC_FORMAT_FLOAT3,
                                                                  sizeof(float) * 3, 4 * count));
        if (points == nullptr || starts == nullptr ||
            (type == CurveType::kRibbon && normals == nullptr)) {
            rtcReleaseGeometry(geometry);
            return false;
        }
        int depth = 0;
        for (size_t primitive = 0; primitive < count; ++primitive) {
            const Curve& curve = scene_curves[indices[primitive / pieces]];
            const std::array<Vec3, 4>& p = curve.control;
            const float u0 = static_cast<float>(primitive % pieces) / static_cast<float>(pieces);
            const float u1 = u0 + 1.0f / static_cast<float>(pieces);
            starts[primitive] = static_cast<unsigned>(4 * primitive);
            for (int k = 0; k < 4; ++k) {
                // The piece's k-th control point: the blossom at (u0, u0, u1) and the like.
                const float a = k < 3 ? u0 : u1, b = k < 2 ? u0 : u1, c = k < 1 ? u0 : u1;
                const Vec3 control = gpu::BezierBlossom(p[0], p[1], p[2], p[3], a, b, c);
                const float along = u0 + (u1 - u0) * static_cast<float>(k) / 3.0f;
                float* point = points + 4 * (4 * primitive + k);
                point[0] = control.x, point[1] = control.y, point[2] = control.z;
                point[3] = 0.5f * (curve.width[0] + (curve.width[1] - curve.width[0]) * along);
                if (normals) {
                    const Vec3 n = gpu::RibbonNormal(curve.normal[0], curve.normal[1], along);
                    float* normal = normals + 3 * (4 * primitive + k);
                    normal[0] = n.x, normal[1] = n.y, normal[2] = n.z;
                }
            }
            depth = std::max(
                depth, gpu::CurveDepth(p[0], p[1], p[2], p[3], curve.width[0], curve.width[1]));
        }
        // Flat curves are drawn as quads facing the ray, as many a segment as this: at least
        // the pieces pbrt-v4 tests (2^depth), within Embree's default 4 and 16.
        rtcSetGeometryTessellationRate(geometry, static_cast<float>(1 << std::clamp(depth, 2, 4)));
        if (alpha) {
            cut_out_geometries.push_back({alpha.get(), nullptr, &indices, pieces});
            rtcSetGeometryUserData(geometry, &cut_out_geometries.back());
            rtcSetGeometryIntersectFilterFunction(geometry, CurveCutOutFilter);
            rtcSetGeometryOccludedFilterFunction(geometry, CurveCutOutFilter);
        }
        rtcCommitGeometry(geometry);
        rtcAttachGeometryByID(target, geometry, id);
        rtcReleaseGeometry(geometry);
        return true;
    }

    // Attaches curves [first, first + count) of `scene_curves` to `target` as a geometry a
    // type, `first_id` + the type's number, recording them as group `scope`'s (0 the world's,
    // 1 + p prototype p's).
    bool AttachCurveTypes(RTCScene target, const std::vector<Curve>& scene_curves, uint32_t first,
                          uint32_t count, unsigned first_id, size_t scope) {
        std::array<std::vector<uint32_t>, 3>& by_type = curves[scope];
        for (uint32_t c = first; c < first + count; ++c)
            by_type[static_cast<uint32_t>(scene_curves[c].type)].push_back(c);
        for (unsigned type = 0; type < 3; ++type)
            if (!by_type[type].empty() &&
                !AttachCurves(target, scene_curves, by_type[type], first_id + type))
                return false;
        return true;
    }

    // Our hit from Embree's: the instance (kFirstInstanceGeometry + its index), the geometry
    // within its scene, the primitive within that geometry. A curve hit keeps the ray.
    void ToRayHit(unsigned instance_geometry, unsigned geometry, unsigned primitive, const Ray& ray,
                  RayHit* hit) const {
        const bool world = instance_geometry == RTC_INVALID_GEOMETRY_ID;
        hit->instance = world ? Instance::kNone : instance_geometry - kFirstInstanceGeometry;
        const size_t group = world ? 0 : instance_group[hit->instance];
        const unsigned first_curve_geometry =
            world ? kFirstInstanceGeometry + static_cast<unsigned>(instance_group.size())
                  : kPrototypeFirstCurveGeometry;
        if (geometry < first_curve_geometry) {
            hit->triangle = groups[group].Triangle(geometry, primitive);
            return;
        }
        const unsigned type = geometry - first_curve_geometry;
        const uint32_t pieces = Pieces(static_cast<CurveType>(type));
        hit->triangle = gpu::kCurveBit | curves[group][type][primitive / pieces];
        hit->b1 = (static_cast<float>(primitive % pieces) + hit->b1) / static_cast<float>(pieces);
        hit->origin = ray.origin;
        hit->direction = ray.direction;
    }
};

absl::StatusOr<std::unique_ptr<EmbreeTracer>> EmbreeTracer::Create(const Scene& scene) {
    absl::StatusOr<Device> device = Device::Create();
    if (!device.ok()) return device.status();
    auto handles = std::make_unique<Handles>(std::move(*device));
    // Embree's own error where it gave one; rtcSetNewGeometryBuffer may fail without.
    const auto out_of_memory = [&](const std::string& what) {
        const std::string reason = handles->device.LastError();
        return absl::ResourceExhaustedError(absl::StrCat(scene.source,
                                                         ": cannot allocate Embree's buffer of ",
                                                         what, reason.empty() ? "" : ": ", reason));
    };
    // Embree reads vertices 16 bytes at a time: the last one needs 4 bytes of padding.
    const size_t vertex_count = scene.positions.size();
    handles->vertices =
        rtcNewBuffer(handles->device.Handle(), sizeof(float) * 3 * vertex_count + sizeof(float));
    auto* vertices =
        handles->vertices ? static_cast<float*>(rtcGetBufferData(handles->vertices)) : nullptr;
    if (vertices == nullptr) return out_of_memory(absl::StrCat(vertex_count, " vertices"));
    for (size_t v = 0; v < vertex_count; ++v) {
        vertices[3 * v] = scene.positions[v].x;
        vertices[3 * v + 1] = scene.positions[v].y;
        vertices[3 * v + 2] = scene.positions[v].z;
    }
    // Cut-outs cost a filter call per candidate hit: only where a material has them.
    const auto cut_out = [&](uint32_t material) { return scene.materials[material].HasCutOuts(); };
    if (std::any_of(scene.triangles.begin(), scene.triangles.end(),
                    [&](const Triangle& t) { return cut_out(t.material); }) ||
        std::any_of(scene.curves.begin(), scene.curves.end(),
                    [&](const Curve& c) { return cut_out(c.material); })) {
        handles->alpha = std::make_unique<Scene>();
        handles->alpha->triangles = scene.triangles;
        handles->alpha->curves = scene.curves;
        handles->alpha->uvs = scene.uvs;
        handles->alpha->materials = scene.materials;
        handles->alpha->textures = scene.textures;
        handles->alpha->colors = scene.colors;
    }
    handles->groups.resize(scene.prototypes.size() + 1);
    handles->curves.resize(scene.prototypes.size() + 1);
    for (size_t p = 0; p < scene.prototypes.size(); ++p) {
        const Prototype& prototype = scene.prototypes[p];
        RTCScene prototype_scene = rtcNewScene(handles->device.Handle());
        handles->prototypes.push_back(prototype_scene);
        rtcSetSceneBuildQuality(prototype_scene, RTC_BUILD_QUALITY_HIGH);
        // A prototype of no triangles (an object of no shapes) is an empty scene: nothing to hit.
        if (prototype.triangle_count > 0 &&
            !handles->AttachGroup(prototype_scene, scene, prototype.first_triangle,
                                  prototype.triangle_count, vertex_count, &handles->groups[1 + p]))
            return out_of_memory(
                absl::StrCat("prototype ", p, "'s ", prototype.triangle_count, " triangles"));
        if (!handles->AttachCurveTypes(prototype_scene, scene.curves, prototype.first_curve,
                                       prototype.curve_count, kPrototypeFirstCurveGeometry, 1 + p))
            return out_of_memory(
                absl::StrCat("prototype ", p, "'s ", prototype.curve_count, " curves"));
        rtcCommitScene(prototype_scene);
    }
    handles->scene = rtcNewScene(handles->device.Handle());
    rtcSetSceneBuildQuality(handles->scene, RTC_BUILD_QUALITY_HIGH);
    if (scene.WorldTriangleCount() > 0 &&
        !handles->AttachGroup(handles->scene, scene, 0, scene.WorldTriangleCount(), vertex_count,
                              &handles->groups[0]))
        return out_of_memory(absl::StrCat(scene.WorldTriangleCount(), " triangles"));
    if (!handles->AttachCurveTypes(
            handles->scene, scene.curves, 0, scene.WorldCurveCount(),
            kFirstInstanceGeometry + static_cast<unsigned>(scene.instances.size()), 0))
        return out_of_memory(absl::StrCat(scene.WorldCurveCount(), " curves"));
    for (uint32_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& instance = scene.instances[i];
        RTCGeometry geometry = rtcNewGeometry(handles->device.Handle(), RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(geometry, handles->prototypes[instance.prototype]);
        rtcSetGeometryTransform(geometry, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR,
                                instance.to_world.data());
        rtcCommitGeometry(geometry);
        rtcAttachGeometryByID(handles->scene, geometry, kFirstInstanceGeometry + i);
        rtcReleaseGeometry(geometry);
        handles->instance_group.push_back(1 + instance.prototype);
    }
    rtcCommitScene(handles->scene);
    if (!handles->device.LastError().empty())
        return absl::InternalError(handles->device.LastError());
    return std::unique_ptr<EmbreeTracer>(new EmbreeTracer(std::move(handles)));
}

EmbreeTracer::EmbreeTracer(std::unique_ptr<Handles> handles) : handles_(std::move(handles)) {}
EmbreeTracer::~EmbreeTracer() = default;

bool EmbreeTracer::Intersect(const Ray& ray, RayHit* hit) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit ray_hit;
    ray_hit.ray = ToRtcRay(ray);
    ray_hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    ray_hit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(handles_->scene, &context, &ray_hit);
    if (ray_hit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    hit->t = ray_hit.ray.tfar;
    hit->b1 = ray_hit.hit.u;
    hit->b2 = ray_hit.hit.v;
    handles_->ToRayHit(ray_hit.hit.instID[0], ray_hit.hit.geomID, ray_hit.hit.primID, ray, hit);
    return true;
}

void EmbreeTracer::IntersectPacket(const Ray (&rays)[kPacketSize],
                                   const bool (&active)[kPacketSize], RayHit (&hits)[kPacketSize],
                                   bool (&found)[kPacketSize]) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    alignas(32) int valid[kPacketSize];
    alignas(32) RTCRayHit8 packet;
    ToRtcRays(rays, active, valid, &packet.ray);
    for (int i = 0; i < kPacketSize; ++i) {
        packet.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        packet.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect8(valid, handles_->scene, &context, &packet);
    for (int i = 0; i < kPacketSize; ++i) {
        if (!active[i]) continue;
        found[i] = packet.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
        if (!found[i]) continue;
        hits[i].t = packet.ray.tfar[i];
        hits[i].b1 = packet.hit.u[i];
        hits[i].b2 = packet.hit.v[i];
        handles_->ToRayHit(packet.hit.instID[0][i], packet.hit.geomID[i], packet.hit.primID[i],
                           rays[i], &hits[i]);
    }
}

void EmbreeTracer::OccludedPacket(const Ray (&rays)[kPacketSize], const bool (&active)[kPacketSize],
                                  bool (&occluded)[kPacketSize]) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    alignas(32) int valid[kPacketSize];
    alignas(32) RTCRay8 packet;
    ToRtcRays(rays, active, valid, &packet);
    rtcOccluded8(valid, handles_->scene, &context, &packet);
    for (int i = 0; i < kPacketSize; ++i)
        if (active[i]) occluded[i] = packet.tfar[i] < 0.0f;  // Embree sets tfar to -inf on a hit
}

uint64_t EmbreeTracer::CountHits(std::span<const Ray> rays) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    uint64_t hits = 0;
    for (const Ray& ray : rays) {
        RTCRayHit ray_hit;
        ray_hit.ray = ToRtcRay(ray);
        ray_hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(handles_->scene, &context, &ray_hit);
        hits += ray_hit.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }
    return hits;
}

bool EmbreeTracer::Occluded(const Ray& ray) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay r = ToRtcRay(ray);
    rtcOccluded1(handles_->scene, &context, &r);
    return r.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

}  // namespace pf::embree
