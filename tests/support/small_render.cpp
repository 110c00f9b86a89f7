// The small render the statistical image comparisons share.
#include "tests/support/small_render.h"

#include <gtest/gtest.h>

#include "core/job/job_spec.h"
#include "embedded/local_render.h"

namespace pf::testing {

Image RenderSmall(const std::string& scene_path, const std::string& backend, uint64_t stream,
                  uint64_t photons, double initial_radius, PhotonTracing tracing) {
    RenderSettings settings;
    settings.scene_path = scene_path;
    settings.backend = backend;
    settings.threads = 2;
    settings.job.width = 32;
    settings.job.height = 32;
    settings.job.photon_budget = photons;
    settings.job.layout = {1u << 16, 4};
    settings.job.photon_stream = stream;
    settings.job.initial_radius = initial_radius;
    settings.job.photon_tracing = tracing;
    // A fixed alpha: balanced, each render's radii would follow its own photons' noise, and
    // these renders compare the photons' estimator, not the radius schedule.
    settings.job.alpha = kDefaultAlpha;
    absl::StatusOr<RenderOutcome> outcome = RenderLocally(settings);
    EXPECT_TRUE(outcome.ok()) << outcome.status();
    return outcome.ok() ? outcome->image : Image();
}

}  // namespace pf::testing
