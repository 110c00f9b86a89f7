// The coordinator's camera passes, each traced while the epoch before it runs, are the passes
// traced on demand, whatever order the epochs are asked for in.
#include "server/camera_passes.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "core/scene_io/scene_loader.h"
#include "embree/embree_tracer.h"

namespace pf {
namespace {

void ExpectSamePass(const CameraPassResult& a, const CameraPassResult& b, uint64_t epoch) {
    ASSERT_EQ(a.hit_points.size(), b.hit_points.size()) << "epoch " << epoch;
    for (size_t i = 0; i < a.hit_points.size(); ++i) {
        const HitPoint &p = a.hit_points[i], &q = b.hit_points[i];
        ASSERT_TRUE(p.position == q.position && p.normal == q.normal && p.weight == q.weight &&
                    p.pixel == q.pixel && p.coat == q.coat && p.gathers == q.gathers)
            << "epoch " << epoch << ", hit point " << i;
    }
    EXPECT_EQ(a.footprint, b.footprint) << "epoch " << epoch;
    EXPECT_EQ(a.emission.pixels, b.emission.pixels) << "epoch " << epoch;
}

TEST(CameraPassesTest, PassesTracedAheadAreThePassesTracedOnDemand) {
    for (const Integrator integrator : {Integrator::kSppm, Integrator::kRpm}) {
        absl::StatusOr<Scene> scene =
            LoadScene(std::string(PF_SOURCE_DIR) + "/scenes/cornell-glass.gltf");
        ASSERT_TRUE(scene.ok()) << scene.status();
        JobSpec spec;
        spec.integrator = integrator;
        spec.width = spec.height = 32;
        spec.samples_per_pixel = 2;
        spec.seed = 3;
        spec.photon_budget = 1;
        auto payload = std::make_shared<const JobPayload>(std::move(*scene), nullptr, spec);
        const CameraPassSettings film = *FilmFor(spec, payload->scene);
        absl::StatusOr<EpochCameraPass> ahead = EpochCameraPasses(payload, film);
        ASSERT_TRUE(ahead.ok()) << ahead.status();
        std::shared_ptr<const Tracer> tracer = *embree::EmbreeTracer::Create(payload->scene);
        const EpochCameraPass on_demand =
            TracedCameraPasses(payload->scene, payload->emitters, tracer, film, payload->spec);
        // In order (each traced ahead), then a skip, a step back and a repeat (traced then).
        for (const uint64_t epoch : {0, 1, 2, 5, 3, 4, 4})
            ExpectSamePass((*ahead)(epoch), on_demand(epoch), epoch);
        // Epochs take samples of their own.
        EXPECT_NE(on_demand(1).emission.pixels, on_demand(2).emission.pixels);
        // Destroyed with epoch 5's pass in flight: it is cut short, and nothing hangs.
    }
}

}  // namespace
}  // namespace pf
