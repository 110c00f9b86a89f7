// The photon walk of one batch's photons, as the uniform loop (photon_pass.cpp) and the
// adaptive one (adaptive_photons.cpp) share it: a path in flight, its start and its step, and
// the gather of a chunk's deposits. Internal to core/ppm. The two loops live in translation units
// of their own: in one, GCC stopped inlining the walk into the uniform loop (photon_bench: -5%).
#pragma once

#include <cstdint>
#include <vector>

#include "core/ppm/photon_pass.h"
#include "core/ppm/photon_walk.h"
#include "core/sampling/rng.h"
#include "core/scene/emitters.h"

namespace pf::photon_trace {

// A photon path in flight.
struct PhotonPath {
    Ray ray;
    Rgb flux;
    Rng rng;
    bool scattered = false;  // the first hit of an unscattered photon is direct light
    bool diffused = false;   // it has scattered at a diffuse surface (no longer a caustic)
    int bounces = 0;
    const PunctualLight* ranged = nullptr;  // the light's window is still to apply at the first hit
};

// A photon emitted by `numbers` whose walk draws from `rng`.
inline PhotonPath StartPhotonFrom(const PhotonPassInputs& inputs, const EmissionNumbers& numbers,
                                  const Rng& rng) {
    PhotonPath path;
    path.rng = rng;
    const EmittedPhoton emitted = inputs.emitters->Emit(numbers);
    path.ray = emitted.ray;
    path.flux = emitted.flux;
    path.ranged = emitted.ranged;
    return path;
}

// Photon `photon` of the batch whose streams `seeds` holds: its random numbers are a function
// of (job seed, batch index, photon index) alone.
inline PhotonPath StartPhoton(const PhotonPassInputs& inputs, const SeedFamily& seeds,
                              uint32_t photon) {
    Rng rng(seeds.Seed(photon));
    const EmissionNumbers numbers = EmissionNumbers::Draw(rng);
    return StartPhotonFrom(inputs, numbers, rng);
}

// Continues a path at its hit (ScatterPhotonAt): a deposit at every diffuse hit after the
// first scattering (a coat turning a photon back to its base is a scattering), and at the first
// where inputs.direct_photons. Returns false where the path ends.
template <bool kSpecular, bool kTextures>
bool ScatterPhoton(const PhotonPassInputs& inputs, const RayHit& hit, PhotonPath& path,
                   std::vector<PhotonDeposit>& deposits) {
    if (path.ranged != nullptr) {  // the light's range, over the first segment
        path.flux *= path.ranged->RangeWindow(hit.t);
        path.ranged = nullptr;
    }
    const PhotonEvent event = ScatterPhotonAt<kSpecular, kTextures>(
        *inputs.scene, hit, path.ray, path.flux, path.rng,
        [&](const Vec3& position, const Vec3& direction, const Rgb& flux, bool returned,
            float cosine, const Vec3& normal) {
            const uint32_t kind = gpu::PhotonKind(path.scattered, path.diffused, returned);
            if (kind == kDirectPhoton && !inputs.direct_photons) return;
            // With shading normals, the flux per unit of its cosine: hit points weigh it by
            // theirs (GatherDeposits).
            if (!inputs.features.ShadingNormals())
                deposits.push_back({position, direction, flux, normal, kind});
            else if (cosine > 0)
                deposits.push_back({position, direction, flux / cosine, normal, kind});
        });
    if (event == PhotonEvent::kEnded) return false;
    path.scattered = true;
    path.diffused = path.diffused || event == PhotonEvent::kDiffuse;
    return ++path.bounces < inputs.max_bounces;
}

// Adds every deposit of `scratch` (weighed by deposit_counts, where there are any) to the hit
// points within their radius whose surface faces the photon, and empties them.
void GatherDeposits(const PhotonPassInputs& inputs, BatchScratch& scratch);

// Adaptive tracing's loop (adaptive_photons.cpp): photons [begin, end) of the batch as steps of
// Markov chains, the loop instantiated for the scene's features; returns the segments traced.
uint64_t TraceAdaptive(const PhotonPassInputs& inputs, const BatchSpec& spec, uint32_t begin,
                       uint32_t end, BatchScratch& scratch);

}  // namespace pf::photon_trace
