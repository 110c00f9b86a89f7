// Where a pixel's camera samples go, the same for every integrator: sample s of a pixel's k
// falls in cell s of k cells of equal area that tile the pixel, jittered, and through a random
// point of the lens where the camera has one.
#pragma once

#include <cmath>

#include "core/geometry/ray.h"
#include "core/math/point2.h"
#include "core/sampling/rng.h"
#include "core/sampling/sampling.h"
#include "core/scene/camera.h"

namespace pf {

struct Film {
    int width = 0, height = 0;
    int samples_per_pixel = 1;
    float Aspect() const { return static_cast<float>(width) / static_cast<float>(height); }
    uint64_t Pixels() const { return uint64_t(width) * uint64_t(height); }
};

// Where in its pixel ([0, 1)^2) sample s of k falls, for jitter (jitter_x, jitter_y) in [0,
// 1)^2: the pixel is cut into floor(sqrt(k)) rows, the first k mod rows of them holding one
// cell more than the others, each row as tall as its share of the k cells, so that every cell
// has area 1/k and together they cover the pixel, whatever k (a perfect square k gives the
// square grid).
inline Point2 PixelSampleOffset(int k, int s, float jitter_x, float jitter_y) {
    const int rows = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(k))));
    const int narrow = k / rows, wide_rows = k % rows, in_wide = wide_rows * (narrow + 1);
    int row, column, cells, cells_above;  // cells_above: in the rows above this one
    if (s < in_wide) {
        row = s / (narrow + 1), column = s % (narrow + 1), cells = narrow + 1;
        cells_above = row * (narrow + 1);
    } else {
        row = wide_rows + (s - in_wide) / narrow, column = (s - in_wide) % narrow, cells = narrow;
        cells_above = in_wide + (row - wide_rows) * narrow;
    }
    // The row's top over its height, plus the jitter, over the rows of that height the pixel
    // holds: (row + jitter_y) / rows exactly, in floats too, where k is a square.
    return {(static_cast<float>(column) + jitter_x) / static_cast<float>(cells),
            (static_cast<float>(cells_above) / static_cast<float>(cells) + jitter_y) /
                (static_cast<float>(k) / static_cast<float>(cells))};
}

// The camera ray of sample s of pixel (x, y): two numbers from rng for the jitter, and two
// more only where the camera has a lens.
inline Ray PixelSampleRay(const Camera& camera, const Film& film, int x, int y, int s, Rng& rng) {
    const float jitter_x = rng.NextFloat();
    const float jitter_y = rng.NextFloat();
    const Point2 offset = PixelSampleOffset(film.samples_per_pixel, s, jitter_x, jitter_y);
    const float fx = (static_cast<float>(x) + offset.x) / static_cast<float>(film.width);
    const float fy = (static_cast<float>(y) + offset.y) / static_cast<float>(film.height);
    if (!camera.HasLens()) return camera.GenerateRay(fx, fy, film.Aspect());
    const float u1 = rng.NextFloat();
    const float u2 = rng.NextFloat();
    return camera.GenerateRay(fx, fy, film.Aspect(), SampleUniformDisk(u1, u2));
}

}  // namespace pf
