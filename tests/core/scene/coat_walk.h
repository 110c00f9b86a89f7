// What the coat tests share: a walk through a coated diffuse surface as photons take it, and
// the small numerical helpers around it.
#pragma once

#include <cmath>
#include <utility>

#include "core/sampling/frame.h"
#include "core/sampling/rng.h"
#include "core/sampling/sampling.h"
#include "core/scene/scattering.h"

namespace pf {

// Light arriving at the coated diffuse surface (normal +z) along d, followed as a photon is
// (core/ppm/photon_walk.h) until it leaves: sets `out` and returns the flux it carries out
// (0 where absorbed).
inline float Walk(const Material& material, const Vec3& d, Rng& rng, Vec3& out) {
    const Vec3 n(0, 0, 1);
    const CoatArrival arrival = ArriveAtCoat(BsdfOf(material), d, n, true, rng.State());
    if (!arrival.at_base) {
        out = arrival.reflected.direction;
        return Average(arrival.reflected.weight);
    }
    float flux = arrival.weight;
    const Frame frame = FrameFromNormal(n);
    for (uint32_t visit = 0; visit < material.coat_depth; ++visit) {
        flux *= material.base_color.x;  // albedo as a weight: no roulette, less noise
        const CoatLeaving leaving =
            LeaveCoatAt(CoatOf(material), frame,
                        SampleCosineHemisphere(rng.NextFloat(), rng.NextFloat()), rng.State());
        flux *= leaving.weight;
        if (leaving.escaped) {
            out = leaving.direction;
            return flux;
        }
    }
    return 0;
}

// The flux a walk arriving from `from` carries out into a small cone about `to`, over cos(to),
// with its standard error: an estimate of f(from, to), for reciprocity checks.
inline std::pair<double, double> IntoCone(const Material& material, const Vec3& from,
                                          const Vec3& to) {
    constexpr int kSamples = 2000000;
    constexpr float kCone = 0.985f;  // cos of the cone's half angle
    Rng rng(17);
    double sum = 0, sum_sq = 0;
    Vec3 out;
    for (int i = 0; i < kSamples; ++i) {
        const float w = Walk(material, -from, rng, out);
        if (Dot(out, to) >= kCone) sum += w, sum_sq += double(w) * w;
    }
    const double mean = sum / kSamples;
    return {mean / to.z, std::sqrt((sum_sq / kSamples - mean * mean) / kSamples) / to.z};
}

inline Vec3 Incident(float cos_theta) {  // arriving at the surface, in the xz plane
    return {std::sqrt(1 - cos_theta * cos_theta), 0, -cos_theta};
}

// Integral over [0, 1] of f(mu) by the midpoint rule.
template <typename F>
double Integrate(F&& f) {
    constexpr int kSteps = 20000;
    double sum = 0;
    for (int i = 0; i < kSteps; ++i) sum += f((i + 0.5) / kSteps);
    return sum / kSteps;
}

}  // namespace pf
