// Initial search radii from the photons: each hit point's R0 from the local density of a pilot
// photon map (its k nearest photons) rather than one pixel footprint everywhere, so that a hit
// point in a dim corner starts wide enough to catch photons and one in a bright caustic starts
// narrow enough not to blur it. The progressive estimate stays consistent whatever R0 is; the
// density only chooses where it starts.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/geometry/tracer.h"
#include "core/job/hit_point.h"
#include "core/scene/emitters.h"
#include "core/scene/scene.h"
#include "core/scene/scene_features.h"

namespace pf {

struct DensityRadiiSettings {
    // Photons emitted for the pilot maps (each, global and caustic, as BuildPhotonMaps). k
    // nearest of fewer photons span more surface, but the density's noise is k's: on
    // cornell-box at 128x128, four seeds, 2^16 gave the RMSE 2^18 gave to three digits at 20M
    // photons, in 0.04 s where 2^18 took 0.15 s before the first image.
    uint64_t pilot_photons = uint64_t{1} << 16;
    uint32_t nearest = 16;  // k of the density estimate
    // R0 is chosen so that the first epoch's photons put about this many within it. On
    // cornell-box at 256x256 (20 s, two cores, ppm's 2^22 photons an epoch), 16 gave radii
    // half the pixel footprint and a relative error of 2.0% (the footprint: 1.3%); 64: 1.3%;
    // 256: 1.1% (RMSE 0.00218 against 0.00223-0.00243), about what a uniform R0 of twice the
    // footprint gives there; 1024: 1.1%, photons 10% slower (wider discs gather more).
    double first_epoch_photons_found = 256;
    // Emitted in the first pass (> 0): a full epoch's, the growing epochs being one pass
    // together (ProgressiveEstimate::FinishEpoch).
    uint64_t first_epoch_photons = 0;
    // Bounds in pixel footprints of the hit point (CameraPassResult::footprint), and in the
    // scene's diagonal.
    double least_footprints = 0.25, most_footprints = 8, most_diagonal = 0.01;
    uint64_t seed = 0;
    int max_depth = 0;  // JobSpec::max_depth
};

// One R0 per hit point (world units): sqrt(c / (pi rho M)), rho the pilot's photons per unit
// area and emitted photon around it, of the photons it gathers (HitPoint::gathers: for ppm's
// those that scattered before, the global map's and the caustic map's; rpm's gather hits every
// landing; its camera hit points the caustic map's alone, 0 where it finds none), M the first
// epoch's photons and c the photons it should find, clamped to the bounds; `fallback` where
// the footprint is 0 (an empty slot of a stochastic pass). Deterministic for the seed; in
// parallel on the calling TBB arena.
std::vector<float> DensityInitialRadii(const Scene& scene, const Emitters& emitters,
                                       const Tracer& tracer, const SceneFeatures& features,
                                       std::span<const HitPoint> hit_points,
                                       std::span<const float> footprint, float fallback,
                                       const DensityRadiiSettings& settings);

}  // namespace pf
