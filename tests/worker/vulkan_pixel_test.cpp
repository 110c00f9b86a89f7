// The integrators that render pixels (path, pm) on the Vulkan backend against the CPU
// backend, under the Khronos validation layer. Both trace each camera sample from the same ray
// with the same stream, drawing its numbers in the same order, so the device's paths are the
// CPU's but for float rounding (a rounding that flips a Russian roulette or a Fresnel choice
// sends a path its own way): nearly every pixel must agree to 1e-3, and the images' means
// closely. A kernel that mis-weighs any light path would fail it outright. The path tracer's
// wavefront design is held to its megakernel's images, which it must match but for rounding.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "core/job/job_spec.h"
#include "core/scene/emitters.h"
#include "core/scene/scene_features.h"
#include "core/scene_io/scene_loader.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/vulkan_validation.h"
#include "worker/backend_factory.h"
#include "worker/backends/vulkan/context.h"
#include "worker/backends/vulkan/gpu_scene.h"
#include "worker/backends/vulkan/vulkan_backend.h"

namespace pf {
namespace {

struct PixelCase {
    std::string scene;
    Integrator integrator;
    uint32_t final_gather = 0;  // pm
    // The share of pixels that must agree to 1e-3: less where the backends' ray tests differ
    // (curves: Embree's primitives on the CPU, pbrt-v4's test on the device, which part at a
    // curve's edge, sending a path grazing it its own way); the means are held alike.
    double agreeing_share = 0.97;
};

std::string CaseName(const ::testing::TestParamInfo<PixelCase>& info) {
    std::string name = info.param.scene.substr(0, info.param.scene.find('.')) + "_" +
                       std::string(IntegratorName(info.param.integrator));
    if (info.param.final_gather > 0) name += "_final_gather";
    std::ranges::replace(name, '-', '_');
    std::ranges::replace(name, '/', '_');
    return name;
}

class VulkanPixelTest : public ::testing::TestWithParam<PixelCase> {
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

// A 24x24 job of `integrator` over `scene` at 4 samples a pixel, in three batches an epoch.
JobSpec SmallJob(Integrator integrator, uint32_t final_gather = 0) {
    JobSpec spec;
    spec.integrator = integrator;
    spec.width = spec.height = 24;
    spec.samples_per_pixel = 4;
    spec.seed = 3;
    spec.photon_map.global_photons = spec.photon_map.caustic_photons = 50'000;
    spec.photon_map.final_gather = final_gather;
    spec.layout = {0, 3};  // three batches an epoch: slices of the image
    return spec;
}

// The batches of epochs 0 and 3 of `spec`, run on `backend`.
void RunEpochs(Backend& backend, const Scene& scene, const Emitters& emitters, const JobSpec& spec,
               std::vector<BatchSpec>& specs, std::vector<BatchResult>& results) {
    specs.clear();
    for (uint64_t epoch : {0u, 3u})
        for (uint32_t b = 0; b < spec.layout.batches_per_epoch; ++b)
            specs.push_back(MakeBatchSpec(spec.layout, epoch, b, spec.width * spec.height));
    ASSERT_TRUE(backend.BeginJob({&scene, &emitters, {}, 7, &spec}).ok());
    for (const BatchSpec& batch : specs) {
        ASSERT_TRUE(backend.BeginEpoch(batch.epoch, {}, nullptr).ok());
        absl::StatusOr<std::vector<BatchResult>> ran = backend.RunBatches({&batch, 1});
        ASSERT_TRUE(ran.ok()) << ran.status();
        results.push_back(std::move(ran->front()));
    }
}

// The device's batches of `integrator` over `scene` against the CPU's, pixel by pixel.
void ExpectPixelsFollowTheCpu(const Scene& scene, Integrator integrator, uint32_t final_gather,
                              double agreeing_share = 0.97) {
    const Emitters emitters(scene);
    const JobSpec spec = SmallJob(integrator, final_gather);
    std::unique_ptr<Backend> cpu = std::move(*CreateBackend("cpu", scene));
    absl::StatusOr<std::unique_ptr<Backend>> vulkan = CreateBackend("vulkan", scene);
    ASSERT_TRUE(vulkan.ok()) << vulkan.status();
    std::vector<BatchSpec> specs;
    std::vector<BatchResult> results[2];
    ASSERT_NO_FATAL_FAILURE(RunEpochs(*cpu, scene, emitters, spec, specs, results[0]));
    ASSERT_NO_FATAL_FAILURE(RunEpochs(**vulkan, scene, emitters, spec, specs, results[1]));
    size_t pixels = 0, agreeing = 0;
    Rgbd sums[2] = {Rgbd(0.0), Rgbd(0.0)};
    for (size_t b = 0; b < specs.size(); ++b) {
        const BatchResult &c = results[0][b], &g = results[1][b];
        ASSERT_EQ(c.samples.size(), specs[b].sample_end - specs[b].sample_begin);
        ASSERT_EQ(g.samples.size(), c.samples.size());
        EXPECT_EQ(g.nonfinite_discarded, c.nonfinite_discarded);
        for (size_t p = 0; p < c.samples.size(); ++p) {
            ++pixels;
            sums[0] = sums[0] + Rgbd(c.samples[p]);
            sums[1] = sums[1] + Rgbd(g.samples[p]);
            const Rgb difference = Abs(c.samples[p] - g.samples[p]);
            agreeing +=
                MaxComponent(difference) <= 1e-3f * std::max(1.0f, MaxComponent(c.samples[p]));
        }
    }
    ASSERT_EQ(pixels, 2u * 24 * 24);
    EXPECT_GE(double(agreeing), agreeing_share * double(pixels))
        << agreeing << " of " << pixels << " pixels agree to 1e-3";
    for (int channel = 0; channel < 3; ++channel) {
        const double cpu_mean = sums[0][channel] / double(pixels);
        const double gpu_mean = sums[1][channel] / double(pixels);
        EXPECT_GT(cpu_mean, 0.0) << "channel " << channel << ": a black image proves nothing";
        EXPECT_NEAR(gpu_mean, cpu_mean, 0.01 * cpu_mean) << "channel " << channel;
    }
}

TEST_P(VulkanPixelTest, BatchesFollowTheCpuBackendsPaths) {
    const PixelCase& param = GetParam();
    const Scene scene = *LoadScene(std::string(PF_SOURCE_DIR) + "/scenes/" + param.scene);
    ExpectPixelsFollowTheCpu(scene, param.integrator, param.final_gather, param.agreeing_share);
}

TEST_F(VulkanPixelTest, ProceduralTexturesFollowTheCpuBackendsPaths) {
    // pbrt-v4's procedural textures, evaluated at each hit by the kernels as on the CPU: a
    // floor of reflectance scaled by wrinkled and bumped by it, a wall of marble, a rough metal
    // panel whose roughness is fbm, a wall mixing dots and the floor's texture by directionmix.
    // The noise is coarse (its space the world's scaled by 5 and 20) and of few octaves: the
    // CPU's camera samples, which filter it over their footprint, then resolve every octave, as
    // the kernels' point lookups do.
    const std::string path = testing::WriteTextFile(
        "LookAt 0 -2.5 1.8  0 0.3 0.4  0 0 1\nCamera \"perspective\" \"float fov\" 50\n"
        "WorldBegin\n"
        "AttributeBegin\nScale 5 5 5\n"
        "Texture \"wrinkles\" \"float\" \"wrinkled\" \"integer octaves\" 4\n"
        "Texture \"rough\" \"float\" \"fbm\" \"integer octaves\" 4\n"
        "Scale 4 4 4\n"
        "Texture \"stone\" \"spectrum\" \"marble\" \"float scale\" 3 \"integer octaves\" 5 "
        "\"float variation\" 2\n"
        "AttributeEnd\n"
        "Texture \"floor\" \"spectrum\" \"scale\" \"rgb tex\" [0.9 0.7 0.5] "
        "\"texture scale\" \"wrinkles\"\n"
        "Texture \"dots\" \"spectrum\" \"dots\" \"rgb inside\" [0.8 0.2 0.1] "
        "\"rgb outside\" [0.1 0.3 0.9] \"float uscale\" 6 \"float vscale\" 6\n"
        "Texture \"mixed\" \"spectrum\" \"directionmix\" \"texture tex1\" \"dots\" "
        "\"texture tex2\" \"floor\" \"vector3 dir\" [1 0 0]\n"
        "Texture \"bumps\" \"float\" \"scale\" \"texture tex\" \"wrinkles\" "
        "\"float scale\" 0.02\n"
        "Material \"diffuse\" \"texture reflectance\" \"floor\" \"texture displacement\" "
        "\"bumps\"\n"
        "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]\n"
        "Material \"diffuse\" \"texture reflectance\" \"stone\"\n"
        "Shape \"bilinearmesh\" \"point3 P\" [-1 1 0  1 1 0  -1 1 1.5  1 1 1.5]\n"
        "Material \"conductor\" \"texture roughness\" \"rough\"\n"
        "Shape \"bilinearmesh\" \"point3 P\" [0.9 1 0  0.9 -1 0  0.4 1 1.2  0.4 -1 1.2]\n"
        "Material \"diffuse\" \"texture reflectance\" \"mixed\"\n"
        "Shape \"bilinearmesh\" \"point3 P\" [-0.9 -1 0  -0.9 1 0  -0.5 -1 1.2  -0.5 1 1.2]\n"
        "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [6 6 6]\n"
        "Material \"diffuse\" \"rgb reflectance\" [0 0 0]\nTranslate 0 -0.6 1.4\n"
        "Rotate 180 1 0 0\n"
        "Shape \"bilinearmesh\" \"point3 P\" [-0.3 -0.3 0  0.3 -0.3 0  -0.3 0.3 0  0.3 0.3 0]\n"
        "AttributeEnd\n",
        "procedural-textures.pbrt");
    const absl::StatusOr<Scene> scene = LoadScene(path);
    ASSERT_TRUE(scene.ok()) << scene.status();
    ASSERT_TRUE(AnalyseFeatures(*scene, Emitters(*scene)).procedural_textures);
    ExpectPixelsFollowTheCpu(*scene, Integrator::kPath, 0);
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, VulkanPixelTest,
    ::testing::Values(
        // Rough metal and rough glass: GGX sampling, light sampling at metal weighed by MIS.
        PixelCase{"cornell-glossy.gltf", Integrator::kPath},
        PixelCase{"cornell-glossy.gltf", Integrator::kPm},
        PixelCase{"cornell-glossy.gltf", Integrator::kPm, 2},
        // Glass, its caustic map; sheen and coats; diffuse transmission and textures; bump
        // maps (shading normals: photons per unit cosine); a sky with its portal-less map.
        PixelCase{"cornell-glass.gltf", Integrator::kPath},
        PixelCase{"cornell-glass.gltf", Integrator::kPm},
        PixelCase{"cornell-velvet.gltf", Integrator::kPath},
        PixelCase{"cornell-velvet.gltf", Integrator::kPm, 2},
        PixelCase{"cornell-stained.gltf", Integrator::kPath},
        PixelCase{"cornell-stained.gltf", Integrator::kPm},
        PixelCase{"cornell-bumpy.gltf", Integrator::kPath},
        PixelCase{"cornell-bumpy.gltf", Integrator::kPm},
        // Curves of each type (core/shared/curve.h's ray test against Embree's curves), some
        // instanced: camera paths and shadow rays meet and shade them alike (the photon
        // kernels trace with the same TraceRay).
        PixelCase{"pbrt/cornell-curves.pbrt", Integrator::kPath, 0, 0.8}),
    CaseName);

// glTF's vertex colours and single-sided surfaces on the device as on the CPU: the lit quad
// with colours on its floor; a quad facing away from the camera between it and the floor (its
// back faces let camera rays, light samples and light through); an unlit quad whose emission is
// its vertex colours; a quad masked by its vertex colours' alpha.
TEST_F(VulkanPixelTest, VertexColoursAndSingleSidedSurfacesFollowTheCpu) {
    testing::TestScene built = testing::LitQuadScene();
    built.meshes[0].color_components = 3;
    built.meshes[0].colors = {1, 0.2f, 0.2f, 0.2f, 1,    0.2f, 0.2f, 0.2f, 1,
                              1, 0.2f, 0.2f, 0.2f, 0.2f, 1,    1,    1,    1};
    const auto quad = [](float x0, float y0, float x1, float y1, float z, bool up) {
        std::vector<Vec3> corners = {{x0, y0, z}, {x1, y0, z}, {x1, y1, z},
                                     {x0, y0, z}, {x1, y1, z}, {x0, y1, z}};
        if (!up) std::swap(corners[1], corners[2]), std::swap(corners[4], corners[5]);
        return corners;
    };
    testing::TestMaterial grey{Rgb(0.7f), Rgb(0.0f)};
    testing::TestMaterial unlit{Rgb(0.9f), Rgb(0.0f)};
    unlit.extensions = R"("KHR_materials_unlit":{})";
    testing::TestMaterial masked{Rgb(0.6f, 0.6f, 0.2f), Rgb(0.0f)};
    masked.extra = R"(,"alphaMode":"MASK","alphaCutoff":0.5,"doubleSided":true)";
    built.materials.insert(built.materials.end(), {grey, unlit, masked});
    built.meshes.push_back({quad(-0.9f, -0.9f, -0.2f, 0.9f, 0.5f, false), 2});
    testing::TestMesh lamp{quad(0.3f, -0.9f, 0.9f, -0.3f, 0.2f, true), 3};
    lamp.color_components = 3;
    lamp.colors = {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 1, 0};
    testing::TestMesh cut{quad(0.3f, 0.2f, 0.9f, 0.9f, 0.3f, true), 4};
    cut.colors = {1, 1, 1, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 0, 1, 1, 1, 1, 1, 1, 1, 0};
    built.meshes.insert(built.meshes.end(), {lamp, cut});
    const Scene scene = *LoadScene(testing::WriteGltf(built, "colors-single-sided.gltf"));
    const SceneFeatures features = AnalyseFeatures(scene, Emitters(scene));
    ASSERT_TRUE(features.vertex_colors && features.cut_outs);
    ExpectPixelsFollowTheCpu(scene, Integrator::kPath, 0);
    // The colours share the tangents' binding; a scene without pays nothing for them.
    EXPECT_EQ(vk::BuildGpuScene(scene, Emitters(scene))->tangents.size(), scene.positions.size());
    const Scene plain = *LoadScene(std::string(PF_SOURCE_DIR) + "/scenes/cornell-box.gltf");
    const vk::GpuScene plain_gpu = *vk::BuildGpuScene(plain, Emitters(plain));
    EXPECT_TRUE(plain_gpu.tangents.empty());
    EXPECT_EQ(vk::SpecConstantsFor(plain_gpu.features)[gpu::kSpecHasVertexColors], 0u);
}

TEST_F(VulkanPixelTest, PhotonMapsTooLargeForTheDeviceAreRefusedNamingThem) {
    // The maps are checked against the host's memory when built (as on the CPU) and against
    // the device's when uploaded.
    const Scene scene = *LoadScene(std::string(PF_SOURCE_DIR) + "/scenes/cornell-box.gltf");
    const Emitters emitters(scene);
    JobSpec spec;
    spec.integrator = Integrator::kPm;
    spec.width = spec.height = 8;
    spec.photon_map.global_photons = spec.photon_map.caustic_photons = 1'000'000'000'000;
    absl::StatusOr<std::unique_ptr<Backend>> vulkan = CreateBackend("vulkan", scene);
    ASSERT_TRUE(vulkan.ok()) << vulkan.status();
    const absl::Status refused = (*vulkan)->BeginJob({&scene, &emitters, {}, 7, &spec});
    EXPECT_TRUE(absl::IsResourceExhausted(refused)) << refused;
    EXPECT_NE(refused.message().find("--pm-photons"), std::string::npos) << refused;
    // Against the device: each of the maps' three arrays is one buffer.
    const vk::GpuScene gpu_scene = *vk::BuildGpuScene(scene, emitters);
    vk::PixelJobData maps;
    maps.photon_positions.resize(40'000);
    maps.photon_powers.resize(40'000);  // 1.28 MB
    const vk::DeviceCapacity small{"small GPU", 1u << 20, 1u << 30};
    const absl::Status buffer = vk::CheckJobFits(small, gpu_scene, 0, &maps);
    EXPECT_TRUE(absl::IsResourceExhausted(buffer)) << buffer;
    EXPECT_NE(buffer.message().find("photon map powers (40000 photons stored)"), std::string::npos)
        << buffer;
    maps.photon_powers.resize(30'000);  // 0.96 MB: fits, as do the positions (0.64 MB)
    EXPECT_TRUE(vk::CheckJobFits(small, gpu_scene, 0, &maps).ok());
}

// The path tracer's two designs on the device (PHOTONFARM_VULKAN_PATH) run the same vertex
// code on the same numbers in the same order: a pixel's mean may differ only by the rounding of
// differently compiled pipelines (none at all on lavapipe). Two scenes queue every class of
// vertex: coats, rough gold mixed with paint, translucent paper (cornell-materials); a glass
// sphere under a sky that escaping paths find (sky-courtyard).
TEST_F(VulkanPixelTest, PathWavefrontTracesTheMegakernelsPaths) {
    for (const char* path : {"pbrt/cornell-materials.pbrt", "pbrt/sky-courtyard.pbrt"}) {
        SCOPED_TRACE(path);
        const Scene scene = *LoadScene(std::string(PF_SOURCE_DIR) + "/scenes/" + path);
        const Emitters emitters(scene);
        const JobSpec spec = SmallJob(Integrator::kPath);
        std::vector<BatchSpec> specs;
        std::vector<BatchResult> results[2];
        for (int design = 0; design < 2; ++design) {
            setenv("PHOTONFARM_VULKAN_PATH", design == 0 ? "megakernel" : "wavefront", 1);
            absl::StatusOr<std::unique_ptr<Backend>> vulkan = CreateBackend("vulkan", scene);
            unsetenv("PHOTONFARM_VULKAN_PATH");
            ASSERT_TRUE(vulkan.ok()) << vulkan.status();
            ASSERT_NO_FATAL_FAILURE(
                RunEpochs(**vulkan, scene, emitters, spec, specs, results[design]));
            EXPECT_EQ(static_cast<vk::VulkanBackend&>(**vulkan).RunsPathWavefront(), design == 1);
        }
        size_t pixels = 0, agreeing = 0;
        for (size_t b = 0; b < specs.size(); ++b) {
            const BatchResult &m = results[0][b], &w = results[1][b];
            ASSERT_EQ(w.samples.size(), m.samples.size());
            EXPECT_EQ(w.nonfinite_discarded, m.nonfinite_discarded);
            for (size_t p = 0; p < m.samples.size(); ++p, ++pixels)
                agreeing += MaxComponent(Abs(m.samples[p] - w.samples[p])) <=
                            1e-5f * std::max(1.0f, MaxComponent(m.samples[p]));
        }
        EXPECT_EQ(pixels, 2u * 24 * 24);
        EXPECT_GE(double(agreeing), 0.99 * double(pixels))
            << agreeing << " of " << pixels << " pixels agree to 1e-5";
    }
}

TEST(VulkanPathDesignTest, AnUnknownDesignIsRefusedNamingTheVariable) {
    setenv("PHOTONFARM_VULKAN_PATH", "wavefrnt", 1);
    const absl::StatusOr<vk::PathDesign> design = vk::PathDesignFromEnvironment();
    unsetenv("PHOTONFARM_VULKAN_PATH");
    EXPECT_TRUE(absl::IsInvalidArgument(design.status())) << design.status();
    EXPECT_EQ(design.status().message(),
              "PHOTONFARM_VULKAN_PATH=wavefrnt: expected megakernel or wavefront");
}

}  // namespace
}  // namespace pf
