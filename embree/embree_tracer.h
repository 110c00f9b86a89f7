// The Tracer over Embree 3: the world's triangles and curves (Embree's curve primitives) and the
// scene's instances, each placing a prototype's own BVH (two levels), single-ray and 8-wide
// queries. The only place
// (with its .cpp) that includes Embree.
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include "absl/status/statusor.h"
#include "core/geometry/tracer.h"
#include "core/scene/scene.h"

namespace pf::embree {

class EmbreeTracer final : public Tracer {
public:
    // Builds the BVHs over scene.triangles and scene.curves: the world's, one per prototype, and
    // one over the instances. Hits name Scene::triangles (or curves) and Scene::instances. The
    // scene's geometry is copied; the scene need not outlive the tracer.
    static absl::StatusOr<std::unique_ptr<EmbreeTracer>> Create(const Scene& scene);
    ~EmbreeTracer() override;
    EmbreeTracer(const EmbreeTracer&) = delete;
    EmbreeTracer& operator=(const EmbreeTracer&) = delete;

    bool Intersect(const Ray& ray, RayHit* hit) const override;
    bool Occluded(const Ray& ray) const override;
    void IntersectPacket(const Ray (&rays)[kPacketSize], const bool (&active)[kPacketSize],
                         RayHit (&hits)[kPacketSize], bool (&found)[kPacketSize]) const override;
    void OccludedPacket(const Ray (&rays)[kPacketSize], const bool (&active)[kPacketSize],
                        bool (&occluded)[kPacketSize]) const override;

    // Casts every ray with bare rtcIntersect1 calls, returning how many hit: the raw ray rate
    // that benchmarks compare the photon pass against, free of this class's own overhead.
    uint64_t CountHits(std::span<const Ray> rays) const;

private:
    struct Handles;
    explicit EmbreeTracer(std::unique_ptr<Handles> handles);
    std::unique_ptr<Handles> handles_;
};

}  // namespace pf::embree
