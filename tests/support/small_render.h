// One small local render for tests that compare images statistically: 32x32, 1M photons (unless
// given) in batches of 2^16, two threads, alpha fixed at 2/3.
#pragma once

#include <cstdint>
#include <string>

#include "core/film/image.h"
#include "core/job/integrator.h"

namespace pf::testing {

// Renders `scene_path` on `backend` with photon stream `stream` (and R0 `initial_radius` for
// every hit point, if not 0); a failed render adds a test failure and gives an empty image.
// Uniform photon tracing unless asked: the comparisons these renders feed (image_agreement.h)
// require the same spread of every render, and the two backends' adaptive chains differ in
// length, and so in spread, where few photons count (auto would choose them on open scenes).
Image RenderSmall(const std::string& scene_path, const std::string& backend, uint64_t stream,
                  uint64_t photons = 1'000'000, double initial_radius = 0,
                  PhotonTracing tracing = PhotonTracing::kUniform);

}  // namespace pf::testing
