// Filtered k-nearest density estimation.
#include "core/pm/density_estimate.h"

#include <cmath>

namespace pf {

Rgb EstimateDiffuseRadiance(const PhotonLookup& lookup, const Vec3& p, const Vec3& n,
                            const Rgb& albedo, uint32_t k, float max_radius_sq,
                            DensityFilter filter, bool per_cosine, NearestPhotons& scratch) {
    lookup.Nearest(p, k, max_radius_sq, scratch);
    const float radius_sq = scratch.RadiusSq();
    if (scratch.entries.empty() || !(radius_sq > 0)) return Rgb(0.0f);
    const std::span<const StoredPhoton> photons = lookup.Photons();
    Rgbd flux(0.0);
    for (const NearestPhotons::Entry& entry : scratch.entries) {
        const StoredPhoton& photon = photons[entry.photon];
        const float facing = -Dot(photon.direction, n);
        if (!(facing > 0)) continue;  // from behind the surface
        const double weight = FilterWeight(filter, entry.distance_sq, radius_sq);
        flux += Rgbd(photon.power) * (per_cosine ? weight * facing : weight);
    }
    const double area = kPiD * double(radius_sq) * double(FilterNormalisation(filter));
    return albedo * Rgb(flux / (kPiD * area));
}

}  // namespace pf
