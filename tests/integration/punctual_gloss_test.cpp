// Glossy surfaces under punctual lights: a point light's highlight on a rough coat, rough metal
// and rough glass, which no sampled direction finds and light sampling at the glossy vertex
// must (core/scene/glossy_lights.h). Before it, every integrator lost the highlight (a coat over
// black reflected nothing; pbrt-v4 0.0058 in the scene). Each scene shows one glossy
// surface over nothing (no other light comes back), lit by one point light, seen straight down
// by an orthographic camera: every pixel is the closed form f cos_i I / d^2, which the test
// computes itself from the BSDF's textbook form (Walter et al. 2007; the conductor's exact
// Fresnel term) and averages over the pixel, against every integrator on the CPU. A layered
// coat over a conductor has no closed form: every integrator against the path tracer there.
// The Vulkan kernels trace pm's and the path tracer's camera paths as the CPU does: pixel for
// pixel the CPU's images.
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

constexpr double kAlpha = 0.3, kEta = 1.5;
constexpr int kSize = 16;

// The scene: an orthographic camera straight down at the plane z = 0 over [-1, 1]^2, and
// `world` (lights, materials and shapes).
std::string Scene(const std::string& world) {
    return "LookAt 0 0 2  0 0 0  0 1 0\nCamera \"orthographic\" \"float screenwindow\" [-1 1 -1 "
           "1]\nPixelFilter \"box\"\nWorldBegin\n" +
           world;
}

constexpr char kPlane[] =
    "Shape \"trianglemesh\" \"point3 P\" [-2 -2 0  2 -2 0  2 2 0  -2 2 0] \"integer indices\" "
    "[0 1 2  0 2 3]\n";

// Unpolarised Fresnel reflectance of light arriving at cosine c from the side of index n_i.
double Fresnel(double c, double n_i, double n_t) {
    const double sin_t = n_i / n_t * std::sqrt(std::max(0.0, 1 - c * c));
    if (sin_t >= 1) return 1;
    const double cos_t = std::sqrt(1 - sin_t * sin_t);
    const double s = (n_i * c - n_t * cos_t) / (n_i * c + n_t * cos_t);
    const double p = (n_i * cos_t - n_t * c) / (n_i * cos_t + n_t * c);
    return (s * s + p * p) / 2;
}

// The same of a conductor of complex index n + i k, from vacuum (Born and Wolf's exact form, as
// Lagarde's "Memo on Fresnel equations" writes it).
double ConductorFresnel(double c, double n, double k) {
    const double sin_sq = 1 - c * c, t0 = n * n - k * k - sin_sq;
    const double a2b2 = std::sqrt(t0 * t0 + 4 * n * n * k * k), a = std::sqrt((a2b2 + t0) / 2);
    const double rs = (a2b2 - 2 * a * c + c * c) / (a2b2 + 2 * a * c + c * c);
    const double rp = rs * (c * c * a2b2 - 2 * a * c * sin_sq + sin_sq * sin_sq) /
                      (c * c * a2b2 + 2 * a * c * sin_sq + sin_sq * sin_sq);
    return (rs + rp) / 2;
}

// GGX: the distribution at a half vector of cosine c, and Smith's Lambda at cosine c.
double Ggx(double c) {
    const double a2 = kAlpha * kAlpha, t = c * c * (a2 - 1) + 1;
    return a2 / (M_PI * t * t);
}
double Lambda(double c) {
    const double tan_sq = (1 - c * c) / (c * c);
    return (std::sqrt(1 + kAlpha * kAlpha * tan_sq) - 1) / 2;
}

// What a surface at (x, y, 0) shows the camera (straight up, wo = +z) of a point light of
// intensity 1 at `light`: f(wo, wi) cos_i / d^2 for the surface `kind`.
enum class Surface { kCoatOverBlack, kRoughMetal, kRoughGlass };
constexpr double kMetalN = 0.9, kMetalK = 2.4;
double Highlight(Surface kind, const double light[3], double x, double y) {
    const double lx = light[0] - x, ly = light[1] - y, lz = light[2];
    const double distance_sq = lx * lx + ly * ly + lz * lz, distance = std::sqrt(distance_sq);
    const double wi[3] = {lx / distance, ly / distance, lz / distance};
    if (kind == Surface::kRoughGlass) {
        // The light below (inside, index kEta), the camera above (outside, 1): Walter et al.'s
        // eq. 21, the BTDF of radiance, with h = -(eta_i wi + eta_o wo) turned up.
        double h[3] = {-kEta * wi[0], -kEta * wi[1], -(kEta * wi[2] + 1)};
        const double length = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
        for (double& c : h) c /= length * (h[2] < 0 ? -1 : 1);
        const double cos_ih = wi[0] * h[0] + wi[1] * h[1] + wi[2] * h[2], cos_oh = h[2];
        if (!(cos_ih < 0 && cos_oh > 0)) return 0;
        const double g2 = 1 / (1 + Lambda(1.0) + Lambda(-wi[2]));
        const double denominator = kEta * cos_ih + cos_oh;
        const double f = std::abs(cos_ih) * cos_oh / std::abs(wi[2]) *
                         (1 - Fresnel(cos_oh, 1, kEta)) * g2 * Ggx(h[2]) /
                         (denominator * denominator);
        return f * std::abs(wi[2]) / distance_sq;
    }
    const double h[3] = {wi[0], wi[1], wi[2] + 1};
    const double cos_h = h[2] / std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    const double cos_oh = cos_h;  // wo = +z
    const double fresnel = kind == Surface::kRoughMetal ? ConductorFresnel(cos_oh, kMetalN, kMetalK)
                                                        : Fresnel(cos_oh, 1, kEta);
    const double g2 = 1 / (1 + Lambda(1.0) + Lambda(wi[2]));
    return fresnel * Ggx(cos_h) * g2 / 4 / distance_sq;  // f cos_i, cos_o = 1
}

// Each pixel's expected value: the highlight averaged over its square (box filter).
std::vector<double> ExpectedPixels(Surface kind, const double light[3]) {
    std::vector<double> pixels(kSize * kSize);
    constexpr int kSub = 16;
    for (int py = 0; py < kSize; ++py)
        for (int px = 0; px < kSize; ++px) {
            double sum = 0;
            for (int sy = 0; sy < kSub; ++sy)
                for (int sx = 0; sx < kSub; ++sx) {
                    // pbrt's camera space is left-handed: looking down -z with y up, the
                    // image's x runs along world -x.
                    const double x = 1 - 2 * (px + (sx + 0.5) / kSub) / kSize;
                    const double y = 1 - 2 * (py + (sy + 0.5) / kSub) / kSize;
                    sum += Highlight(kind, light, x, y);
                }
            pixels[py * kSize + px] = sum / (kSub * kSub);
        }
    return pixels;
}

RenderSettings GlossRender(const std::string& scene_path, Integrator integrator,
                           const std::string& backend) {
    RenderSettings settings;
    settings.scene_path = scene_path;
    settings.threads = 2;
    settings.backend = backend;
    JobSpec& job = settings.job;
    job.integrator = integrator;
    job.width = job.height = kSize;
    job.seed = 3;
    if (integrator == Integrator::kPm) {
        job.photon_map.global_photons = job.photon_map.caustic_photons = 20'000;
        job.epoch_budget = 8;
    } else if (integrator == Integrator::kPath) {
        job.epoch_budget = 8;
    } else {
        job.photon_budget = 1'000'000;
        job.layout = {1u << 15, 2};
    }
    return settings;
}

// The mean difference of the pixels in columns [first, end) from `expected` against its
// Student's t bound from their spread (the pixels draw independent numbers), and that the bound
// catches a 2% error.
void ExpectPixels(const Image& image, const std::vector<double>& expected, const std::string& what,
                  int first = 0, int end = kSize) {
    ASSERT_EQ(image.pixels.size(), expected.size());
    double sum = 0, sum_sq = 0, mean_expected = 0;
    const double n = double(kSize * (end - first));
    for (int y = 0; y < kSize; ++y)
        for (int x = first; x < end; ++x) {
            const size_t i = size_t(y) * kSize + x;
            const double difference = image.pixels[i].y - expected[i];
            sum += difference, sum_sq += difference * difference;
            mean_expected += expected[i] / n;
        }
    const double mean = sum / n;
    const double sigma = std::sqrt(std::max(0.0, (sum_sq / n - mean * mean) / (n - 1)));
    const double bound =
        testing::StudentTQuantile(testing::kFalseAlarm / 2, n - 1) * sigma + 1e-3 * mean_expected;
    std::printf("%s: mean %.6f, expected %.6f, bound %.6f\n", what.c_str(), mean + mean_expected,
                mean_expected, bound);
    EXPECT_NEAR(mean, 0.0, bound) << what;
    EXPECT_LT(bound, testing::kBiasToCatch * mean_expected) << what << ": a 2% error must not pass";
}

// The scene of `kind`: the surface, the light (above it; below rough glass, which lies at
// z = 0 with nothing under it).
std::string SurfaceScene(Surface kind, const double light[3]) {
    const std::string material =
        kind == Surface::kCoatOverBlack
            ? absl::StrCat("Material \"coateddiffuse\" \"rgb reflectance\" [0 0 0] \"float eta\" ",
                           kEta)
        : kind == Surface::kRoughMetal
            ? absl::StrCat("Material \"conductor\" \"float eta\" ", kMetalN, " \"float k\" ",
                           kMetalK)
            : absl::StrCat("Material \"dielectric\" \"float eta\" ", kEta);
    return Scene(absl::StrCat("LightSource \"point\" \"point3 from\" [", light[0], " ", light[1],
                              " ", light[2], "] \"rgb I\" [1 1 1]\n", material,
                              " \"float roughness\" ", kAlpha, " \"bool remaproughness\" false\n",
                              kPlane));
}

void ExpectClosedForm(Surface kind, const char* name) {
    const double above[3] = {0.3, 0.0, 1.0}, below[3] = {0.3, 0.0, -1.2};
    const double* light = kind == Surface::kRoughGlass ? below : above;
    const std::string scene =
        testing::WriteTextFile(SurfaceScene(kind, light), std::string(name) + ".pbrt");
    const std::vector<double> expected = ExpectedPixels(kind, light);
    for (const Integrator integrator : {Integrator::kPpm, Integrator::kSppm, Integrator::kRpm,
                                        Integrator::kPm, Integrator::kPath}) {
        const absl::StatusOr<RenderOutcome> outcome =
            RenderLocally(GlossRender(scene, integrator, "cpu"));
        ASSERT_TRUE(outcome.ok()) << outcome.status();
        ExpectPixels(outcome->image, expected,
                     std::string(name) + ", " + std::string(IntegratorName(integrator)));
    }
}

TEST(PunctualGloss, ARoughCoatOverBlackShowsAPointLightAsTheClosedForm) {
    ExpectClosedForm(Surface::kCoatOverBlack, "coat-over-black");
}

TEST(PunctualGloss, RoughMetalShowsAPointLightAsTheClosedForm) {
    ExpectClosedForm(Surface::kRoughMetal, "rough-metal");
}

TEST(PunctualGloss, RoughGlassShowsAPointLightBehindItAsTheClosedForm) {
    ExpectClosedForm(Surface::kRoughGlass, "rough-glass");
}

// A rough coat over rough copper (nsamples 4 walks an estimate): every integrator's image is the
// path tracer's, the same light sampling at the same vertex.
std::string CoatedConductor() {
    const double light[3] = {0.3, 0.0, 1.0};
    return Scene(absl::StrCat(
        "LightSource \"point\" \"point3 from\" [", light[0], " ", light[1], " ", light[2],
        "] \"rgb I\" [1 1 1]\nMaterial \"coatedconductor\" \"float interface.roughness\" 0.2 "
        "\"float conductor.roughness\" 0.3 \"bool remaproughness\" false \"integer nsamples\" 4\n",
        kPlane));
}

TEST(PunctualGloss, EveryIntegratorSeesACoatedConductorAsThePathTracer) {
    const std::string scene = testing::WriteTextFile(CoatedConductor(), "coated-conductor.pbrt");
    RenderSettings reference_settings = GlossRender(scene, Integrator::kPath, "cpu");
    reference_settings.job.epoch_budget = 64;
    const absl::StatusOr<RenderOutcome> reference = RenderLocally(reference_settings);
    ASSERT_TRUE(reference.ok()) << reference.status();
    std::vector<double> expected;
    for (const Rgb& pixel : reference->image.pixels) expected.push_back(pixel.y);
    for (const Integrator integrator :
         {Integrator::kPpm, Integrator::kSppm, Integrator::kRpm, Integrator::kPm}) {
        const absl::StatusOr<RenderOutcome> outcome =
            RenderLocally(GlossRender(scene, integrator, "cpu"));
        ASSERT_TRUE(outcome.ok()) << outcome.status();
        ExpectPixels(outcome->image, expected, std::string(IntegratorName(integrator)));
    }
}

// The Vulkan kernels trace pm's and the path tracer's camera paths as the CPU does, drawing the
// same numbers: pixel for pixel the CPU's image (but where device rounding flips a choice), of
// each surface above.
TEST(PunctualGloss, VulkanKernelsSeeTheHighlightsAsTheCpu) {
    testing::SkipWithoutVulkan();
    if (::testing::Test::IsSkipped() || ::testing::Test::HasFatalFailure()) return;
    const double above[3] = {0.3, 0.0, 1.0}, below[3] = {0.3, 0.0, -1.2};
    // All four surfaces side by side, each lit by its own light.
    const std::string scene = testing::WriteTextFile(
        Scene(absl::StrCat(
            "LightSource \"point\" \"point3 from\" [", above[0], " ", above[1], " ", above[2],
            "] \"rgb I\" [1 1 1]\nLightSource \"point\" \"point3 from\" [", below[0], " ", below[1],
            " ", below[2], "] \"rgb I\" [1 1 1]\n",
            "AttributeBegin\nMaterial \"coatedconductor\" \"float interface.roughness\" 0.2 "
            "\"float conductor.roughness\" 0.3\nShape \"trianglemesh\" \"point3 P\" [-1 -1 0  0 "
            "-1 0  0 0 0  -1 0 0] \"integer indices\" [0 1 2  0 2 3]\nAttributeEnd\n"
            "AttributeBegin\nMaterial \"coateddiffuse\" \"rgb reflectance\" [0 0 0] \"float "
            "roughness\" 0.3\nShape \"trianglemesh\" \"point3 P\" [0 -1 0  1 -1 0  1 0 0  0 0 0] "
            "\"integer indices\" [0 1 2  0 2 3]\nAttributeEnd\n"
            "AttributeBegin\nMaterial \"conductor\" \"float roughness\" 0.3\nShape "
            "\"trianglemesh\" \"point3 P\" [-1 0 0  0 0 0  0 1 0  -1 1 0] \"integer indices\" [0 1 "
            "2  0 2 3]\nAttributeEnd\n"
            "AttributeBegin\nMaterial \"dielectric\" \"float roughness\" 0.3\nShape "
            "\"trianglemesh\" \"point3 P\" [0 0 0.5  1 0 0.5  1 1 0.5  0 1 0.5] \"integer "
            "indices\" [0 1 2  0 2 3]\nAttributeEnd\n")),
        "glossy-quarters.pbrt");
    for (const Integrator integrator : {Integrator::kPm, Integrator::kPath}) {
        RenderSettings settings = GlossRender(scene, integrator, "cpu");
        settings.job.epoch_budget = 2;
        const absl::StatusOr<RenderOutcome> cpu = RenderLocally(settings);
        settings.backend = "vulkan";
        const absl::StatusOr<RenderOutcome> vulkan = RenderLocally(settings);
        ASSERT_TRUE(cpu.ok() && vulkan.ok()) << cpu.status() << vulkan.status();
        int differing = 0;
        double mean = 0;
        for (size_t i = 0; i < cpu->image.pixels.size(); ++i) {
            const Rgb a = cpu->image.pixels[i], b = vulkan->image.pixels[i];
            differing += MaxComponent(Abs(a - b)) > 1e-4f * std::max(1.0f, MaxComponent(a));
            mean += a.y;
        }
        EXPECT_LE(differing, 3) << IntegratorName(integrator);
        EXPECT_GT(mean, 0) << "highlights to compare";
    }
    EXPECT_EQ(testing::VulkanValidationErrors(), 0u);
}

}  // namespace
}  // namespace pf
