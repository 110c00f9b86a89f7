// Initial search radii from the photons: each hit point's R0 from the local density of a pilot
// photon map (its k nearest photons) rather than one pixel footprint everywhere, so that a hit
// point in a dim corner starts wide enough to catch photons and one in a bright caustic starts
// narrow enough not to blur it. The progressive estimate stays consistent whatever R0 is; the
// density only chooses where it starts.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include "core/geometry/tracer.h"
#include "core/job/hit_point.h"
#include "core/job/job_spec.h"
#include "core/pm/photon_map.h"
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

// Reverse photon mapping's: classic photon mapping's radii, those its k nearest
// (PhotonMapSettings::nearest) reach in a global map of its global_photons, within its
// search's limit (MaxSearchRadius), whatever the pixels' footprints.
DensityRadiiSettings ReverseRadiiSettings(const JobSpec& spec, const Scene& scene);

// The pilot maps kept, for radii asked again and again (reverse photon mapping's: its slots
// move every epoch, each taking the radius its new place and kind call for). `everything`:
// the global map holds every landing (some hit point gathers direct light), and then stands
// for the caustic map's too but where a hit point gathers caustics alone. Immutable once built.
class DensityRadii {
public:
    // `cells`: count the photons per cell too, for CellRadii.
    DensityRadii(const Scene& scene, const Emitters& emitters, const Tracer& tracer,
                 const SceneFeatures& features, bool everything,
                 const DensityRadiiSettings& settings, bool cells = false);
    // DensityInitialRadii's radii at `hit_points`, the density from each map's k nearest.
    // Thread-safe.
    std::vector<float> Radii(std::span<const HitPoint> hit_points, std::span<const float> footprint,
                             float fallback) const;
    // The same from the photons counted per cell of a grid over the maps (built with `cells`;
    // cells about twice
    // the k nearest's median reach, so a cell of a plane holds some 4k / pi photons; a cell
    // with fewer than k / 2 takes its 26 neighbours' too, over nine cells' area): a density a
    // few hash lookups away rather than a k-nearest search, for radii wanted every epoch; a
    // surface's area in a cell is taken as the cell's face (exact for surfaces along the
    // axes; corners and slopes choose radii within a factor of about 1.7). Thread-safe.
    std::vector<float> CellRadii(std::span<const HitPoint> hit_points,
                                 std::span<const float> footprint, float fallback) const;

private:
    // Whether `point` gathers the photons of map `map` (0 global, 1 caustic).
    bool Gathers(const HitPoint& point, int map) const;
    // The radius for hit point `point` of footprint `footprint`, from its density (photons per
    // unit area and emitted photon, of the maps it gathers: `density`).
    float RadiusFor(const HitPoint& point, float footprint, double density) const;
    // Photons per unit area and emitted photon of map `map` (0 global, 1 caustic) about p, by
    // the grid's cells.
    double CellDensity(const Vec3& p, int map) const;

    DensityRadiiSettings settings_;
    bool everything_;
    float diagonal_limit_;
    PhotonMaps maps_;
    double emitted_[2] = {0, 0};  // the maps' photons emitted
    float cell_size_ = 0;
    std::unordered_map<uint64_t, std::array<uint32_t, 2>> cells_;  // photons per map a cell
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
