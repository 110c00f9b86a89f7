// Next-event estimation at hit points.
#include "core/ppm/direct_light.h"

#include <algorithm>

#include "core/camera/pixel_sample.h"
#include "core/sampling/frame.h"
#include "core/sampling/sampling.h"
#include "core/scene/scattering.h"
#include "core/util/check.h"

namespace pf {

namespace {

// The fraction of light arriving along `direction` that a coat lets through to the point
// (1 without one).
float CoatFactor(const DirectLightRays& rays, const Vec3& n, const Vec3& direction) {
    if (rays.coat == nullptr) return 1.0f;
    return gpu::CoatTransmittance(CoatOf(*rays.coat), ToLocal(FrameFromNormal(n), direction),
                                  rays.coat_u1, rays.coat_u2);
}

}  // namespace

DirectLightRays StartDirectLight(const Emitters& emitters, const Vec3& p, const Vec3& n,
                                 const Material* coat, Rng& rng) {
    // In the order the Vulkan kernel draws them.
    DirectLightNumbers numbers;
    numbers.pick = rng.NextFloat();
    numbers.light.x = rng.NextFloat();
    numbers.light.y = rng.NextFloat();
    if (emitters.FoundByRays()) {
        numbers.cosine.x = rng.NextFloat();
        numbers.cosine.y = rng.NextFloat();
    }
    if (coat != nullptr && coat->coat_roughness > 0) {
        numbers.coat.x = rng.NextFloat();
        numbers.coat.y = rng.NextFloat();
    }
    return StartDirectLight(emitters, p, n, coat, numbers);
}

DirectLightRays StartDirectLight(const Emitters& emitters, const Vec3& p, const Vec3& n,
                                 const Material* coat, const DirectLightNumbers& numbers) {
    DirectLightRays rays;
    rays.light_active = emitters.SampleDirect(p, n, numbers.pick, numbers.light, &rays.light,
                                              numbers.pick_from_light);
    if (emitters.FoundByRays()) {
        const Vec3 direction =
            ToWorld(FrameFromNormal(n), SampleCosineHemisphere(numbers.cosine.x, numbers.cosine.y));
        rays.bsdf_ray = {OffsetRayOrigin(p, n, emitters.SceneScale()), direction};
        rays.bsdf_active = true;
    }
    rays.coat = coat;
    if (coat != nullptr && coat->coat_roughness > 0) {
        rays.coat_u1 = numbers.coat.x;
        rays.coat_u2 = numbers.coat.y;
    }
    return rays;
}

Rgb FinishDirectLight(const Emitters& emitters, const Vec3& n, const DirectLightRays& rays,
                      bool occluded, const RayHit* bsdf_hit) {
    Rgb irradiance(0.0f);
    if (rays.light_active && !occluded) {
        const float cosine = Dot(rays.light.direction, n);
        // A punctual light (pdf 0) is found by light sampling alone.
        const float weight =
            rays.light.pdf > 0 ? PowerHeuristic(rays.light.pdf, cosine / kPi) : 1.0f;
        irradiance += rays.light.radiance_over_pdf *
                      (cosine * weight * CoatFactor(rays, n, rays.light.direction));
    }
    if (!rays.bsdf_active) return irradiance;
    const Ray& ray = rays.bsdf_ray;
    Emitters::Hit hit;
    if (bsdf_hit == nullptr)
        hit = emitters.Escaped(ray.origin, ray.direction);
    else if (bsdf_hit->instance == Instance::kNone)
        hit = emitters.HitEmitter(*bsdf_hit, ray.origin, ray.origin + ray.direction * bsdf_hit->t);
    // L cos / (cos / pi): the cosine ray's own weight is pi.
    if (hit.pdf > 0)
        irradiance += hit.radiance * (kPi * PowerHeuristic(Dot(ray.direction, n) / kPi, hit.pdf) *
                                      CoatFactor(rays, n, ray.direction));
    return irradiance;
}

Rgb SampleDirectIrradiance(const Emitters& emitters, const Tracer& tracer, const Vec3& p,
                           const Vec3& n, const Material* coat, Rng& rng) {
    const DirectLightRays rays = StartDirectLight(emitters, p, n, coat, rng);
    const bool occluded = rays.light_active && tracer.Occluded(rays.light.shadow_ray);
    RayHit hit;
    const bool found = rays.bsdf_active && tracer.Intersect(rays.bsdf_ray, &hit);
    return FinishDirectLight(emitters, n, rays, occluded, found ? &hit : nullptr);
}

namespace {
constexpr uint64_t kDirectStream = 0x646972656374ull;
}  // namespace

SeedFamily DirectLightSeeds(uint64_t seed, uint64_t epoch) {
    return SeedFamily(seed, kDirectStream, epoch);
}

uint64_t DirectLightSequences(uint64_t seed) { return gpu::FamilyPartial(seed, kDirectStream); }

uint64_t SampleDirectLight(const Emitters& emitters, const Tracer& tracer,
                           std::span<const Material> materials,
                           std::span<const HitPoint> hit_points, uint32_t first, uint64_t seed,
                           uint64_t epoch, const DirectLightSequence* sequence, std::span<Rgb> out,
                           uint64_t points_offset) {
    uint64_t discarded = 0;
    PF_CHECK(first >= points_offset && first - points_offset + out.size() <= hit_points.size());
    // The points sampled, out[i]'s at points[i]; its index in the whole set is first + i.
    const std::span<const HitPoint> points = hit_points.subspan(first - points_offset, out.size());
    constexpr int kLanes = Tracer::kPacketSize;
    const SeedFamily seeds = DirectLightSeeds(seed, epoch);
    const uint64_t sequences = DirectLightSequences(seed);
    for (size_t begin = 0; begin < out.size(); begin += kLanes) {
        const int lanes = static_cast<int>(std::min<size_t>(kLanes, out.size() - begin));
        DirectLightRays samples[kLanes];
        Ray shadow_rays[kLanes] = {}, bsdf_rays[kLanes] = {};
        bool shadow_active[kLanes] = {}, bsdf_active[kLanes] = {}, occluded[kLanes] = {},
             found[kLanes] = {};
        RayHit hits[kLanes];
        for (int lane = 0; lane < lanes; ++lane) {
            const uint32_t index = first + static_cast<uint32_t>(begin) + lane;
            const HitPoint& hit_point = points[begin + lane];
            if (hit_point.gathers & kDirectPhoton) continue;  // its photons carry direct light
            const Material* coat = hit_point.coat == kNoCoat ? nullptr : &materials[hit_point.coat];
            if (sequence != nullptr) {
                // The emitter's pick with the point on it, and the cosine ray, from the pixel's
                // sequences (PixelSampler's, drawn as the Vulkan kernel draws them); the coat's
                // microfacet from the point's stream.
                const uint64_t prefix = gpu::FamilyPrefixOf(
                    sequences, PixelSampler::SequenceOf(hit_point.pixel, epoch));
                const uint64_t slots = uint64_t(sequence->slots_per_sample);
                const auto sample = static_cast<uint32_t>(
                    sequence->first + (index - uint64_t{hit_point.pixel} *
                                                   uint64_t(sequence->samples_per_pixel) * slots) /
                                          slots);
                DirectLightNumbers numbers;
                numbers.light = gpu::SequenceSample2D(prefix, sample, 0);
                numbers.pick_from_light = true;
                if (emitters.FoundByRays())
                    numbers.cosine = gpu::SequenceSample2D(prefix, sample, 1);
                if (coat != nullptr && coat->coat_roughness > 0) {
                    Rng rng(seeds.Seed(index));
                    numbers.coat.x = rng.NextFloat();
                    numbers.coat.y = rng.NextFloat();
                }
                samples[lane] =
                    StartDirectLight(emitters, hit_point.position, hit_point.normal, coat, numbers);
            } else {
                Rng rng(seeds.Seed(index));
                samples[lane] =
                    StartDirectLight(emitters, hit_point.position, hit_point.normal, coat, rng);
            }
            shadow_active[lane] = samples[lane].light_active;
            shadow_rays[lane] = samples[lane].light.shadow_ray;
            bsdf_active[lane] = samples[lane].bsdf_active;
            bsdf_rays[lane] = samples[lane].bsdf_ray;
        }
        tracer.OccludedPacket(shadow_rays, shadow_active, occluded);
        if (emitters.FoundByRays()) tracer.IntersectPacket(bsdf_rays, bsdf_active, hits, found);
        for (int lane = 0; lane < lanes; ++lane) {
            const HitPoint& hit_point = points[begin + lane];
            if (hit_point.gathers & kDirectPhoton) {
                out[begin + lane] = Rgb(0.0f);
                continue;
            }
            const Rgb sample =
                hit_point.weight * FinishDirectLight(emitters, hit_point.normal, samples[lane],
                                                     occluded[lane],
                                                     found[lane] ? &hits[lane] : nullptr);
            const bool finite = IsFinite(sample);
            discarded += !finite;
            out[begin + lane] = finite ? sample : Rgb(0.0f);
        }
    }
    return discarded;
}

}  // namespace pf
