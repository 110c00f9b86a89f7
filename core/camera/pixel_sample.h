// Where a pixel's camera samples go, the same for every integrator: sample s of a pixel falls
// in cell s of a strata x strata grid over the pixel, jittered, and through a random point of
// the lens where the camera has one.
#pragma once

#include <cmath>

#include "core/geometry/ray.h"
#include "core/sampling/rng.h"
#include "core/sampling/sampling.h"
#include "core/scene/camera.h"

namespace pf {

struct Film {
    int width = 0, height = 0;
    int samples_per_pixel = 1;
    int Strata() const {
        return static_cast<int>(std::ceil(std::sqrt(static_cast<double>(samples_per_pixel))));
    }
    float Aspect() const { return static_cast<float>(width) / static_cast<float>(height); }
    uint64_t Pixels() const { return uint64_t(width) * uint64_t(height); }
};

// The camera ray of sample s of pixel (x, y): two numbers from rng for the jitter, and two
// more only where the camera has a lens.
inline Ray PixelSampleRay(const Camera& camera, const Film& film, int x, int y, int s, Rng& rng) {
    const int strata = film.Strata();
    const float jitter_x = rng.NextFloat();
    const float jitter_y = rng.NextFloat();
    const float fx = (x + ((s % strata) + jitter_x) / strata) / film.width;
    const float fy = (y + ((s / strata) + jitter_y) / strata) / film.height;
    if (!camera.HasLens()) return camera.GenerateRay(fx, fy, film.Aspect());
    const float u1 = rng.NextFloat();
    const float u2 = rng.NextFloat();
    return camera.GenerateRay(fx, fy, film.Aspect(), SampleUniformDisk(u1, u2));
}

}  // namespace pf
