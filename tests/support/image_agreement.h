// Whether an image is another independent draw of the estimator two reference images come
// from (the statistical bound derived in image_agreement.cpp). For comparing backends and
// farms whose random streams differ.
#pragma once

#include "core/film/image.h"

namespace pf::testing {

// The mean over pixels of the squared difference of the pixels' channel averages.
double MeanSquaredDifference(const Image& a, const Image& b);

// Adds a test failure, with the numbers, unless `image` agrees with `a` and `b` (two
// renders of the same seed and budget with independent photon streams) within their noise.
void ExpectSameEstimator(const Image& image, const Image& a, const Image& b);

}  // namespace pf::testing
