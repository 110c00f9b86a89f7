// A diffuse floor under a dielectric slab in a uniform sky, seen from above through the slab
// and from inside it: the closed form of radiance through one refraction (Veach 1997, section
// 5.2: L / eta^2 is what a ray keeps across an interface), against every integrator on the CPU
// and the pixel integrators on the Vulkan backend. Paths that go in and out of the slab cancel
// the factor eta^2; a floor seen through the slab does not, so a camera path that carried
// radiance like flux made it eta^2 too bright (3.24x at eta 1.8), and a path tracer's camera
// inside the slab eta^2 too dark.
//
// The slab: a smooth dielectric top face at z = 1 over a floor of albedo rho at z = 0, closed
// at its sides by mirrors, which make it the infinite slab exactly (by the slab's symmetry
// about each mirror). Under a sky of radiance L, with R_ext the cosine-weighted hemispherical
// reflectance of the top face from outside and R_int = 1 - (1 - R_ext) / eta^2 from inside
// (total internal reflection included; the two are related by reciprocity), the floor's
// irradiance E satisfies E = pi L (1 - R_ext) + rho R_int E, so its radiance (in the slab) is
//     L_floor = rho L (1 - R_ext) / (1 - rho R_int);
// seen from inside, straight down: L_floor; seen from above, straight down through the top:
//     F(0) L + (1 - F(0)) L_floor / eta^2, with F(0) = ((eta - 1) / (eta + 1))^2.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "absl/strings/str_cat.h"
#include "embedded/local_render.h"
#include "tests/support/gltf_builder.h"  // WriteTextFile
#include "tests/support/image_agreement.h"
#include "tests/support/vulkan_validation.h"

namespace pf {
namespace {

constexpr double kAlbedo = 0.5;

// Unpolarised Fresnel reflectance of light arriving at cos_i from the side of index n_i.
double Fresnel(double cos_i, double n_i, double n_t) {
    const double sin_t = n_i / n_t * std::sqrt(std::max(0.0, 1 - cos_i * cos_i));
    if (sin_t >= 1) return 1;
    const double cos_t = std::sqrt(1 - sin_t * sin_t);
    const double s = (n_i * cos_i - n_t * cos_t) / (n_i * cos_i + n_t * cos_t);
    const double p = (n_i * cos_t - n_t * cos_i) / (n_i * cos_t + n_t * cos_i);
    return (s * s + p * p) / 2;
}

// The cosine-weighted hemispherical reflectance from outside, 2 int F(mu) mu dmu (midpoint
// rule, far finer than any bound below).
double OutsideHemisphericalReflectance(double eta) {
    constexpr int kSteps = 100000;
    double sum = 0;
    for (int i = 0; i < kSteps; ++i) {
        const double mu = (i + 0.5) / kSteps;
        sum += Fresnel(mu, 1, eta) * 2 * mu / kSteps;
    }
    return sum;
}

double FloorRadiance(double eta) {
    const double outside = OutsideHemisphericalReflectance(eta);
    const double inside = 1 - (1 - outside) / (eta * eta);
    return kAlbedo * (1 - outside) / (1 - kAlbedo * inside);
}

double SeenThrough(double eta) {
    const double head_on = Fresnel(1, 1, eta);
    return head_on + (1 - head_on) * FloorRadiance(eta) / (eta * eta);
}

// The scene, the camera at height `camera_z` looking straight down at the slab: at all of it
// but a margin, so that no pixel's filter reaches past the mirrors to the sky. `reversed`
// writes the same slab from its other side: the top face turned over (its front toward the
// slab) with eta 1 / eta, the index of the air above against the slab's.
std::string SlabScene(double eta, double camera_z, bool reversed = false) {
    std::string scene = absl::StrCat(
        "LookAt 0 0 ", camera_z,
        "  0 0 -1  0 1 0\nCamera \"orthographic\" \"float screenwindow\" [-1.8 1.8 -1.8 1.8]\n"
        "WorldBegin\nLightSource \"infinite\" \"rgb L\" [1 1 1]\n"
        "AttributeBegin\n",
        reversed ? "ReverseOrientation\n" : "", "Material \"dielectric\" \"float eta\" ",
        reversed ? 1 / eta : eta,
        "\nShape \"trianglemesh\" \"point3 P\" [-2 -2 1  2 -2 1  2 2 1  -2 2 1] "
        "\"integer indices\" [0 1 2  0 2 3]\nAttributeEnd\n"
        "AttributeBegin\nMaterial \"conductor\" \"rgb reflectance\" [1 1 1]\n");
    for (const char* side : {"-2 -2 0  2 -2 0  2 -2 1  -2 -2 1", "-2 2 0  2 2 0  2 2 1  -2 2 1",
                             "-2 -2 0  -2 2 0  -2 2 1  -2 -2 1", "2 -2 0  2 2 0  2 2 1  2 -2 1"})
        absl::StrAppend(&scene, "Shape \"trianglemesh\" \"point3 P\" [", side,
                        "] \"integer indices\" [0 1 2  0 2 3]\n");
    return absl::StrCat(scene, "AttributeEnd\nMaterial \"diffuse\" \"rgb reflectance\" [", kAlbedo,
                        " ", kAlbedo, " ", kAlbedo,
                        "]\nShape \"trianglemesh\" \"point3 P\" [-2 -2 0  2 -2 0  2 2 0  -2 2 0] "
                        "\"integer indices\" [0 1 2  0 2 3]\n");
}

struct View {
    const char* name;
    double camera_z;
    double (*expected)(double eta);
};
constexpr View kThrough{"through the top", 3.0, SeenThrough};
constexpr View kInside{"from inside", 0.5, FloorRadiance};

// The image's mean (green) with a bound from its 8x8 blocks' means: the field is uniform, so
// the blocks are draws of one mean, nearly independent (a photon's gather radius is half a
// block); Student's t over 63 degrees of freedom at the suite's false-alarm rate.
struct Measured {
    double mean = 0, bound = 0;
};
Measured MeasureBlocks(const Image& image) {
    constexpr int kBlock = 4;  // pixels across: about 2 gather radii
    const int across = image.width / kBlock;
    const int blocks = across * across;
    double sum = 0, sum_sq = 0;
    for (int by = 0; by < across; ++by)
        for (int bx = 0; bx < across; ++bx) {
            double mean = 0;
            for (int y = by * kBlock; y < (by + 1) * kBlock; ++y)
                for (int x = bx * kBlock; x < (bx + 1) * kBlock; ++x)
                    mean += image.pixels[size_t(y) * image.width + x].y;
            mean /= double(kBlock * kBlock);
            sum += mean, sum_sq += mean * mean;
        }
    const double mean = sum / blocks;
    const double spread = std::sqrt(std::max(0.0, (sum_sq - blocks * mean * mean) / (blocks - 1)));
    return {mean, testing::StudentTQuantile(testing::kFalseAlarm / 2, blocks - 1) * spread /
                      std::sqrt(double(blocks))};
}

// A render of the slab at 32x32, with budgets that catch a 2% error.
RenderSettings SlabRender(Integrator integrator, double eta, const View& view,
                          const std::string& backend, bool reversed = false) {
    RenderSettings settings;
    settings.scene_path = testing::WriteTextFile(
        SlabScene(eta, view.camera_z, reversed),
        absl::StrCat("slab-", eta, "-", view.camera_z, reversed ? "-reversed" : "", ".pbrt"));
    settings.threads = 2;
    settings.backend = backend;
    JobSpec& job = settings.job;
    job.integrator = integrator;
    job.width = job.height = 32;
    job.seed = 11;
    switch (integrator) {
        case Integrator::kPpm:
        case Integrator::kSppm:
            // The field is uniform: a wide radius that does not shrink gathers many photons
            // and adds no bias. sppm's camera samples choose the top's reflection or refraction
            // at random: more of them.
            job.photon_budget = 2'000'000;
            job.layout = {1u << 17, 4};
            job.initial_radius = 0.2;
            job.alpha = 1;
            if (integrator == Integrator::kSppm) job.samples_per_pixel = 16;
            break;
        case Integrator::kRpm:  // its radii from the k nearest photons of a pilot map
            job.photon_budget = 2'000'000;
            job.layout = {1u << 17, 4};
            job.photon_map.nearest = 256;
            job.samples_per_pixel = 16;
            break;
        case Integrator::kPm:
            job.photon_map.global_photons = 400'000;
            job.photon_map.caustic_photons = 400'000;
            job.samples_per_pixel = 8;
            job.epoch_budget = 12;
            break;
        case Integrator::kPath:
            job.epoch_budget = 64;
            break;
    }
    return settings;
}

void ExpectClosedForm(Integrator integrator, double eta, const View& view,
                      const std::string& backend = "cpu", bool reversed = false) {
    const absl::StatusOr<RenderOutcome> outcome =
        RenderLocally(SlabRender(integrator, eta, view, backend, reversed));
    ASSERT_TRUE(outcome.ok()) << outcome.status();
    const Measured measured = MeasureBlocks(outcome->image);
    const double expected = view.expected(eta);
    const std::string what = std::string(IntegratorName(integrator)) + " on " + backend + ", eta " +
                             std::to_string(eta) + (reversed ? " (as 1 / eta reversed)" : "") +
                             ", " + view.name;
    std::printf("%s: %.5f (closed form %.5f, bound %.5f)\n", what.c_str(), measured.mean, expected,
                measured.bound);
    // Beyond the noise: 0.2% for the closed form's quadrature and the mirrors' 0.9999; rpm's
    // gather hits read 0.6% low here, seen from inside as from above (a bias of its own, which
    // no refraction of a camera path enters), so its bound is wider and must still catch 3%.
    const bool rpm = integrator == Integrator::kRpm;
    const double allowed = measured.bound + (rpm ? 8e-3 : 2e-3) * expected;
    EXPECT_NEAR(measured.mean, expected, allowed) << what;
    const double catchable = rpm ? 0.03 : testing::kBiasToCatch;
    EXPECT_LT(allowed, catchable * expected)
        << what << ": an error of " << catchable * 100 << "% must not pass";
}

TEST(Refraction, EveryIntegratorSeesAFloorThroughASlabAsTheClosedForm) {
    for (const double eta : {1.33, 1.8})
        for (const Integrator integrator : {Integrator::kPpm, Integrator::kSppm, Integrator::kRpm,
                                            Integrator::kPm, Integrator::kPath})
            ExpectClosedForm(integrator, eta, kThrough);
}

TEST(Refraction, EveryIntegratorSeesTheFloorFromInsideTheSlabAsTheClosedForm) {
    for (const double eta : {1.33, 1.8})
        for (const Integrator integrator : {Integrator::kPpm, Integrator::kSppm, Integrator::kRpm,
                                            Integrator::kPm, Integrator::kPath})
            ExpectClosedForm(integrator, eta, kInside);
}

// pbrt-v4's eta below 1 (glass-of-water's water against its glass): the interface whose front
// side is the denser one. The slab written with its top turned over and eta 1 / 1.5 is the slab
// of eta 1.5: the same closed form, from above (Fresnel from the air, the eta^2 of radiance
// going in) and from inside (total internal reflection from the slab's side, the eta^2 coming
// out), for the path tracer and ppm.
TEST(Refraction, AnEtaBelowOneIsTheInterfaceSeenFromItsOtherSide) {
    for (const Integrator integrator : {Integrator::kPpm, Integrator::kPath}) {
        ExpectClosedForm(integrator, 1.5, kThrough, "cpu", true);
        ExpectClosedForm(integrator, 1.5, kInside, "cpu", true);
    }
}

// A glass of tea, seen straight down through its stack of interfaces onto a lamp below: air,
// tea (absorbing, 1 deep), glass (0.5 deep), air. The tea is bounded by its surface, with the tea
// inside (MediumInterface "tea" ""), and by the glass's inner surface, with the tea outside
// (MediumInterface "" "tea", normals into the glass, index 1.5 / 1.33), as Bitterli's teapot
// declares it. Head-on, the interfaces reflect R = ((n1 - n2) / (n1 + n2))^2 and the tea keeps
// a = exp(-sigma_a d) a crossing; between two parts of a stack light bounces back and forth, so
// a stack of part X over part Y (through a layer of transmittance a) transmits
// T_X a T_Y / (1 - R'_X a^2 R_Y) (incoherent light: intensities add). The eta^2 of each
// refraction cancels, lamp and camera both in air.
struct StackPart {
    double r_above, r_below, t;
};
StackPart Interface(double n1, double n2) {
    const double r = (n1 - n2) * (n1 - n2) / ((n1 + n2) * (n1 + n2));
    return {r, r, 1 - r};
}
StackPart Stack(const StackPart& x, double a, const StackPart& y) {
    const double bounces = 1 / (1 - x.r_below * a * a * y.r_above);
    return {x.r_above + x.t * x.t * a * a * y.r_above * bounces,
            y.r_below + y.t * y.t * a * a * x.r_below * bounces, x.t * a * y.t * bounces};
}

std::string TeaScene() {
    const auto plane = [](double z, bool up) {
        return absl::StrCat("Shape \"trianglemesh\" \"point3 P\" [-20 -20 ", z, "  20 -20 ", z,
                            "  20 20 ", z, "  -20 20 ", z, "] \"integer indices\" ",
                            up ? "[0 1 2  0 2 3]" : "[0 2 1  0 3 2]", "\n");
    };
    return absl::StrCat(
        "LookAt 0 0 3  0 0 0  0 1 0\nCamera \"orthographic\" \"float screenwindow\" [-0.5 0.5 "
        "-0.5 0.5]\nPixelFilter \"box\"\nWorldBegin\n"
        "MakeNamedMedium \"tea\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [0.5 0.5 0.5] "
        "\"rgb sigma_s\" [0 0 0]\n"
        "AttributeBegin\nMediumInterface \"tea\" \"\"\nMaterial \"dielectric\" \"float eta\" "
        "1.33\n",
        plane(1.5, true),
        "AttributeEnd\nAttributeBegin\nMediumInterface \"\" \"tea\"\nMaterial \"dielectric\" "
        "\"float eta\" ",
        1.5 / 1.33, "\n", plane(0.5, true),
        "AttributeEnd\nMaterial \"dielectric\" \"float eta\" 1.5\n", plane(0, false),
        "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 1]\nMaterial \"diffuse\" "
        "\"rgb reflectance\" [0 0 0]\n",
        plane(-1, true), "AttributeEnd\n");
}

double TeaClosedForm() {
    const StackPart tea = Stack(Interface(1, 1.33), std::exp(-0.5), Interface(1.33, 1.5));
    return Stack(tea, 1.0, Interface(1.5, 1)).t;
}

// Renders `scene` (a uniform field) with each of `integrators` and expects `expected` within
// its blocks' bound, a bound that must catch a 2% error.
void ExpectUniformClosedForm(const std::string& name, const std::string& scene, double expected,
                             std::initializer_list<Integrator> integrators, uint64_t photons,
                             uint32_t epochs, uint64_t seed) {
    for (const Integrator integrator : integrators) {
        RenderSettings settings;
        settings.scene_path = scene;
        settings.threads = 2;
        settings.job.integrator = integrator;
        settings.job.width = settings.job.height = 16;
        settings.job.seed = seed;
        if (integrator == Integrator::kPath)
            settings.job.epoch_budget = epochs;
        else
            settings.job.photon_budget = photons, settings.job.layout = {1u << 15, 2};
        const absl::StatusOr<RenderOutcome> outcome = RenderLocally(settings);
        ASSERT_TRUE(outcome.ok()) << outcome.status();
        const Measured measured = MeasureBlocks(outcome->image);
        std::printf("%s, %s: %.5f (closed form %.5f, bound %.5f)\n", name.c_str(),
                    std::string(IntegratorName(integrator)).c_str(), measured.mean, expected,
                    measured.bound);
        const double allowed = measured.bound + 2e-3 * expected;
        EXPECT_NEAR(measured.mean, expected, allowed) << IntegratorName(integrator);
        EXPECT_LT(allowed, testing::kBiasToCatch * expected) << "a 2% error must not pass";
    }
}

TEST(Refraction, ATeaOutsideItsGlassAbsorbs) {
    ExpectUniformClosedForm("tea", testing::WriteTextFile(TeaScene(), "tea.pbrt"), TeaClosedForm(),
                            {Integrator::kPpm, Integrator::kPath}, 200'000, 32, 9);
}

// Fog in a scene of nothing but diffuse surfaces: a lamp of radiance Le facing up at z = 0,
// its front in an absorbing medium (MediumInterface "" "fog"), seen straight down from z = 3:
// the camera's segment ends on the lamp's front and keeps exp(-3 sigma) of Le. The passes'
// diffuse-only variants must take media too (they once skipped them: Le itself). Light
// sampled from a surface in a medium is not attenuated yet (docs/scenes.md): no diffuse
// surface here is lit.
TEST(Refraction, FogInADiffuseSceneAbsorbsInEveryIntegrator) {
    constexpr double kSigma = 0.5;
    const std::string scene = testing::WriteTextFile(
        absl::StrCat("LookAt 0 0 3  0 0 0  0 1 0\nCamera \"orthographic\" \"float screenwindow\" "
                     "[-0.5 0.5 -0.5 0.5]\nPixelFilter \"box\"\nWorldBegin\n"
                     "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [",
                     kSigma, " ", kSigma, " ", kSigma,
                     "] \"rgb sigma_s\" [0 0 0]\n"
                     "AttributeBegin\nMediumInterface \"\" \"fog\"\nAreaLightSource \"diffuse\" "
                     "\"rgb L\" [1 1 1]\nMaterial \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]\n"
                     "Shape \"trianglemesh\" \"point3 P\" [-2 -2 0  2 -2 0  2 2 0  -2 2 0] "
                     "\"integer indices\" [0 1 2  0 2 3]\nAttributeEnd\n"),
        "fog.pbrt");
    ExpectUniformClosedForm("fog", scene, std::exp(-3 * kSigma),
                            {Integrator::kPpm, Integrator::kSppm, Integrator::kPath}, 100'000, 4,
                            11);
}

// The Vulkan kernels trace the camera paths of pm and the path tracer as the CPU does, drawing
// the same numbers in the same order: their images match the CPU's pixel for pixel (but where
// the device's float rounding flips a random choice, a few pixels in a thousand at most), so
// the CPU's closed form above holds them, radiance into the slab (pm from above) and out of it
// (the path tracer from inside). ppm's photons, on the device from streams of its own, are held
// to the closed form themselves. A render costs lavapipe's pipelines seconds to build: few.
TEST(Refraction, VulkanKernelsSeeTheClosedForm) {
    testing::SkipWithoutVulkan();
    if (::testing::Test::IsSkipped() || ::testing::Test::HasFatalFailure()) return;
    const auto same_pixels = [](Integrator integrator, const View& view) {
        RenderSettings settings = SlabRender(integrator, 1.8, view, "cpu");
        settings.job.width = settings.job.height = 16;
        settings.job.epoch_budget = 2;
        const absl::StatusOr<RenderOutcome> cpu = RenderLocally(settings);
        settings.backend = "vulkan";
        const absl::StatusOr<RenderOutcome> vulkan = RenderLocally(settings);
        ASSERT_TRUE(cpu.ok() && vulkan.ok()) << cpu.status() << vulkan.status();
        ASSERT_EQ(cpu->image.pixels.size(), vulkan->image.pixels.size());
        int differing = 0;
        double mean = 0;
        for (size_t i = 0; i < cpu->image.pixels.size(); ++i) {
            const Rgb a = cpu->image.pixels[i], b = vulkan->image.pixels[i];
            differing += MaxComponent(Abs(a - b)) > 1e-4f * std::max(1.0f, MaxComponent(a));
            mean += a.y / double(cpu->image.pixels.size());
        }
        EXPECT_LE(differing, 3) << IntegratorName(integrator) << ", " << view.name;
        EXPECT_GT(mean, 0.1 * view.expected(1.8)) << "something to compare";
    };
    same_pixels(Integrator::kPm, kThrough);
    same_pixels(Integrator::kPath, kInside);
    {  // the tea outside its glass
        RenderSettings settings;
        settings.scene_path = testing::WriteTextFile(TeaScene(), "tea.pbrt");
        settings.threads = 2;
        settings.job.integrator = Integrator::kPath;
        settings.job.width = settings.job.height = 8;
        settings.job.seed = 9;
        settings.job.epoch_budget = 2;
        const absl::StatusOr<RenderOutcome> cpu = RenderLocally(settings);
        settings.backend = "vulkan";
        const absl::StatusOr<RenderOutcome> vulkan = RenderLocally(settings);
        ASSERT_TRUE(cpu.ok() && vulkan.ok()) << cpu.status() << vulkan.status();
        int differing = 0;
        for (size_t i = 0; i < cpu->image.pixels.size(); ++i)
            differing += MaxComponent(Abs(cpu->image.pixels[i] - vulkan->image.pixels[i])) >
                         1e-4f * std::max(1.0f, MaxComponent(cpu->image.pixels[i]));
        EXPECT_LE(differing, 1) << "the tea outside its glass";
    }
    ExpectClosedForm(Integrator::kPpm, 1.8, kThrough, "vulkan");
    EXPECT_EQ(testing::VulkanValidationErrors(), 0u);
}

}  // namespace
}  // namespace pf
