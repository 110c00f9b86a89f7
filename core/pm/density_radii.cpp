// Initial radii from a pilot photon map's density.
#include "core/pm/density_radii.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/pm/photon_map.h"
#include "core/util/check.h"

namespace pf {

std::vector<float> DensityInitialRadii(const Scene& scene, const Emitters& emitters,
                                       const Tracer& tracer, const SceneFeatures& features,
                                       std::span<const HitPoint> hit_points,
                                       std::span<const float> footprint, float fallback,
                                       const DensityRadiiSettings& settings) {
    PF_CHECK(hit_points.size() == footprint.size() && settings.first_epoch_photons > 0 &&
             settings.nearest > 0);
    PhotonMapSettings pilot;
    pilot.global_photons = pilot.caustic_photons = settings.pilot_photons;
    pilot.index = PhotonIndex::kKdTree;
    // Where some hit point gathers direct light (rpm's gather hits), the global map holds
    // every landing, as a global map for final gathering does; it then stands for all.
    const bool everything =
        std::any_of(hit_points.begin(), hit_points.end(),
                    [](const HitPoint& h) { return h.gathers & kDirectPhoton; });
    pilot.final_gather = everything ? 1 : 0;
    const PhotonMaps maps = BuildPhotonMaps(scene, emitters, tracer, features, pilot, settings.seed,
                                            settings.max_depth);
    const struct {
        const PhotonLookup* lookup;
        double emitted;
    } sources[] = {{maps.global.get(), double(maps.global_emitted)},
                   {maps.caustic.get(), double(maps.caustic_emitted)}};
    const float diagonal_limit =
        static_cast<float>(settings.most_diagonal * scene.bounds.Diagonal());
    const double found_per_density =
        settings.first_epoch_photons_found /
        (std::numbers::pi * static_cast<double>(settings.first_epoch_photons));
    std::vector<float> radii(hit_points.size(), fallback);
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, hit_points.size(), 1024),
        [&](const tbb::blocked_range<size_t>& range) {
            NearestPhotons nearest;
            for (size_t i = range.begin(); i < range.end(); ++i) {
                if (!(footprint[i] > 0)) continue;
                const float most = std::min(
                    static_cast<float>(settings.most_footprints) * footprint[i], diagonal_limit);
                const float least =
                    std::min(static_cast<float>(settings.least_footprints) * footprint[i], most);
                // Photons per unit area and photon emitted: each map's k nearest (or those
                // within the scene's bound) over their disc, of the maps whose photons the hit
                // point gathers.
                const uint32_t gathers = hit_points[i].gathers;
                const bool caustics_alone = gathers == kCausticPhoton;
                double density = 0;
                for (const auto& source : sources) {
                    const bool caustic = &source == &sources[1];
                    if (caustic ? everything && !caustics_alone : caustics_alone) continue;
                    if (source.emitted == 0 || source.lookup->Photons().empty()) continue;
                    source.lookup->Nearest(hit_points[i].position, settings.nearest,
                                           diagonal_limit * diagonal_limit, nearest);
                    const double radius_sq = nearest.RadiusSq();
                    if (radius_sq > 0)
                        density += static_cast<double>(nearest.entries.size()) /
                                   (std::numbers::pi * radius_sq * source.emitted);
                }
                // Caustics alone, with none about: no radius (the hit point takes no part)
                // rather than the widest, which would widen the gather grid's cells for all.
                if (caustics_alone && !(density > 0)) {
                    radii[i] = 0;
                    continue;
                }
                const double radius =
                    density > 0 ? std::sqrt(found_per_density / density) : double(most);
                radii[i] = std::clamp(static_cast<float>(radius), least, most);
            }
        });
    return radii;
}

}  // namespace pf
