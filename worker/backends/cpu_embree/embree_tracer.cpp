// Embree 3 device, scene and queries. Errors reach us through one device error callback.
#include "worker/backends/cpu_embree/embree_tracer.h"

#include <embree3/rtcore.h>
#include <spdlog/spdlog.h>

#include <limits>
#include <string>

#include "absl/strings/str_cat.h"

namespace pf::embree {
namespace {

void OnEmbreeError(void* user, RTCError code, const char* message) {
    auto* last_error = static_cast<std::string*>(user);
    *last_error = absl::StrCat("Embree error ", static_cast<int>(code), ": ", message ? message : "");
    spdlog::error("{}", *last_error);
}

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
        packet->org_x[i] = ray.origin.x, packet->org_y[i] = ray.origin.y, packet->org_z[i] = ray.origin.z;
        packet->dir_x[i] = ray.direction.x, packet->dir_y[i] = ray.direction.y, packet->dir_z[i] = ray.direction.z;
        packet->tnear[i] = 0.0f;
        packet->tfar[i] = active[i] ? ray.t_max : 0.0f;
        packet->time[i] = 0.0f;
        packet->mask[i] = std::numeric_limits<unsigned>::max();
        packet->id[i] = 0;
        packet->flags[i] = 0;
    }
}

}  // namespace

struct EmbreeTracer::Handles {
    std::string last_error;
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    ~Handles() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

absl::StatusOr<std::unique_ptr<EmbreeTracer>> EmbreeTracer::Create(const Scene& scene) {
    auto handles = std::make_unique<Handles>();
    handles->device = rtcNewDevice(nullptr);
    if (handles->device == nullptr)
        return absl::UnavailableError("cannot create an Embree device (CPU without SSE2?)");
    rtcSetDeviceErrorFunction(handles->device, OnEmbreeError, &handles->last_error);
    handles->scene = rtcNewScene(handles->device);
    rtcSetSceneBuildQuality(handles->scene, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry geometry = rtcNewGeometry(handles->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                                  RTC_FORMAT_FLOAT3, sizeof(float) * 3,
                                                                  scene.positions.size()));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0,
                                                                    RTC_FORMAT_UINT3, sizeof(unsigned) * 3,
                                                                    scene.triangles.size()));
    if (vertices == nullptr || indices == nullptr) {
        rtcReleaseGeometry(geometry);
        return absl::ResourceExhaustedError(absl::StrCat("cannot allocate Embree buffers: ", handles->last_error));
    }
    for (size_t v = 0; v < scene.positions.size(); ++v) {
        vertices[3 * v] = scene.positions[v].x;
        vertices[3 * v + 1] = scene.positions[v].y;
        vertices[3 * v + 2] = scene.positions[v].z;
    }
    for (size_t t = 0; t < scene.triangles.size(); ++t)
        for (int k = 0; k < 3; ++k) indices[3 * t + k] = scene.triangles[t].vertex[k];
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(handles->scene, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(handles->scene);
    if (!handles->last_error.empty()) return absl::InternalError(handles->last_error);
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
    hit->triangle = ray_hit.hit.primID;
    hit->b1 = ray_hit.hit.u;
    hit->b2 = ray_hit.hit.v;
    return true;
}

void EmbreeTracer::IntersectPacket(const Ray (&rays)[kPacketSize], const bool (&active)[kPacketSize],
                                   RayHit (&hits)[kPacketSize], bool (&found)[kPacketSize]) const {
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
        hits[i] = {packet.ray.tfar[i], packet.hit.primID[i], packet.hit.u[i], packet.hit.v[i]};
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
