// Error against run time on every shipped scene: each is rendered in small epochs from 2^14 to
// 1.6M photons (two decades) and measured every epoch against a long reference, the same
// job's hit points with independent photons (another photon stream) and 20x the photons in
// small epochs (small radii), or for the furnaces the exact answer L = Le / (1 - rho) = 2.
// Checked: the estimated error (variance from the half-estimates plus the bias from the inner
// discs) stays within a factor of 2 of the measured one from epoch 8 on; the measured error
// falls; no pixel is ever NaN or Inf; and on cornell-box the fitted log-log slope of the
// measured RMSE against photons is at or below -0.25 (PPM with alpha = 2/3: -1/3 in the limit).
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "embedded/local_render.h"

namespace pf {
namespace {

constexpr int kSize = 32;
constexpr uint32_t kEpochPhotons = 1u << 12;
constexpr uint64_t kPhotons = 400 * kEpochPhotons;         // 1.6M: two decades past epoch 4
constexpr uint64_t kReferencePhotons = uint64_t{1} << 25;  // 20x
constexpr uint64_t kFirstCheckedEpoch = 8;

struct SceneCase {
    const char* file;
    bool analytic;  // the furnace: every pixel is exactly 2
    bool check_slope;
    // Whether the estimate is held to track the measured error within a factor 2. Not yet
    // for caustic-glass (issue 25): its tiny light (4000 W/m^2/sr) seen through the glass
    // sphere is found by an epoch's camera sample now and then with a value thousands of times
    // the pixel's, and the even/odd difference of such rare samples says anything from 0.3 to
    // 2.2 times the error over the first hundred epochs, by the seed. Its error must still
    // fall.
    bool estimate_tracks = true;
};

RenderSettings Settings(const std::string& file, uint64_t photons, uint32_t photons_per_batch,
                        uint32_t batches, uint64_t stream) {
    RenderSettings settings;
    settings.scene_path = std::string(PF_SOURCE_DIR) + "/scenes/" + file;
    settings.job.width = kSize;
    settings.job.height = kSize;
    settings.job.photon_budget = photons;
    settings.job.layout = {photons_per_batch, batches};
    settings.job.photon_stream = stream;
    return settings;
}

class ShippedSceneConvergence : public testing::TestWithParam<SceneCase> {};

TEST_P(ShippedSceneConvergence, ErrorFallsAndTheEstimateTracksIt) {
    const SceneCase& scene = GetParam();
    auto reference = std::make_shared<Image>(kSize, kSize);
    if (scene.analytic) {
        for (Rgb& pixel : reference->pixels) pixel = Rgb(2.0f);
    } else {
        // Epochs of 2 x 2^13 photons: the reference's radii shrink as far as 2048 epochs take them.
        const absl::StatusOr<RenderOutcome> long_render =
            RenderLocally(Settings(scene.file, kReferencePhotons, 1u << 13, 2, /*stream=*/1));
        ASSERT_TRUE(long_render.ok()) << long_render.status();
        *reference = long_render->image;
    }
    RenderSettings settings = Settings(scene.file, kPhotons, kEpochPhotons, 1, 0);
    settings.reference = reference;
    const absl::StatusOr<RenderOutcome> outcome = RenderLocally(settings);
    ASSERT_TRUE(outcome.ok()) << outcome.status();
    const std::vector<ConvergencePoint>& log = outcome->convergence;
    ASSERT_EQ(log.size(), kPhotons / kEpochPhotons);
    EXPECT_EQ(outcome->progress.nonfinite_discarded, 0u)
        << "no photon path or direct sample may become NaN or Inf";

    double worst_low = 1e9, worst_high = 0;
    for (const ConvergencePoint& point : log) {
        ASSERT_TRUE(point.measured.has_value());
        ASSERT_EQ(point.measured->nonfinite_pixels, 0u) << "epoch " << point.epochs;
        if (point.epochs < kFirstCheckedEpoch) continue;
        ASSERT_TRUE(point.estimated.has_value());
        const double ratio = point.estimated->rmse / point.measured->rmse;
        worst_low = std::min(worst_low, ratio);
        worst_high = std::max(worst_high, ratio);
        EXPECT_TRUE(!scene.estimate_tracks || (ratio >= 0.5 && ratio <= 2.0))
            << scene.file << " epoch " << point.epochs << ": estimated RMSE "
            << point.estimated->rmse << " (its bias part " << point.estimated->bias_rmse
            << ") against a measured " << point.measured->rmse;
    }
    RecordProperty("estimate_over_measured_min", std::to_string(worst_low));
    RecordProperty("estimate_over_measured_max", std::to_string(worst_high));
    EXPECT_LT(log.back().measured->rmse, 0.5 * log[kFirstCheckedEpoch].measured->rmse)
        << "the error must fall";

    if (scene.check_slope) {
        const ConvergenceFits fits = FitConvergence(log);
        ASSERT_TRUE(fits.measured_vs_photons.has_value());
        const ConvergencePoint& first_fitted = log[kFitSkipEpochs];
        ASSERT_GE(
            static_cast<double>(log.back().photons) / static_cast<double>(first_fitted.photons),
            100.0)
            << "the fit must span two decades";
        EXPECT_LE(fits.measured_vs_photons->slope, -0.25);
        RecordProperty("slope", std::to_string(fits.measured_vs_photons->slope));
    }
}

INSTANTIATE_TEST_SUITE_P(Scenes, ShippedSceneConvergence,
                         testing::Values(SceneCase{"cornell-box.gltf", false, true},
                                         SceneCase{"cornell-glass.gltf", false, false},
                                         SceneCase{"caustic-glass.gltf", false, false, false},
                                         SceneCase{"furnace.gltf", true, false},
                                         SceneCase{"furnace-glass.gltf", true, false}),
                         [](const testing::TestParamInfo<SceneCase>& param) {
                             std::string name = param.param.file;
                             name = name.substr(0, name.find('.'));
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

}  // namespace
}  // namespace pf
