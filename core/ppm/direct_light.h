// Direct lighting at diffuse points: one light sample with a shadow ray and, where the scene
// has emitting triangles or an environment, one cosine-distributed ray that may find one,
// weighed against each other by the power heuristic (Veach 1997, ch. 9). Light sampling alone
// leaves fireflies wherever a point sits close to an emitting surface (its 1/d^2); the cosine ray
// finds that light with a bounded weight. Taken once per hit point per epoch and averaged, so
// direct light converges like the photons do while the photons carry only indirect light.
#pragma once

#include <cstdint>
#include <span>

#include "core/geometry/tracer.h"
#include "core/job/hit_point.h"
#include "core/sampling/rng.h"
#include "core/scene/emitters.h"
#include "core/scene/material.h"

namespace pf {

// The rays of one direct-light sample at point p with unit normal n (toward the side lit),
// drawn from rng: 3 numbers for the light sample, then 2 for the cosine ray where a ray can
// find an emitter (a triangle, the environment), then 2 for the microfacet of a rough coat
// over p (`coat`, or nullptr). The Vulkan kernel draws the same numbers in the same order.
struct DirectLightRays {
    LightSample light;
    bool light_active = false;
    Ray bsdf_ray;
    bool bsdf_active = false;
    const Material* coat = nullptr;
    float coat_u1 = 0, coat_u2 = 0;
};
DirectLightRays StartDirectLight(const Emitters& emitters, const Vec3& p, const Vec3& n,
                                 const Material* coat, Rng& rng);
// The numbers of one sample drawn elsewhere: the emitter's pick, the point on it, the cosine
// ray's direction and the coat's microfacet.
struct DirectLightNumbers {
    float pick = 0;
    Point2 light, cosine, coat;
    bool pick_from_light = false;  // light.x picks the emitter too (Emitters::SampleDirect)
};
DirectLightRays StartDirectLight(const Emitters& emitters, const Vec3& p, const Vec3& n,
                                 const Material* coat, const DirectLightNumbers& numbers);

// The sample's estimate of the irradiance at p, the integral of L_i cos over the hemisphere
// (a diffuse point reflects it times albedo / pi) -- under a coat, of L_i cos times the
// fraction of it the coat lets through to p -- from whether the shadow ray was occluded and
// what the cosine ray hit (nullptr where it hit nothing or was not cast).
Rgb FinishDirectLight(const Emitters& emitters, const Vec3& n, const DirectLightRays& rays,
                      bool occluded, const RayHit* bsdf_hit);

// Both steps with single rays.
Rgb SampleDirectIrradiance(const Emitters& emitters, const Tracer& tracer, const Vec3& p,
                           const Vec3& n, const Material* coat, Rng& rng);

// The streams of epoch `epoch`'s direct-light samples: hit point h draws from
// Rng(DirectLightSeeds(seed, epoch).Seed(h)), on every backend.
SeedFamily DirectLightSeeds(uint64_t seed, uint64_t epoch);

// Where the direct-light samples of an epoch's camera pass in slot order (pixel * k + sample:
// a StochasticCameraPass) take their numbers: slot s of pixel p takes the index first + s of
// p's sequences for the epoch's parity (EpochCameraSamples), as its camera sample does, so
// that a pixel's light samples are stratified across epochs as its camera samples are.
struct DirectLightSequence {
    int samples_per_pixel = 0;  // the pass's k
    uint64_t first = 0;
    int slots_per_sample = 1;  // 1 + gather rays for rpm (CameraPassSettings::gather_rays)
};
// The part of seed's pixel sequences of direct light that all pixels share
// (gpu::FamilyPartial), for the Vulkan kernel to derive each pixel's.
uint64_t DirectLightSequences(uint64_t seed);

// One sample each of the light reflected at hit_points[first + i] toward its camera path,
// already multiplied by the hit point's weight (throughput x BSDF), in W/(m^2 sr), into
// out[i]. Hit point h's sample in `epoch` draws from a stream seeded by (seed, epoch, h)
// alone, or, given `sequence`, from its pixel's scrambled (0,2)-sequences keyed by (seed,
// pixel, epoch's parity, index). Rays are cast in packets. A sample that comes out NaN or Inf
// is set to 0; returns how many were. `materials` holds the hit points' coats. A hit point
// that gathers direct photons (rpm's gather hits) takes no sample: 0. `points_offset`: the
// index h of hit_points[0], where they are a part of a larger set (a worker's part of an epoch's
// camera pass); `first` and h count in the whole set.
uint64_t SampleDirectLight(const Emitters& emitters, const Tracer& tracer,
                           std::span<const Material> materials,
                           std::span<const HitPoint> hit_points, uint32_t first, uint64_t seed,
                           uint64_t epoch, const DirectLightSequence* sequence, std::span<Rgb> out,
                           uint64_t points_offset = 0);

}  // namespace pf
