// Radiance from the photons nearest a point (Jensen 1996, eq. 7; the filters of Jensen 2001,
// section 7.1): L = rho / pi * sum_p w_p Phi_p / (c pi r^2), with r the distance to the k-th
// photon and c the filter's normalisation, so that a uniform photon density is estimated
// without bias whatever the filter. Photons arriving from behind the surface are left out.
#pragma once

#include "core/job/integrator.h"
#include "core/math/vec3.h"
#include "core/pm/photon_map.h"
#include "core/shared/density_filter.h"

namespace pf {

using gpu::kConeFilterK;
using gpu::kGaussianBeta;
static_assert(uint32_t(DensityFilter::kBox) == gpu::kFilterBox &&
              uint32_t(DensityFilter::kCone) == gpu::kFilterCone &&
              uint32_t(DensityFilter::kGaussian) == gpu::kFilterGaussian);

// The weight of a photon at squared distance distance_sq from the point, in a disc of
// squared radius radius_sq, and the filter's normalisation (core/shared/density_filter.h).
inline float FilterWeight(DensityFilter filter, float distance_sq, float radius_sq) {
    return gpu::DensityFilterWeight(static_cast<uint32_t>(filter), distance_sq, radius_sq);
}
inline float FilterNormalisation(DensityFilter filter) {
    return gpu::DensityFilterNormalisation(static_cast<uint32_t>(filter));
}

// Reflected radiance at point p of a diffuse surface with unit (shading) normal n (on the side
// light is gathered from) and albedo rho, from `lookup`'s k nearest photons within
// max_radius_sq. `per_cosine`: the photons' power is per unit of their cosine at the surface
// (a scene with shading normals, ScatterPhotonAt), each weighed by its cosine to n here.
// `scratch` is the caller's, one per thread.
Rgb EstimateDiffuseRadiance(const PhotonLookup& lookup, const Vec3& p, const Vec3& n,
                            const Rgb& albedo, uint32_t k, float max_radius_sq,
                            DensityFilter filter, bool per_cosine, NearestPhotons& scratch);

}  // namespace pf
