// Next-event estimation at hit points.
#include "core/ppm/direct_light.h"

#include <algorithm>

#include "core/sampling/rng.h"
#include "core/util/check.h"

namespace pf {
SeedFamily DirectLightSeeds(uint64_t seed, uint64_t epoch) {
    constexpr uint64_t kDirectStream = 0x646972656374ull;
    return SeedFamily(seed, kDirectStream, epoch);
}

uint64_t SampleDirectLight(const Emitters& emitters, const Tracer& tracer, std::span<const HitPoint> hit_points,
                           uint32_t first, uint64_t seed, uint64_t epoch, std::span<Rgb> out) {
    uint64_t discarded = 0;
    PF_CHECK(first + out.size() <= hit_points.size());
    constexpr int kLanes = Tracer::kPacketSize;
    const SeedFamily seeds = DirectLightSeeds(seed, epoch);
    for (size_t begin = 0; begin < out.size(); begin += kLanes) {
        const int lanes = static_cast<int>(std::min<size_t>(kLanes, out.size() - begin));
        Ray rays[kLanes] = {};
        bool active[kLanes] = {}, occluded[kLanes];
        LightSample samples[kLanes];
        for (int lane = 0; lane < lanes; ++lane) {
            const uint32_t index = first + static_cast<uint32_t>(begin) + lane;
            const HitPoint& hit_point = hit_points[index];
            Rng rng(seeds.Seed(index));
            active[lane] = emitters.SampleDirect(hit_point.position, hit_point.normal, rng, &samples[lane]);
            if (active[lane]) rays[lane] = samples[lane].shadow_ray;
        }
        tracer.OccludedPacket(rays, active, occluded);
        for (int lane = 0; lane < lanes; ++lane) {
            const HitPoint& hit_point = hit_points[first + begin + lane];
            const Rgb sample = active[lane] && !occluded[lane] ? hit_point.weight * samples[lane].radiance_over_pdf *
                                                                     Dot(samples[lane].direction, hit_point.normal)
                                                               : Rgb(0.0f);
            const bool finite = IsFinite(sample);
            discarded += !finite;
            out[begin + lane] = finite ? sample : Rgb(0.0f);
        }
    }
    return discarded;
}

}  // namespace pf
