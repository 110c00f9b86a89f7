// Initial radii from a pilot photon map's density.
#include "core/pm/density_radii.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/pm/photon_map.h"
#include "core/util/check.h"

namespace pf {

namespace {

// A grid cell's key: its integer coordinates, 21 bits each (wrapping: distant cells that
// share a key only add photons, a radius chosen a little small).
uint64_t CellKey(int64_t x, int64_t y, int64_t z) {
    constexpr uint64_t kMask = (uint64_t{1} << 21) - 1;
    return (uint64_t(x) & kMask) | (uint64_t(y) & kMask) << 21 | (uint64_t(z) & kMask) << 42;
}

}  // namespace

DensityRadii::DensityRadii(const Scene& scene, const Emitters& emitters, const Tracer& tracer,
                           const SceneFeatures& features, bool everything,
                           const DensityRadiiSettings& settings, bool cells)
    : settings_(settings),
      everything_(everything),
      diagonal_limit_(static_cast<float>(settings.most_diagonal * scene.bounds.Diagonal())) {
    PF_CHECK(settings.first_epoch_photons > 0 && settings.nearest > 0);
    PhotonMapSettings pilot;
    pilot.global_photons = pilot.caustic_photons = settings.pilot_photons;
    pilot.index = PhotonIndex::kKdTree;
    pilot.final_gather = everything ? 1 : 0;
    maps_ = BuildPhotonMaps(scene, emitters, tracer, features, pilot, settings.seed,
                            settings.max_depth);
    emitted_[0] = double(maps_.global_emitted);
    emitted_[1] = double(maps_.caustic_emitted);
    if (!cells) return;
    // The cells: twice the median reach of the k nearest about a sample of the photons.
    const PhotonLookup& sampled = maps_.global->Photons().empty() ? *maps_.caustic : *maps_.global;
    const std::span<const StoredPhoton> photons = sampled.Photons();
    if (photons.empty()) return;
    std::vector<float> reach;
    NearestPhotons nearest;
    const size_t step = std::max<size_t>(1, photons.size() / 1024);
    for (size_t i = 0; i < photons.size(); i += step) {
        sampled.Nearest(photons[i].position, settings.nearest, diagonal_limit_ * diagonal_limit_,
                        nearest);
        reach.push_back(std::sqrt(nearest.RadiusSq()));
    }
    std::nth_element(reach.begin(), reach.begin() + std::ptrdiff_t(reach.size() / 2), reach.end());
    cell_size_ = 2 * reach[reach.size() / 2];
    if (!(cell_size_ > 0)) return;
    for (int map = 0; map < 2; ++map)
        for (const StoredPhoton& photon : (map == 0 ? *maps_.global : *maps_.caustic).Photons()) {
            const Vec3 c = photon.position / cell_size_;
            ++cells_[CellKey(int64_t(std::floor(c.x)), int64_t(std::floor(c.y)),
                             int64_t(std::floor(c.z)))][map];
        }
}

double DensityRadii::CellDensity(const Vec3& p, int map) const {
    if (!(cell_size_ > 0) || !(emitted_[map] > 0)) return 0;
    const Vec3 c = p / cell_size_;
    const int64_t x = int64_t(std::floor(c.x)), y = int64_t(std::floor(c.y)),
                  z = int64_t(std::floor(c.z));
    const auto count = [&](int64_t i, int64_t j, int64_t k) -> double {
        const auto it = cells_.find(CellKey(i, j, k));
        return it == cells_.end() ? 0.0 : double(it->second[map]);
    };
    const double area = double(cell_size_) * cell_size_;
    const double own = count(x, y, z);
    if (own >= 0.5 * settings_.nearest) return own / (area * emitted_[map]);
    double around = 0;
    for (int64_t i = x - 1; i <= x + 1; ++i)
        for (int64_t j = y - 1; j <= y + 1; ++j)
            for (int64_t k = z - 1; k <= z + 1; ++k) around += count(i, j, k);
    return around / (9 * area * emitted_[map]);
}

float DensityRadii::RadiusFor(const HitPoint& point, float footprint, double density) const {
    const float most =
        std::min(static_cast<float>(settings_.most_footprints) * footprint, diagonal_limit_);
    const float least = std::min(static_cast<float>(settings_.least_footprints) * footprint, most);
    // Caustics alone, with none about: no radius (the hit point takes no part) rather than the
    // widest, which would widen the gather grid's cells for all.
    if (point.gathers == kCausticPhoton && !(density > 0)) return 0;
    const double found_per_density =
        settings_.first_epoch_photons_found /
        (std::numbers::pi * static_cast<double>(settings_.first_epoch_photons));
    const double radius = density > 0 ? std::sqrt(found_per_density / density) : double(most);
    return std::clamp(static_cast<float>(radius), least, most);
}

std::vector<float> DensityRadii::Radii(std::span<const HitPoint> hit_points,
                                       std::span<const float> footprint, float fallback) const {
    PF_CHECK(hit_points.size() == footprint.size());
    const PhotonLookup* lookups[] = {maps_.global.get(), maps_.caustic.get()};
    std::vector<float> radii(hit_points.size(), fallback);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, hit_points.size(), 1024),
                      [&](const tbb::blocked_range<size_t>& range) {
                          NearestPhotons nearest;
                          for (size_t i = range.begin(); i < range.end(); ++i) {
                              if (!(footprint[i] > 0)) continue;
                              // Photons per unit area and photon emitted: each map's k nearest
                              // (or those within the scene's bound) over their disc, of the maps
                              // whose photons the hit point gathers.
                              double density = 0;
                              for (int map = 0; map < 2; ++map) {
                                  if (!Gathers(hit_points[i], map) || emitted_[map] == 0 ||
                                      lookups[map]->Photons().empty())
                                      continue;
                                  lookups[map]->Nearest(hit_points[i].position, settings_.nearest,
                                                        diagonal_limit_ * diagonal_limit_, nearest);
                                  const double radius_sq = nearest.RadiusSq();
                                  if (radius_sq > 0)
                                      density += static_cast<double>(nearest.entries.size()) /
                                                 (std::numbers::pi * radius_sq * emitted_[map]);
                              }
                              radii[i] = RadiusFor(hit_points[i], footprint[i], density);
                          }
                      });
    return radii;
}

std::vector<float> DensityRadii::CellRadii(std::span<const HitPoint> hit_points,
                                           std::span<const float> footprint, float fallback) const {
    PF_CHECK(hit_points.size() == footprint.size());
    std::vector<float> radii(hit_points.size(), fallback);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, hit_points.size(), 4096),
                      [&](const tbb::blocked_range<size_t>& range) {
                          for (size_t i = range.begin(); i < range.end(); ++i) {
                              if (!(footprint[i] > 0)) continue;
                              double density = 0;
                              for (int map = 0; map < 2; ++map)
                                  if (Gathers(hit_points[i], map))
                                      density += CellDensity(hit_points[i].position, map);
                              radii[i] = RadiusFor(hit_points[i], footprint[i], density);
                          }
                      });
    return radii;
}

bool DensityRadii::Gathers(const HitPoint& point, int map) const {
    const bool caustics_alone = point.gathers == kCausticPhoton;
    return map == 1 ? caustics_alone || !everything_ : !caustics_alone;
}

DensityRadiiSettings ReverseRadiiSettings(const JobSpec& spec, const Scene& scene) {
    const PhotonMapSettings& maps = spec.photon_map;
    DensityRadiiSettings density;
    density.seed = spec.seed;
    density.first_epoch_photons = std::max<uint64_t>(maps.global_photons, 1);
    density.first_epoch_photons_found = maps.nearest;
    density.least_footprints = 0;
    density.most_footprints = std::numeric_limits<double>::infinity();
    density.most_diagonal = MaxSearchRadius(maps, scene) / scene.bounds.Diagonal();
    return density;
}

std::vector<float> DensityInitialRadii(const Scene& scene, const Emitters& emitters,
                                       const Tracer& tracer, const SceneFeatures& features,
                                       std::span<const HitPoint> hit_points,
                                       std::span<const float> footprint, float fallback,
                                       const DensityRadiiSettings& settings) {
    // Where some hit point gathers direct light (rpm's gather hits), the global map holds
    // every landing, as a global map for final gathering does; it then stands for all.
    const bool everything =
        std::any_of(hit_points.begin(), hit_points.end(),
                    [](const HitPoint& h) { return h.gathers & kDirectPhoton; });
    return DensityRadii(scene, emitters, tracer, features, everything, settings)
        .Radii(hit_points, footprint, fallback);
}

}  // namespace pf
