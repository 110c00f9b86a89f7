// Photon tracing with Russian roulette and the gather into the hit-point grid
// (Hachisuka et al. 2008, section 4.2; Jensen 2001 for the photon random walk).
#include "core/ppm/photon_pass.h"

#include <algorithm>

#include "core/math/frame.h"
#include "core/ppm/direct_light.h"
#include "core/sampling/rng.h"
#include "core/sampling/sampling.h"
#include "core/scene/specular.h"
#include "core/util/radix_sort.h"

namespace pf {
namespace {

// Stream ids separating the random numbers of photons from those of direct light.
constexpr uint64_t kPhotonStream = 0x70686f746f6e0001ull;

// A photon path in flight.
struct PhotonPath {
    Ray ray;
    Rgb flux;
    Rng rng;
    bool scattered = false;  // the first hit of an unscattered photon is direct light
    int bounces = 0;
};

// Photon `photon` of the batch whose streams `seeds` holds: its random numbers are a function
// of (job seed, batch index, photon index) alone.
PhotonPath StartPhoton(const PhotonPassInputs& inputs, const SeedFamily& seeds, uint32_t photon) {
    PhotonPath path;
    path.rng = Rng(seeds.Seed(photon));
    const EmittedPhoton emitted = inputs.emitters->Emit(path.rng);
    path.ray = emitted.ray;
    path.flux = emitted.flux;
    return path;
}

// Continues a path at its hit: a deposit at every diffuse hit after the first scattering,
// Russian roulette, the next ray. Returns false where the path ends.
bool ScatterPhoton(const PhotonPassInputs& inputs, const RayHit& hit, PhotonPath& path,
                   std::vector<PhotonDeposit>& deposits) {
    const Scene& scene = *inputs.scene;
    Ray& ray = path.ray;
    const SurfacePoint surface = scene.Surface(hit);
    const Material& material = scene.materials[surface.material];
    const bool front_facing = Dot(ray.direction, surface.geometric_normal) < 0;
    const Rgb base_color = scene.BaseColor(surface);
    if (material.type == MaterialType::kDiffuse) {
        if (path.scattered) deposits.push_back({surface.position, ray.direction, path.flux});
        // Russian roulette by albedo: survivors carry flux * albedo / p (Jensen 2001, 2.3.3).
        const float survive = std::min(1.0f, MaxComponent(base_color));
        if (!(path.rng.NextFloat() < survive)) return false;
        path.flux *= base_color / survive;
        const Vec3 normal = front_facing ? surface.shading_normal : -surface.shading_normal;
        const Vec3 geometric = front_facing ? surface.geometric_normal : -surface.geometric_normal;
        ray.direction = Frame::FromNormal(normal).ToWorld(
            SampleCosineHemisphere(path.rng.NextFloat(), path.rng.NextFloat()));
        if (!(Dot(ray.direction, geometric) > 0)) return false;  // shading normal pointed it inside
        ray.origin = OffsetRayOrigin(surface.position, geometric);
    } else {
        const SpecularBounce bounce = ScatterSpecular(material, ray.direction, surface.shading_normal, front_facing,
                                                      base_color, path.rng.NextFloat());
        const float survive = std::min(1.0f, MaxComponent(bounce.weight));
        if (!(path.rng.NextFloat() < survive)) return false;
        path.flux *= bounce.weight / survive;
        const Vec3 side = front_facing == bounce.transmitted ? -surface.geometric_normal : surface.geometric_normal;
        ray.origin = OffsetRayOrigin(surface.position, side);
        ray.direction = bounce.direction;
    }
    ray.t_max = std::numeric_limits<float>::infinity();
    path.scattered = true;
    return ++path.bounces < kMaxPhotonBounces;
}

// Adds every deposit to the hit points within their radius whose surface faces the photon.
// Deposits are visited in the order of their grid bucket (ties in path order), so the grid's
// arrays are read front to back instead of at random: a deterministic order, and a much
// faster one once the hit points no longer fit in cache.
void GatherDeposits(const PhotonPassInputs& inputs, BatchScratch& scratch) {
    const std::vector<PhotonDeposit>& deposits = scratch.deposits;
    std::vector<uint64_t>& keys = scratch.sort_keys;
    keys.resize(deposits.size());
    for (size_t i = 0; i < deposits.size(); ++i)
        keys[i] = uint64_t{inputs.grid->BucketOf(deposits[i].position)} << 32 | i;
    // Keys are already in deposit order: a stable sort by bucket alone orders them fully.
    RadixSortBits(keys, scratch.sort_scratch, 32, inputs.grid->BucketBits());
    // Permute in a loop of its own: its loads are independent and overlap, where inside the
    // gather each would stall the loop.
    std::vector<PhotonDeposit>& sorted = scratch.sorted_deposits;
    sorted.resize(deposits.size());
    for (size_t i = 0; i < keys.size(); ++i) sorted[i] = deposits[static_cast<uint32_t>(keys[i])];
    for (const PhotonDeposit& deposit : sorted) {
        inputs.grid->ForEachGathering(deposit.position, deposit.direction,
                                      [&](uint32_t index) { scratch.tally.Add(index, deposit.flux); });
    }
    scratch.deposits.clear();
}

// Traces the batch's photons a packet at a time: each lane of the packet carries one path,
// and a lane whose path ends takes the next photon, so packets stay full. Every photon's
// random numbers depend on its index alone, and lanes are filled in a fixed order, so the
// deposits (and their order) depend only on the batch. Returns the segments traced.
uint64_t TracePhotons(const PhotonPassInputs& inputs, const BatchSpec& spec, BatchScratch& scratch) {
    constexpr int kLanes = Tracer::kPacketSize;
    PhotonPath paths[kLanes];
    Ray rays[kLanes] = {};
    RayHit hits[kLanes];
    bool active[kLanes], found[kLanes];
    const SeedFamily seeds(inputs.seed, kPhotonStream, spec.index);
    uint32_t next = 0;
    int live = 0;
    for (int lane = 0; lane < kLanes; ++lane) {
        active[lane] = next < spec.photons;
        if (active[lane]) paths[lane] = StartPhoton(inputs, seeds, next++), ++live;
    }
    uint64_t segments = 0;
    while (live > 0) {
        for (int lane = 0; lane < kLanes; ++lane)
            if (active[lane]) rays[lane] = paths[lane].ray;
        inputs.tracer->IntersectPacket(rays, active, hits, found);
        for (int lane = 0; lane < kLanes; ++lane) {
            if (!active[lane]) continue;
            ++segments;
            if (found[lane] && ScatterPhoton(inputs, hits[lane], paths[lane], scratch.deposits)) continue;
            if (next < spec.photons) {
                paths[lane] = StartPhoton(inputs, seeds, next++);
            } else {
                active[lane] = false;
                --live;
            }
        }
        // Bounded memory however long the paths (albedo near 1): gather in chunks, at points
        // fixed by the batch alone, so the sums stay deterministic.
        if (scratch.deposits.size() >= kMaxPendingDeposits) GatherDeposits(inputs, scratch);
    }
    return segments;
}

}  // namespace

BatchResult RunPhotonBatch(const PhotonPassInputs& inputs, const BatchSpec& spec, BatchScratch& scratch) {
    BatchResult result;
    result.spec = spec;
    scratch.tally.Resize(inputs.hit_points.size());
    scratch.deposits.clear();
    result.segments_traced = TracePhotons(inputs, spec, scratch);
    GatherDeposits(inputs, scratch);
    result.photons_emitted = spec.photons;
    result.tally = scratch.tally.Extract();
    result.direct.resize(spec.direct_end - spec.direct_begin);
    SampleDirectLight(*inputs.emitters, *inputs.tracer, inputs.hit_points, spec.direct_begin, inputs.seed, spec.epoch,
                      result.direct);
    return result;
}

}  // namespace pf
