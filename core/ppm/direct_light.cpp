// Next-event estimation at hit points.
#include "core/ppm/direct_light.h"

namespace pf {
namespace {
constexpr uint64_t kDirectStream = 0x646972656374ull;
}  // namespace

Rng DirectLightRng(uint64_t seed, uint64_t epoch, uint32_t hit_point) {
    return Rng(HashSeed(seed, kDirectStream, epoch, hit_point));
}

Rgb SampleDirectLight(const Emitters& emitters, const Tracer& tracer, const HitPoint& hit_point,
                      Rng rng) {
    LightSample sample;
    if (!emitters.SampleDirect(hit_point.position, hit_point.normal, rng, &sample)) return Rgb(0.0f);
    if (tracer.Occluded(sample.shadow_ray)) return Rgb(0.0f);
    return hit_point.weight * sample.radiance_over_pdf * Dot(sample.direction, hit_point.normal);
}

}  // namespace pf
