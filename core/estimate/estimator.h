// The progressive photon mapping estimate of one hit point, as pure functions
// (Hachisuka, Ogaki & Jensen 2008, "Progressive Photon Mapping", section 4.2).
// Counts and flux sums are double so they stay exact well beyond 2^32 photons.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/math/vec3.h"
#include "core/util/check.h"

namespace pf {

struct PointEstimate {
    double photon_count = 0;  // N: accumulated (alpha-weighted) photon count
    double radius_sq = 0;     // R^2: squared search radius, world units^2
    Rgbd flux;                // tau: accumulated flux times the hit point's weight, W
};

// Folds one pass into the estimate: M photons found within R carrying flux Phi_M (already
// multiplied by the hit point's BSDF weight). Eq. 7-10 of Hachisuka et al. 2008:
//   N' = N + alpha M,  R'^2 = R^2 (N + alpha M) / (N + M),  tau' = (tau + Phi_M) R'^2 / R^2.
// M = 0 leaves the estimate unchanged; alpha in (0, 1].
// The area's shrink R'^2 / R^2 = (N + alpha M) / (N + M), in [alpha, 1]; 1 when M = 0.
// `min_radius_sq` is the floor: R^2 shrinks no further (the ratio becomes 1 at the floor), so
// a hit point that keeps finding photons whatever its radius (all of a caustic's focus) cannot
// shrink into denormals and lose tau's precision; from there on its estimate is a density
// estimate of fixed radius. EstimateFor sets the floor far below anything a float position
// resolves (docs/numerics.md).
inline double ShrinkRatio(const PointEstimate& estimate, double new_photons, double alpha,
                          double min_radius_sq = 0) {
    PF_DCHECK(alpha > 0 && alpha <= 1 && new_photons >= 0);
    if (new_photons <= 0) return 1.0;
    const double ratio =
        (estimate.photon_count + alpha * new_photons) / (estimate.photon_count + new_photons);
    if (estimate.radius_sq * ratio >= min_radius_sq) return ratio;
    return estimate.radius_sq > min_radius_sq ? min_radius_sq / estimate.radius_sq : 1.0;
}

inline PointEstimate UpdateEstimate(const PointEstimate& estimate, double new_photons,
                                    const Rgbd& new_flux, double alpha, double min_radius_sq = 0) {
    if (new_photons <= 0) return estimate;
    const double ratio = ShrinkRatio(estimate, new_photons, alpha, min_radius_sq);
    return {estimate.photon_count + alpha * new_photons, estimate.radius_sq * ratio,
            (estimate.flux + new_flux) * ratio};
}

// Reflected radiance estimate tau / (pi R^2 N_emitted), with N_emitted counting every emitted
// photon path, including those that left the scene. Zero before any photon was emitted or
// when the radius has collapsed to nothing.
inline Rgbd EstimateRadiance(const PointEstimate& estimate, double photons_emitted) {
    const double denominator = kPiD * estimate.radius_sq * photons_emitted;
    if (!(denominator > 0) || !std::isfinite(denominator)) return Rgbd(0.0);
    return estimate.flux / denominator;
}

}  // namespace pf
