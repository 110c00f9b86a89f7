// Every integrator against the analytic white furnace, and every photon mapper against the
// unbiased path tracer on the shipped Cornell scenes, within statistical bounds measured
// from the path tracer's own epochs: a photon mapper that comes out darker or brighter than
// the path tracer has lost or invented light.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "client/local_render.h"
#include "core/render/integrator.h"

namespace pf {
namespace {

std::string ScenePath(const std::string& name) {
    return std::string(PF_SOURCE_DIR) + "/scenes/" + name;
}

// A small render of `scene` with `integrator`, on two threads, with a budget that puts its
// noise well below the bounds below in a few seconds.
RenderSettings Small(const std::string& scene, Integrator integrator, int size) {
    RenderSettings settings;
    settings.scene_path = ScenePath(scene);
    settings.threads = 2;
    JobSpec& job = settings.job;
    job.integrator = integrator;
    job.width = job.height = size;
    job.seed = 5;
    job.layout = {1u << 18, 8};
    switch (integrator) {
        // Progressive photon mapping keeps its k camera samples a pixel for good: with 4, the
        // light's edge pixels alone move a 64-pixel image's mean by a few percent from seed to
        // seed, error that no photon removes (stochastic ppm re-samples them every epoch).
        case Integrator::kPpm:
            job.samples_per_pixel = 16, job.photon_budget = 12'000'000;
            break;
        case Integrator::kSppm:
            job.photon_budget = 12'000'000;
            break;
        case Integrator::kPm:
            job.photon_map.global_photons = 1'000'000;
            job.photon_map.caustic_photons = 1'000'000;
            job.epoch_budget = 8;
            break;
        case Integrator::kPath:
            job.epoch_budget = 96;
            break;
    }
    return settings;
}

std::string Name(const ::testing::TestParamInfo<Integrator>& info) {
    return std::string(IntegratorName(info.param));
}

// Means over square blocks of pixels, per channel, averaged into one value a block.
std::vector<double> BlockMeans(const Image& image, int block) {
    std::vector<double> means;
    for (int by = 0; by + block <= image.height; by += block)
        for (int bx = 0; bx + block <= image.width; bx += block) {
            double sum = 0;
            for (int y = by; y < by + block; ++y)
                for (int x = bx; x < bx + block; ++x) sum += Average(image.At(x, y));
            means.push_back(sum / (block * block));
        }
    return means;
}

class WhiteFurnace : public ::testing::TestWithParam<Integrator> {};

TEST_P(WhiteFurnace, ConvergesToEmissionOverOneMinusAlbedo) {
    // furnace.gltf: a closed room of albedo 0.5 emitting Le = 1 everywhere, so L = 2 exactly,
    // through every path length: direct emission, light sampling, photons and MIS weights alike.
    const absl::StatusOr<RenderOutcome> outcome =
        RenderLocally(Small("furnace.gltf", GetParam(), 32));
    ASSERT_TRUE(outcome.ok()) << outcome.status();
    std::vector<float> values;
    double sum = 0;
    for (const Rgb& pixel : outcome->image.pixels) {
        ASSERT_TRUE(IsFinite(pixel));
        values.push_back(Average(pixel));
        sum += values.back();
    }
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    EXPECT_NEAR(sum / values.size(), 2.0, 0.03)
        << "the image mean must be within 1.5% of Le / (1 - rho)";
    EXPECT_NEAR(values[values.size() / 2], 2.0, 0.08) << "the typical pixel must be within 4%";
}

INSTANTIATE_TEST_SUITE_P(Integrators, WhiteFurnace,
                         ::testing::Values(Integrator::kPpm, Integrator::kSppm, Integrator::kPm,
                                           Integrator::kPath),
                         Name);

// The path tracer's image of a scene, with each block's standard error measured from the
// spread of its epochs (independent samples).
struct Reference {
    std::vector<double> mean, standard_error;
};

Reference PathTracerReference(const std::string& scene, int size, int block) {
    Reference reference;
    std::vector<std::vector<double>> epochs;
    Image previous(size, size);
    const EpochCallback on_epoch = [&](const RenderProgress& progress, const Job& job) {
        // The job's image is the mean of its epochs: this epoch's own is n E_n - (n - 1) E_(n-1).
        const Image current = *job.CurrentImage();
        Image epoch(size, size);
        const float n = static_cast<float>(progress.epochs);
        for (size_t p = 0; p < current.pixels.size(); ++p)
            epoch.pixels[p] = current.pixels[p] * n - previous.pixels[p] * (n - 1);
        epochs.push_back(BlockMeans(epoch, block));
        previous = current;
    };
    const absl::StatusOr<RenderOutcome> outcome =
        RenderLocally(Small(scene, Integrator::kPath, size), on_epoch);
    EXPECT_TRUE(outcome.ok()) << outcome.status();
    if (!outcome.ok() || epochs.size() < 2) return reference;
    reference.mean = BlockMeans(outcome->image, block);
    const double n = static_cast<double>(epochs.size());
    for (size_t b = 0; b < reference.mean.size(); ++b) {
        double squares = 0;
        for (const std::vector<double>& epoch : epochs)
            squares += (epoch[b] - reference.mean[b]) * (epoch[b] - reference.mean[b]);
        reference.standard_error.push_back(std::sqrt(squares / (n - 1) / n));
    }
    return reference;
}

struct SceneCase {
    std::string scene;
    Integrator integrator;
};

class AgreesWithThePathTracer : public ::testing::TestWithParam<SceneCase> {};

TEST_P(AgreesWithThePathTracer, BlockByBlockAndOverall) {
    constexpr int kSize = 64, kBlock = 16;
    const SceneCase& c = GetParam();
    const Reference reference = PathTracerReference(c.scene, kSize, kBlock);
    ASSERT_FALSE(reference.mean.empty());
    const absl::StatusOr<RenderOutcome> outcome =
        RenderLocally(Small(c.scene, c.integrator, kSize));
    ASSERT_TRUE(outcome.ok()) << outcome.status();
    const std::vector<double> blocks = BlockMeans(outcome->image, kBlock);
    // Each block within 4 of the path tracer's standard errors plus 4% for the photon mapper's
    // own noise and its bias (radii or k-nearest discs that blur light across edges); the
    // whole image within 4 standard errors plus 1.5%.
    double sum = 0, reference_sum = 0, variance = 0;
    for (size_t b = 0; b < blocks.size(); ++b) {
        const double expected = reference.mean[b];
        EXPECT_NEAR(blocks[b], expected, 4 * reference.standard_error[b] + 0.04 * expected)
            << IntegratorName(c.integrator) << " on " << c.scene << ", block " << b << " of "
            << blocks.size();
        sum += blocks[b];
        reference_sum += expected;
        variance += reference.standard_error[b] * reference.standard_error[b];
    }
    const double count = static_cast<double>(blocks.size());
    EXPECT_NEAR(sum / count, reference_sum / count,
                4 * std::sqrt(variance) / count + 0.015 * reference_sum / count)
        << IntegratorName(c.integrator) << " on " << c.scene
        << ": the image mean against the path tracer's";
}

std::string CaseName(const ::testing::TestParamInfo<SceneCase>& info) {
    std::string scene = info.param.scene.substr(0, info.param.scene.find('.'));
    std::replace(scene.begin(), scene.end(), '-', '_');
    return std::string(IntegratorName(info.param.integrator)) + "_" + scene;
}

INSTANTIATE_TEST_SUITE_P(PhotonMappers, AgreesWithThePathTracer,
                         ::testing::Values(SceneCase{"cornell-box.gltf", Integrator::kPpm},
                                           SceneCase{"cornell-box.gltf", Integrator::kSppm},
                                           SceneCase{"cornell-box.gltf", Integrator::kPm},
                                           SceneCase{"cornell-glossy.gltf", Integrator::kSppm}),
                         CaseName);

}  // namespace
}  // namespace pf
