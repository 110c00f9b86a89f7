// The Vulkan backend against the CPU backend on the same batches, with the Khronos validation
// layer on (tests/support/vulkan_validation.cpp): every test ends with zero validation
// errors. Skipped only where no Vulkan device exists at all (lavapipe counts as one).
#include "worker/backends/vulkan/vulkan_backend.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "core/camera/camera_pass.h"
#include "core/estimate/progressive_estimate.h"
#include "core/job/job_spec.h"
#include "core/scene/emitters.h"
#include "core/scene_io/scene_loader.h"
#include "embree/embree_tracer.h"
#include "tests/support/image_agreement.h"
#include "tests/support/vulkan_validation.h"
#include "worker/backend_factory.h"
#include "worker/backends/vulkan/context.h"
#include "worker/backends/vulkan/gpu_scene.h"

namespace pf {
namespace {

// One scene's ppm job: its hit points and first epoch, with both backends begun on it (each
// tracing the epoch's camera pass for direct light itself, as the estimate does).
struct Rendering {
    Scene scene;
    JobSpec spec;
    std::unique_ptr<Emitters> emitters;
    std::unique_ptr<ProgressiveEstimate> estimate;
    std::unique_ptr<Backend> cpu, vulkan;
};

std::unique_ptr<Rendering> BeginBoth(const std::string& name, int size,
                                     BatchLayout layout = {1u << 16, 4}) {
    auto setup = std::make_unique<Rendering>();
    setup->scene = *LoadScene(std::string(PF_SOURCE_DIR) + "/scenes/" + name);
    std::shared_ptr<const Tracer> tracer = std::move(*embree::EmbreeTracer::Create(setup->scene));
    JobSpec& spec = setup->spec;
    spec.width = spec.height = size;
    spec.samples_per_pixel = 2;
    spec.seed = 1;
    spec.photon_budget = 1;
    spec.layout = layout;
    const CameraPassSettings film = *FilmFor(spec, setup->scene);
    setup->emitters = std::make_unique<Emitters>(setup->scene);
    CameraPassResult camera_pass = RunCameraPass(setup->scene, *setup->emitters, *tracer, film);
    const EstimateSettings settings = EstimateFor(spec, camera_pass, setup->scene, name);
    // The hit points' surfaces probed, so that both backends keep to them alike.
    camera_pass.extent = ProbeSurfaceExtents(
        setup->scene, *tracer, camera_pass.hit_points,
        std::vector<float>(camera_pass.hit_points.size(), float(settings.initial_radius)));
    setup->estimate =
        std::make_unique<ProgressiveEstimate>(camera_pass, settings, EpochCameraPass{});
    setup->cpu = std::move(*CreateBackend("cpu", setup->scene));
    absl::StatusOr<std::unique_ptr<Backend>> vulkan = CreateBackend("vulkan", setup->scene);
    EXPECT_TRUE(vulkan.ok()) << vulkan.status();
    if (!vulkan.ok()) return nullptr;
    setup->vulkan = std::move(*vulkan);
    for (Backend* backend : {setup->cpu.get(), setup->vulkan.get()}) {
        EXPECT_TRUE(backend
                        ->BeginJob({&setup->scene, setup->emitters.get(),
                                    setup->estimate->HitPoints(), 7, &setup->spec})
                        .ok());
        EXPECT_TRUE(
            backend->BeginEpoch(setup->estimate->Epoch(), setup->estimate->Regions(), nullptr)
                .ok());
    }
    return setup;
}

class VulkanBackendTest : public ::testing::Test {
protected:
    void SetUp() override {
        testing::SkipWithoutVulkan();
        if (IsSkipped() || HasFatalFailure()) return;
        context_ = *vk::Context::Shared();
    }
    void TearDown() override {
        EXPECT_EQ(vk::Context::ValidationErrors(), 0u) << "see the 'Vulkan validation' lines above";
    }

    std::shared_ptr<vk::Context> context_;
};

double TotalPhotons(const Tally& tally) {
    double sum = 0;
    for (uint32_t photons : tally.photons) sum += photons;
    return sum;
}

// The flux per channel (R, G, B), summed over the tally.
Rgbd TotalFlux(const Tally& tally) {
    Rgbd sum(0.0);
    for (const Rgb& flux : tally.flux) sum = sum + Rgbd(flux);
    return sum;
}

TEST_F(VulkanBackendTest, BatchIsAPureFunctionOfItsSpec) {
    std::unique_ptr<Rendering> setup = BeginBoth("cornell-glass.gltf", 32);
    ASSERT_NE(setup, nullptr);
    const std::vector<BatchSpec> specs = setup->estimate->EpochBatches();
    const absl::StatusOr<std::vector<BatchResult>> all = setup->vulkan->RunBatches(specs);
    ASSERT_TRUE(all.ok()) << all.status();
    // The second batch alone, after the grid was rebuilt: the same integers summed in
    // whatever order the device's threads arrived.
    ASSERT_TRUE(
        setup->vulkan->BeginEpoch(setup->estimate->Epoch(), setup->estimate->Regions(), nullptr)
            .ok());
    const absl::StatusOr<std::vector<BatchResult>> one =
        setup->vulkan->RunBatches(std::span(specs).subspan(1, 1));
    ASSERT_TRUE(one.ok()) << one.status();
    const BatchResult& a = (*all)[1];
    const BatchResult& b = (*one)[0];
    EXPECT_EQ(a.tally.hit_point, b.tally.hit_point);
    EXPECT_EQ(a.tally.photons, b.tally.photons);
    EXPECT_EQ(a.tally.inner_photons, b.tally.inner_photons);
    EXPECT_EQ(a.tally.flux, b.tally.flux);
    EXPECT_EQ(a.samples, b.samples);
    EXPECT_EQ(a.segments_traced, b.segments_traced);
    EXPECT_GT(a.tally.Size(), 0u);
    // Compacted on the device in hit point order, one entry per hit point reached.
    EXPECT_TRUE(std::adjacent_find(a.tally.hit_point.begin(), a.tally.hit_point.end(),
                                   std::greater_equal<>()) == a.tally.hit_point.end());
    for (size_t e = 0; e < a.tally.Size(); ++e) {
        EXPECT_GT(a.tally.photons[e], 0u);
        EXPECT_LE(a.tally.inner_photons[e], a.tally.photons[e]);
    }
}

// The shaders draw the same random numbers as the CPU (core/shared/rng.h) in the same order,
// so the two backends start the same paths; float differences (trig, intersection) move
// deposits a little, and paths that graze an edge part ways, so the totals differ by noise
// (about 0.9% per channel over 2^18 photons, measured over ten seeds: not the 1/sqrt(M) of
// identical paths). Batches are independent, so each total is compared by a paired t-test
// over the batches: x_b = Vulkan's total minus the CPU's in batch b has mean 0 for a kernel
// that computes the same estimator, and mean(x) / (sd(x) / sqrt(K)) is Student's t with K - 1
// degrees of freedom (K batches), allowed to the two-sided 1e-5 quantile. Compared: photons
// found, each channel's flux (so a tint or a channel swap in a kernel fails), segments traced.
// Each direct-light sample (same numbers, no radius) must match in every channel.
struct PairedTotal {
    double cpu = 0, mean_difference = 0, standard_error = 0, limit = 0;
    bool Passed() const { return std::abs(mean_difference) <= limit; }
    // The relative bias of the Vulkan total that fails this check with probability 0.999.
    double DetectableBias(size_t batches) const {
        return (limit + 3.1 * standard_error) * static_cast<double>(batches) / cpu;
    }
};

PairedTotal ComparePaired(const std::vector<double>& cpu, const std::vector<double>& gpu) {
    PairedTotal total;
    const double batches = static_cast<double>(cpu.size());
    double sum = 0, squares = 0;
    for (size_t b = 0; b < cpu.size(); ++b) {
        total.cpu += cpu[b];
        sum += gpu[b] - cpu[b];
        squares += (gpu[b] - cpu[b]) * (gpu[b] - cpu[b]);
    }
    total.mean_difference = sum / batches;
    const double variance =
        std::max(0.0, squares - batches * total.mean_difference * total.mean_difference) /
        (batches - 1);
    total.standard_error = std::sqrt(variance / batches);
    total.limit =
        testing::StudentTQuantile(testing::kFalseAlarm / 2, batches - 1) * total.standard_error;
    return total;
}

struct BatchComparison {
    size_t batches = 0;
    PairedTotal photons, segments;
    std::array<PairedTotal, 3> flux;            // R, G, B
    size_t samples = 0, differing_samples = 0;  // a sample differs if any channel does
    bool same_emitted = true, finite = true;

    // One entry per check that failed, with its numbers; empty if all held.
    std::string Failures() const {
        std::string failures;
        if (batches < 8) failures += absl::StrCat(batches, " batches, too few to compare; ");
        if (!same_emitted) failures += "photons emitted or sample counts differ; ";
        if (!finite) failures += "the Vulkan backend discarded NaN/Inf paths; ";
        const auto check = [&](const char* name, const PairedTotal& total) {
            if (!total.Passed())
                failures +=
                    absl::StrCat(name, ": Vulkan - CPU ", total.mean_difference, " a batch (CPU ",
                                 total.cpu / batches, "), allowed +-", total.limit, "; ");
        };
        check("photons found", photons);
        check("red flux", flux[0]);
        check("green flux", flux[1]);
        check("blue flux", flux[2]);
        check("segments", segments);
        if (differing_samples > samples / 100)
            failures += absl::StrCat(differing_samples, " of ", samples,
                                     " direct-light samples differ (allowed: 1%, grazing shadow "
                                     "rays); ");
        return failures;
    }
};

BatchComparison CompareBatches(const std::vector<BatchResult>& cpu,
                               const std::vector<BatchResult>& gpu) {
    BatchComparison comparison;
    comparison.batches = std::min(cpu.size(), gpu.size());
    comparison.same_emitted = cpu.size() == gpu.size();
    std::vector<double> photons[2], segments[2], flux[2][3];
    for (size_t b = 0; b < comparison.batches; ++b) {
        for (int side = 0; side < 2; ++side) {
            const BatchResult& result = side == 0 ? cpu[b] : gpu[b];
            photons[side].push_back(TotalPhotons(result.tally));
            segments[side].push_back(static_cast<double>(result.segments_traced));
            const Rgbd total = TotalFlux(result.tally);
            for (int c = 0; c < 3; ++c) flux[side][c].push_back(total[c]);
        }
        const BatchResult& c = cpu[b];
        const BatchResult& g = gpu[b];
        comparison.same_emitted = comparison.same_emitted &&
                                  g.photons_emitted == c.photons_emitted &&
                                  g.samples.size() == c.samples.size();
        comparison.finite = comparison.finite && g.nonfinite_discarded == 0;
        for (size_t i = 0; i < c.samples.size() && i < g.samples.size(); ++i) {
            ++comparison.samples;
            bool differs = false;
            for (int channel = 0; channel < 3; ++channel) {
                const double expected = c.samples[i][channel], actual = g.samples[i][channel];
                differs =
                    differs || !(std::abs(actual - expected) <= 1e-3 * std::abs(expected) + 1e-6);
            }
            comparison.differing_samples += differs;
        }
    }
    if (comparison.batches < 2) return comparison;
    comparison.photons = ComparePaired(photons[0], photons[1]);
    comparison.segments = ComparePaired(segments[0], segments[1]);
    for (int c = 0; c < 3; ++c) comparison.flux[c] = ComparePaired(flux[0][c], flux[1][c]);
    return comparison;
}

// Runs `specs` on both backends and compares; returns both sides' results.
std::pair<std::vector<BatchResult>, std::vector<BatchResult>> ExpectBatchesAgree(
    Backend& cpu_backend, Backend& vulkan_backend, const std::vector<BatchSpec>& specs) {
    const absl::StatusOr<std::vector<BatchResult>> cpu = cpu_backend.RunBatches(specs);
    const absl::StatusOr<std::vector<BatchResult>> gpu = vulkan_backend.RunBatches(specs);
    EXPECT_TRUE(cpu.ok() && gpu.ok());
    if (!cpu.ok() || !gpu.ok()) return {};
    EXPECT_EQ(CompareBatches(*cpu, *gpu).Failures(), "");
    return {*cpu, *gpu};
}

TEST_F(VulkanBackendTest, BatchesMatchTheCpuBackendsOnTheSameStreams) {
    // 64 batches of 2^13 photons (512k) on the glass and furnace scenes: 63 degrees of freedom.
    for (const char* scene : {"cornell-glass.gltf", "furnace.gltf"}) {
        SCOPED_TRACE(scene);
        std::unique_ptr<Rendering> setup = BeginBoth(scene, 32, {1u << 13, 64});
        ASSERT_NE(setup, nullptr);
        ExpectBatchesAgree(*setup->cpu, *setup->vulkan, setup->estimate->EpochBatches());
    }
}

// cornell-box (coloured walls, so red and blue differ) with 64 batches of 2^16 photons (4M):
// enough that every channel's flux would fail with a 2% bias, as the Vulkan results changed as
// a broken kernel would change them show: every channel's flux 2% high or low, green's alone,
// red and blue swapped, the direct light's green 2% high.
TEST_F(VulkanBackendTest, CornellBoxBatchesMatchAndABiasedOrSwappedKernelWouldNot) {
    std::unique_ptr<Rendering> setup = BeginBoth("cornell-box.gltf", 32, {1u << 16, 64});
    ASSERT_NE(setup, nullptr);
    const auto [cpu, gpu] =
        ExpectBatchesAgree(*setup->cpu, *setup->vulkan, setup->estimate->EpochBatches());
    ASSERT_FALSE(gpu.empty());
    const BatchComparison measured = CompareBatches(cpu, gpu);
    for (int c = 0; c < 3; ++c) {
        EXPECT_LE(measured.flux[c].DetectableBias(measured.batches), 0.02) << "channel " << c;
        RecordProperty("flux_detectable_bias_" + std::to_string(c),
                       std::to_string(measured.flux[c].DetectableBias(measured.batches)));
    }
    const auto broken = [&](const std::function<void(Rgb&)>& flux,
                            const std::function<void(Rgb&)>& sample) {
        std::vector<BatchResult> results = gpu;
        for (BatchResult& result : results) {
            for (Rgb& value : result.tally.flux) flux(value);
            for (Rgb& value : result.samples) sample(value);
        }
        return CompareBatches(cpu, results).Failures();
    };
    const auto keep = [](Rgb&) {};
    EXPECT_NE(broken([](Rgb& v) { v = v * 1.02f; }, keep), "") << "flux 2% high";
    EXPECT_NE(broken([](Rgb& v) { v = v * 0.98f; }, keep), "") << "flux 2% low";
    EXPECT_NE(broken([](Rgb& v) { v.y *= 1.02f; }, keep), "") << "green flux 2% high";
    EXPECT_NE(broken([](Rgb& v) { std::swap(v.x, v.z); }, keep), "") << "flux red and blue";
    EXPECT_NE(broken(keep, [](Rgb& v) { v.y *= 1.02f; }), "") << "direct green 2% high";
    EXPECT_EQ(broken(keep, keep), "");
}

TEST_F(VulkanBackendTest, StochasticEpochsTraceTheirOwnHitPointsAndMatchTheCpuBackend) {
    // Each backend traces the epoch's stochastic camera pass itself; both must gather on the
    // same hit points, epoch after epoch (the slots move with every epoch's jitter): sppm's,
    // and rpm's camera hit points (caustics alone: the rough metal sphere's) with their gather
    // hits (every photon, direct light's included), no direct light sampled at the latter.
    Scene scene = *LoadScene(std::string(PF_SOURCE_DIR) + "/scenes/cornell-glossy.gltf");
    const Emitters emitters(scene);
    for (const Integrator integrator : {Integrator::kSppm, Integrator::kRpm}) {
        SCOPED_TRACE(IntegratorName(integrator));
        JobSpec spec;
        spec.integrator = integrator;
        spec.width = spec.height = 24;
        spec.samples_per_pixel = 2;
        spec.photon_budget = 1;
        spec.layout = {1u << 14, 16};  // 16 batches an epoch: 15 degrees of freedom to compare
        const GatherRegions regions{
            std::vector<float>(size_t{24} * 24 * 2 * SlotsPerCameraSample(spec), 0.03f * 0.03f),
            {}};
        const std::vector<float>& radius_sq = regions.radius_sq;
        std::unique_ptr<Backend> cpu = std::move(*CreateBackend("cpu", scene));
        absl::StatusOr<std::unique_ptr<Backend>> vulkan = CreateBackend("vulkan", scene);
        ASSERT_TRUE(vulkan.ok()) << vulkan.status();
        for (Backend* backend : {cpu.get(), vulkan->get()})
            ASSERT_TRUE(backend->BeginJob({&scene, &emitters, {}, 7, &spec}).ok());
        for (uint64_t epoch : {0u, 5u}) {
            SCOPED_TRACE(epoch);
            for (Backend* backend : {cpu.get(), vulkan->get()})
                ASSERT_TRUE(backend->BeginEpoch(epoch, regions, nullptr).ok());
            std::vector<BatchSpec> specs;
            for (uint32_t b = 0; b < spec.layout.batches_per_epoch; ++b)
                specs.push_back(
                    MakeBatchSpec(spec.layout, epoch, b, static_cast<uint32_t>(radius_sq.size())));
            const auto [cpu_results, gpu_results] = ExpectBatchesAgree(*cpu, **vulkan, specs);
            if (integrator != Integrator::kRpm || gpu_results.empty()) continue;
            // Direct light at camera hit points alone: every fifth slot (1 + 4 gather rays).
            size_t lit = 0;
            for (const BatchResult& result : gpu_results)
                for (uint32_t i = 0; i < result.samples.size(); ++i) {
                    const bool gather_slot = (result.spec.sample_begin + i) % 5 != 0;
                    if (gather_slot) {
                        EXPECT_TRUE(IsBlack(result.samples[i]));
                    }
                    lit += !IsBlack(result.samples[i]);
                }
            EXPECT_GT(lit, radius_sq.size() / 5 / 2);
        }
    }
}

TEST_F(VulkanBackendTest, BatchLargerThanOneDispatchTracesEveryPhoton) {
    // A batch of more photons than one dispatch takes runs as several. 8 independent batches of
    // 1 + 1/12 dispatches each, against the CPU's on the same streams by the paired t-tests
    // above (7 degrees of freedom): a lost or skipped second dispatch (1/13 of the photons,
    // 7.7%) must lie beyond what the check can miss, so its detectable bias is held under 4%
    // (with hit points enough that the batches' sums spread little: 24 x 24 pixels).
    std::unique_ptr<Rendering> setup = BeginBoth("cornell-box.gltf", 24);
    ASSERT_NE(setup, nullptr);
    std::vector<BatchSpec> specs;
    for (uint32_t b = 0; b < 8; ++b) {
        BatchSpec spec = MakeBatchSpec({1u << 16, 8}, 0, b, 0);
        spec.photons = vk::kMaxThreadsPerDispatch + vk::kMaxThreadsPerDispatch / 12;
        specs.push_back(spec);
    }
    const auto [cpu, gpu] = ExpectBatchesAgree(*setup->cpu, *setup->vulkan, specs);
    ASSERT_EQ(gpu.size(), specs.size());
    const BatchComparison measured = CompareBatches(cpu, gpu);
    EXPECT_LE(measured.photons.DetectableBias(measured.batches), 0.04);
    EXPECT_LE(measured.segments.DetectableBias(measured.batches), 0.04);
    for (int c = 0; c < 3; ++c) {
        EXPECT_LE(measured.flux[c].DetectableBias(measured.batches), 0.04) << "channel " << c;
        RecordProperty("flux_detectable_bias_" + std::to_string(c),
                       std::to_string(measured.flux[c].DetectableBias(measured.batches)));
    }
    // The same results with the photons of the second dispatch dropped must fail.
    std::vector<BatchResult> lost = gpu;
    for (BatchResult& result : lost) {
        for (Rgb& flux : result.tally.flux) flux = flux * (12.0f / 13.0f);
        for (uint32_t& photons : result.tally.photons) photons = photons * 12 / 13;
        result.segments_traced = result.segments_traced * 12 / 13;
    }
    EXPECT_NE(CompareBatches(cpu, lost).Failures(), "") << "a lost dispatch passed";
}

TEST_F(VulkanBackendTest, KernelsAreSpecialisedToTheScenesFeatures) {
    for (const auto& [name, glass] :
         {std::pair{"cornell-box.gltf", false}, std::pair{"cornell-glass.gltf", true}}) {
        const Scene scene = *LoadScene(std::string(PF_SOURCE_DIR) + "/scenes/" + name);
        const absl::StatusOr<vk::GpuScene> gpu_scene = vk::BuildGpuScene(scene, Emitters(scene));
        ASSERT_TRUE(gpu_scene.ok());
        EXPECT_EQ(gpu_scene->features.dielectric, glass) << name;
        EXPECT_EQ(gpu_scene->features.mirror, glass)
            << name;  // cornell-glass has a mirror sphere too
        EXPECT_TRUE(gpu_scene->features.triangle_lights) << name;
        EXPECT_FALSE(gpu_scene->features.point_lights || gpu_scene->features.spot_lights) << name;
        EXPECT_EQ(vk::SpecConstantsFor(gpu_scene->features)[gpu::kSpecHasDielectric],
                  glass ? 1u : 0u);
        // Data no kernel of the scene reads is not built.
        EXPECT_EQ(gpu_scene->normals.empty(), !gpu_scene->features.smooth_normals) << name;
        EXPECT_TRUE(gpu_scene->uvs.empty() && gpu_scene->texels.empty()) << name;
        EXPECT_EQ(vk::SpecConstantsFor(gpu_scene->features)[gpu::kSpecHasImageLights], 0u);
        EXPECT_TRUE(gpu_scene->light_image_texels.empty() && gpu_scene->light_image_tables.empty())
            << name;
    }
    // A projector (a 64 x 64 picture) and a goniometric lamp (32 x 32) upload their images, one
    // after the other, with their sampling tables.
    const Scene lamps = *LoadScene(std::string(PF_SOURCE_DIR) + "/scenes/pbrt/cornell-lamps.pbrt");
    const absl::StatusOr<vk::GpuScene> lit = vk::BuildGpuScene(lamps, Emitters(lamps));
    ASSERT_TRUE(lit.ok()) << lit.status();
    EXPECT_EQ(vk::SpecConstantsFor(lit->features)[gpu::kSpecHasImageLights], 1u);
    EXPECT_EQ(lit->light_image_texels.size(), 64u * 64 + 32 * 32);
    // The projector's cumulative table and probabilities, the lamp's rows', texels' and
    // probabilities.
    EXPECT_EQ(lit->light_image_tables.size(), (64u * 64 + 1 + 64 * 64) + (33 + 32 * 33 + 32 * 32));
}

TEST_F(VulkanBackendTest, JobTooLargeForTheDeviceIsRefusedNamingTheLimit) {
    const Scene scene = *LoadScene(std::string(PF_SOURCE_DIR) + "/scenes/cornell-box.gltf");
    const vk::GpuScene gpu_scene = *vk::BuildGpuScene(scene, Emitters(scene));
    const vk::DeviceCapacity small{"small GPU", 64u << 20, 1u << 30};
    EXPECT_TRUE(vk::CheckJobFits(small, gpu_scene, 1'000'000).ok());
    const absl::Status buffer = vk::CheckJobFits(small, gpu_scene, 4'000'000);
    EXPECT_TRUE(absl::IsResourceExhausted(buffer));
    EXPECT_NE(buffer.message().find("small GPU"), std::string::npos) << buffer;
    EXPECT_NE(buffer.message().find("maxStorageBufferRange"), std::string::npos) << buffer;
    const absl::Status memory =
        vk::CheckJobFits({"small GPU", uint64_t{4} << 30, 64u << 20}, gpu_scene, 1'000'000);
    EXPECT_TRUE(absl::IsResourceExhausted(memory));
    EXPECT_NE(memory.message().find("the device has 64 MiB"), std::string::npos) << memory;
}

TEST_F(VulkanBackendTest, AProcessMakesContextsJobAfterJob) {
    // A worker makes a context per job: 40 in a row, each listed and made anew, must all
    // work. (They share the process's instance: NVIDIA's driver, unloaded with the last
    // instance and loaded again, failed vkCreateInstance after some 25 rounds on an H200.)
    for (int job = 0; job < 40; ++job) {
        ASSERT_TRUE(vk::ListDevices().ok()) << "job " << job;
        const absl::StatusOr<std::shared_ptr<vk::Context>> context = vk::Context::Create({});
        ASSERT_TRUE(context.ok()) << "job " << job << ": " << context.status();
    }
}

TEST_F(VulkanBackendTest, TheChosenDeviceIsListed) {
    const std::string listing = DescribeDevices(2);
    EXPECT_NE(listing.find(context_->Info().name), std::string::npos) << listing;
    EXPECT_NE(listing.find("<- --backend vulkan uses this one"), std::string::npos) << listing;
}

}  // namespace
}  // namespace pf
