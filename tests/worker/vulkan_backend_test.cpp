// The Vulkan backend against the CPU backend on the same batches, with the Khronos validation
// layer on (tests/support/vulkan_validation.cpp): every test ends with zero validation
// errors. Skipped only where no Vulkan device exists at all (lavapipe counts as one).
#include "worker/backends/vulkan/vulkan_backend.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <string>

#include "core/ppm/camera_pass.h"
#include "core/ppm/job_spec.h"
#include "core/ppm/progressive_estimate.h"
#include "core/scene/emitters.h"
#include "core/scene/scene_loader.h"
#include "tests/support/vulkan_validation.h"
#include "worker/backend_factory.h"
#include "worker/backends/cpu_embree/embree_tracer.h"
#include "worker/backends/vulkan/context.h"
#include "worker/backends/vulkan/gpu_scene.h"

namespace pf {
namespace {

// One scene's hit points and first epoch, with both backends begun on it.
struct Rendering {
    Scene scene;
    std::unique_ptr<Emitters> emitters;
    std::unique_ptr<ProgressiveEstimate> estimate;
    std::unique_ptr<Backend> cpu, vulkan;
};

std::unique_ptr<Rendering> BeginBoth(const std::string& name, int size) {
    auto setup = std::make_unique<Rendering>();
    setup->scene = *LoadScene(std::string(PF_SOURCE_DIR) + "/scenes/" + name);
    auto tracer = std::move(*embree::EmbreeTracer::Create(setup->scene));
    const CameraPassResult camera_pass = RunCameraPass(setup->scene, *tracer, {size, size, 2, 1});
    JobSpec spec;
    spec.photon_budget = 1;
    spec.layout = {1u << 16, 4};
    setup->estimate = std::make_unique<ProgressiveEstimate>(
        camera_pass, EstimateFor(spec, camera_pass, setup->scene, name));
    setup->emitters = std::make_unique<Emitters>(setup->scene);
    setup->cpu = std::move(*CreateBackend("cpu", setup->scene));
    absl::StatusOr<std::unique_ptr<Backend>> vulkan = CreateBackend("vulkan", setup->scene);
    EXPECT_TRUE(vulkan.ok()) << vulkan.status();
    if (!vulkan.ok()) return nullptr;
    setup->vulkan = std::move(*vulkan);
    for (Backend* backend : {setup->cpu.get(), setup->vulkan.get()}) {
        EXPECT_TRUE(
            backend
                ->BeginJob({&setup->scene, setup->emitters.get(), setup->estimate->HitPoints(), 7})
                .ok());
        EXPECT_TRUE(
            backend->BeginEpoch(setup->estimate->Epoch(), setup->estimate->SearchRadiusSq()).ok());
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

double TotalFlux(const Tally& tally) {
    double sum = 0;
    for (const Rgb& flux : tally.flux) sum += Average(flux);
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
        setup->vulkan->BeginEpoch(setup->estimate->Epoch(), setup->estimate->SearchRadiusSq())
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
// so the two backends follow nearly the same paths; float differences (trig, intersection)
// move deposits a little, and those near a hit point's radius go the other way. The totals
// must agree within the photon noise of independent streams, 4/sqrt(M), which is
// conservative here; each direct-light sample (same numbers, no radius) must match.
void ExpectBatchesAgree(Backend& cpu_backend, Backend& vulkan_backend,
                        const std::vector<BatchSpec>& specs) {
    const absl::StatusOr<std::vector<BatchResult>> cpu = cpu_backend.RunBatches(specs);
    const absl::StatusOr<std::vector<BatchResult>> gpu = vulkan_backend.RunBatches(specs);
    ASSERT_TRUE(cpu.ok() && gpu.ok());
    double cpu_photons = 0, gpu_photons = 0, cpu_flux = 0, gpu_flux = 0, cpu_segments = 0,
           gpu_segments = 0;
    size_t samples = 0, differing = 0;
    for (size_t b = 0; b < specs.size(); ++b) {
        const BatchResult& c = (*cpu)[b];
        const BatchResult& g = (*gpu)[b];
        cpu_photons += TotalPhotons(c.tally), gpu_photons += TotalPhotons(g.tally);
        cpu_flux += TotalFlux(c.tally), gpu_flux += TotalFlux(g.tally);
        cpu_segments += c.segments_traced, gpu_segments += g.segments_traced;
        EXPECT_EQ(g.photons_emitted, c.photons_emitted);
        EXPECT_EQ(g.nonfinite_discarded, 0u);
        ASSERT_EQ(g.samples.size(), c.samples.size());
        for (size_t i = 0; i < c.samples.size(); ++i, ++samples) {
            const double expected = Average(c.samples[i]), actual = Average(g.samples[i]);
            differing += std::abs(actual - expected) > 1e-3 * std::abs(expected) + 1e-6;
        }
    }
    const double noise = 4 / std::sqrt(cpu_photons);
    EXPECT_GT(cpu_photons, 1000);
    EXPECT_NEAR(gpu_photons / cpu_photons, 1.0, noise)
        << cpu_photons << " photons gathered on the CPU";
    EXPECT_NEAR(gpu_flux / cpu_flux, 1.0, noise);
    EXPECT_NEAR(gpu_segments / cpu_segments, 1.0, 4 / std::sqrt(cpu_segments));
    EXPECT_LE(differing, samples / 100)
        << "direct-light samples must match but for a few grazing shadow rays";
}

TEST_F(VulkanBackendTest, BatchesMatchTheCpuBackendsOnTheSameStreams) {
    for (const char* scene : {"cornell-box.gltf", "cornell-glass.gltf", "furnace.gltf"}) {
        SCOPED_TRACE(scene);
        std::unique_ptr<Rendering> setup = BeginBoth(scene, 32);
        ASSERT_NE(setup, nullptr);
        ExpectBatchesAgree(*setup->cpu, *setup->vulkan, setup->estimate->EpochBatches());
    }
}

TEST_F(VulkanBackendTest, SppmEpochsTraceTheirOwnHitPointsAndMatchTheCpuBackend) {
    // Each backend traces the epoch's stochastic camera pass itself; both must gather on the
    // same hit points, epoch after epoch (the slots move with every epoch's jitter).
    Scene scene = *LoadScene(std::string(PF_SOURCE_DIR) + "/scenes/cornell-glossy.gltf");
    const Emitters emitters(scene);
    JobSpec spec;
    spec.integrator = Integrator::kSppm;
    spec.width = spec.height = 24;
    spec.samples_per_pixel = 2;
    spec.photon_budget = 1;
    spec.layout = {1u << 16, 4};
    const std::vector<float> radius_sq(size_t{24} * 24 * 2, 0.03f * 0.03f);
    std::unique_ptr<Backend> cpu = std::move(*CreateBackend("cpu", scene));
    absl::StatusOr<std::unique_ptr<Backend>> vulkan = CreateBackend("vulkan", scene);
    ASSERT_TRUE(vulkan.ok()) << vulkan.status();
    for (Backend* backend : {cpu.get(), vulkan->get()})
        ASSERT_TRUE(backend->BeginJob({&scene, &emitters, {}, 7, &spec}).ok());
    for (uint64_t epoch : {0u, 5u}) {
        SCOPED_TRACE(epoch);
        for (Backend* backend : {cpu.get(), vulkan->get()})
            ASSERT_TRUE(backend->BeginEpoch(epoch, radius_sq).ok());
        std::vector<BatchSpec> specs;
        for (uint32_t b = 0; b < 4; ++b)
            specs.push_back(
                MakeBatchSpec(spec.layout, epoch, b, static_cast<uint32_t>(radius_sq.size())));
        ExpectBatchesAgree(*cpu, **vulkan, specs);
    }
}

TEST_F(VulkanBackendTest, BatchLargerThanOneDispatchTracesEveryPhoton) {
    // A batch of more photons than one dispatch takes runs as several; the paths traced match
    // the CPU's (the same streams) within 4/sqrt(segments), which a lost dispatch (8% of the
    // photons here) would exceed many times over.
    std::unique_ptr<Rendering> setup = BeginBoth("cornell-box.gltf", 16);
    ASSERT_NE(setup, nullptr);
    BatchSpec spec = setup->estimate->EpochBatches()[0];
    spec.photons = vk::kMaxThreadsPerDispatch + vk::kMaxThreadsPerDispatch / 12;
    const absl::StatusOr<std::vector<BatchResult>> cpu =
        setup->cpu->RunBatches(std::span(&spec, 1));
    const absl::StatusOr<std::vector<BatchResult>> gpu =
        setup->vulkan->RunBatches(std::span(&spec, 1));
    ASSERT_TRUE(cpu.ok() && gpu.ok());
    const double cpu_segments = (*cpu)[0].segments_traced;
    EXPECT_NEAR((*gpu)[0].segments_traced / cpu_segments, 1.0, 4 / std::sqrt(cpu_segments));
    EXPECT_NEAR(TotalPhotons((*gpu)[0].tally) / TotalPhotons((*cpu)[0].tally), 1.0,
                4 / std::sqrt(TotalPhotons((*cpu)[0].tally)));
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
    }
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

TEST_F(VulkanBackendTest, TheChosenDeviceIsListed) {
    const std::string listing = DescribeDevices(2);
    EXPECT_NE(listing.find(context_->Info().name), std::string::npos) << listing;
    EXPECT_NE(listing.find("<- --backend vulkan uses this one"), std::string::npos) << listing;
}

}  // namespace
}  // namespace pf
