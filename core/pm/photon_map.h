// Classic photon mapping's maps (Jensen 1996): photons traced once from the lights and stored
// where they land on diffuse surfaces, searched for the k nearest to a point through a
// balanced kd-tree or a uniform grid (PhotonLookup). Unlike the progressive photon mappers,
// memory grows with every photon stored.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/geometry/tracer.h"
#include "core/job/integrator.h"
#include "core/math/vec3.h"
#include "core/scene/emitters.h"
#include "core/scene/scene.h"
#include "core/scene/scene_features.h"

namespace pf {

// A photon where it landed: W, already divided by the photons emitted for its map.
struct StoredPhoton {
    Vec3 position;
    Vec3 direction;  // of travel, unit
    Rgb power;
};

// The k nearest photons to a point, nearest last (a max-heap on distance until Finish).
struct NearestPhotons {
    struct Entry {
        float distance_sq;
        uint32_t photon;
        bool operator<(const Entry& other) const { return distance_sq < other.distance_sq; }
    };
    std::vector<Entry> entries;
    uint32_t k = 0;
    float max_distance_sq = 0;  // of the search: shrinks to the k-th distance once k are found

    void Reset(uint32_t k_in, float max_distance_sq_in) {
        entries.clear();
        k = k_in;
        max_distance_sq = max_distance_sq_in;
    }
    // Offers a photon within max_distance_sq.
    void Offer(float distance_sq, uint32_t photon);
    // The squared distance the estimate's disc reaches: the k-th photon's when k were found,
    // the search's limit otherwise.
    float RadiusSq() const { return max_distance_sq; }
};

// A search structure over one map's photons, which it holds in its own order.
class PhotonLookup {
public:
    virtual ~PhotonLookup() = default;
    std::span<const StoredPhoton> Photons() const { return photons_; }
    // The (up to) k photons nearest to p within sqrt(max_distance_sq) into `out`. Thread-safe.
    virtual void Nearest(const Vec3& p, uint32_t k, float max_distance_sq,
                         NearestPhotons& out) const = 0;
    // Bytes held, photons included.
    virtual uint64_t Bytes() const = 0;

protected:
    std::vector<StoredPhoton> photons_;
};

// Builds the lookup of `index` over the photons (consumed); `cell_size` is the grid's
// (GridCellSize). Runs on the calling TBB arena.
std::unique_ptr<PhotonLookup> BuildPhotonLookup(PhotonIndex index,
                                                std::vector<StoredPhoton> photons, float cell_size);

// The k-nearest search's limit: the settings' max_radius, or 2% of the scene's diagonal.
float MaxSearchRadius(const PhotonMapSettings& settings, const Scene& scene);
// The area of the scene's surfaces, instances included (by their linear maps' scale), world
// units^2: for the grid's cell size.
double SceneSurfaceArea(const Scene& scene);

// The two maps of a job: the global map (indirect light; with final gathering, every photon
// that reached a diffuse surface, for the gather rays' estimates) and the caustic map (photons
// that reached a diffuse surface through specular or rough bounces alone).
struct PhotonMaps {
    std::unique_ptr<PhotonLookup> global, caustic;  // either may hold no photons
    uint64_t global_emitted = 0, caustic_emitted = 0;
    uint64_t Bytes() const { return global->Bytes() + caustic->Bytes(); }
};

// What building the maps would store, from a pilot of a few thousand photons per map traced
// with the job's seed: photons stored per photon emitted, and so the bytes in all.
struct PhotonMapForecast {
    double global_stored_per_emitted = 0, caustic_stored_per_emitted = 0;
    uint64_t bytes = 0;
};
PhotonMapForecast ForecastPhotonMaps(const Scene& scene, const Emitters& emitters,
                                     const Tracer& tracer, const SceneFeatures& features,
                                     const PhotonMapSettings& settings, uint64_t seed,
                                     int max_depth = 0);

// Memory this process may use: the physical memory available, or the cgroup's limit where
// it is lower (a container), bytes.
uint64_t AvailableMemoryBytes();
// RESOURCE_EXHAUSTED naming the flags when the forecast does not fit in `available` bytes
// (with room left for the rest of the render).
absl::Status CheckPhotonMapsFit(const PhotonMapForecast& forecast,
                                const PhotonMapSettings& settings, uint64_t available);

// Traces and stores the maps (photon p of the global map draws from a stream of (seed, p)
// alone, so every worker builds the same maps), in parallel on the calling TBB arena.
// Without specular or rough materials there are no caustics and no caustic photons are traced.
// Photons reach at most `max_depth` surfaces (JobSpec::max_depth; 0: no limit).
PhotonMaps BuildPhotonMaps(const Scene& scene, const Emitters& emitters, const Tracer& tracer,
                           const SceneFeatures& features, const PhotonMapSettings& settings,
                           uint64_t seed, int max_depth = 0);

}  // namespace pf
