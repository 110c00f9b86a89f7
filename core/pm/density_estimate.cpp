// Filtered k-nearest density estimation.
#include "core/pm/density_estimate.h"

#include <cmath>

namespace pf {

float FilterWeight(DensityFilter filter, float distance_sq, float radius_sq) {
    switch (filter) {
        case DensityFilter::kBox:
            return 1.0f;
        case DensityFilter::kCone:
            return 1.0f - std::sqrt(distance_sq / radius_sq) / kConeFilterK;
        case DensityFilter::kGaussian: {
            const float s2 = distance_sq / radius_sq;
            return 1.0f - (1.0f - std::exp(-0.5f * kGaussianBeta * s2)) /
                              (1.0f - std::exp(-kGaussianBeta));
        }
    }
    return 1.0f;
}

float FilterNormalisation(DensityFilter filter) {
    switch (filter) {
        case DensityFilter::kBox:
            return 1.0f;
        // integral over the unit disc of (1 - s / k) 2 s ds = 1 - 2 / (3 k)
        case DensityFilter::kCone:
            return 1.0f - 2.0f / (3.0f * kConeFilterK);
        // integral of (1 - (1 - e^(-beta s^2 / 2)) / (1 - e^-beta)) 2 s ds
        case DensityFilter::kGaussian: {
            const float b = kGaussianBeta;
            return 1.0f -
                   (1.0f - (2.0f / b) * (1.0f - std::exp(-0.5f * b))) / (1.0f - std::exp(-b));
        }
    }
    return 1.0f;
}

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
