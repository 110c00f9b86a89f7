// The environment light through every integrator, against the analytic answer: a convex
// diffuse body of albedo rho under a uniform environment of radiance L reflects exactly rho L
// everywhere (it sees only the sky, which gives irradiance pi L, and never itself), and the
// sky seen past it is L exactly. Each channel differs, so a channel swap shows; each check is
// also run on the image made 2% brighter, darker and greener, and must fail.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "absl/strings/str_format.h"
#include "core/geometry/tracer.h"
#include "core/job/integrator.h"
#include "core/scene_io/pbrt/pbrt_parameters.h"
#include "core/scene_io/scene_loader.h"
#include "core/shared/coat.h"
#include "core/shared/conductor.h"
#include "core/shared/path_sampling.h"
#include "embedded/local_render.h"
#include "embree/embree_tracer.h"
#include "tests/support/gltf_builder.h"

namespace pf {
namespace {

constexpr int kSize = 64;
constexpr float kAlbedo = 0.6f;
const Rgb kSky(1.0f, 0.5f, 0.25f);

// A unit cube turned so that the camera on +z sees three of its faces.
testing::TestScene TurnedCube() {
    const auto turn = [](Vec3 p) {
        const float a = 0.6f, b = 0.5f;  // about y, then about x
        p = {p.x * std::cos(a) + p.z * std::sin(a), p.y, -p.x * std::sin(a) + p.z * std::cos(a)};
        return Vec3{p.x, p.y * std::cos(b) - p.z * std::sin(b),
                    p.y * std::sin(b) + p.z * std::cos(b)};
    };
    testing::TestScene scene;
    scene.materials = {testing::TestMaterial{Rgb(kAlbedo)}};
    scene.camera_position = Vec3(0, 0, 2.6f);
    testing::TestMesh mesh;
    // Each face as two triangles wound counter-clockwise seen from outside.
    for (int axis = 0; axis < 3; ++axis)
        for (float side : {-0.5f, 0.5f}) {
            const auto corner = [&](float u, float v) {
                Vec3 p;
                p[axis] = side;
                p[(axis + 1) % 3] = side > 0 ? u : v;
                p[(axis + 2) % 3] = side > 0 ? v : u;
                return turn(p);
            };
            for (const Vec3& p : {corner(-0.5f, -0.5f), corner(0.5f, -0.5f), corner(0.5f, 0.5f),
                                  corner(-0.5f, -0.5f), corner(0.5f, 0.5f), corner(-0.5f, 0.5f)})
                mesh.positions.push_back(p);
        }
    scene.meshes = {mesh};
    return scene;
}

// Which pixels see only the body (all four corners' rays hit it: the body is convex) and
// which only the sky (no corner of it or of its eight neighbours hits).
struct PixelClasses {
    std::vector<bool> body, sky;
};
PixelClasses Classify(const Scene& scene) {
    const absl::StatusOr<std::unique_ptr<embree::EmbreeTracer>> tracer =
        embree::EmbreeTracer::Create(scene);
    EXPECT_TRUE(tracer.ok()) << tracer.status();
    std::vector<bool> corner_hits((kSize + 1) * (kSize + 1));
    for (int y = 0; y <= kSize; ++y)
        for (int x = 0; x <= kSize; ++x) {
            RayHit hit;
            corner_hits[y * (kSize + 1) + x] = (*tracer)->Intersect(
                scene.camera.GenerateRay(float(x) / kSize, float(y) / kSize, 1.0f), &hit);
        }
    const auto corner = [&](int x, int y) {
        return x >= 0 && y >= 0 && x <= kSize && y <= kSize && corner_hits[y * (kSize + 1) + x];
    };
    PixelClasses classes{std::vector<bool>(kSize * kSize), std::vector<bool>(kSize * kSize)};
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            classes.body[y * kSize + x] =
                corner(x, y) && corner(x + 1, y) && corner(x, y + 1) && corner(x + 1, y + 1);
            bool any = false;
            for (int dy = -1; dy <= 2; ++dy)
                for (int dx = -1; dx <= 2; ++dx) any |= corner(x + dx, y + dy);
            classes.sky[y * kSize + x] = !any;
        }
    return classes;
}

// The body's pixels' mean per channel against rho L, by a z-test on their spread (every
// integrator's body pixels are independent here: no photon is ever stored on a convex body,
// its light is all direct), and the sky's pixels against L to float rounding.
struct FurnaceResult {
    bool passed = true;
    double worst_z = 0, detectable = 0;  // detectable: 5 standard errors, relative
    std::string text;
};
// `scale` multiplies the body's pixels: a bias the check must catch.
FurnaceResult Check(const Image& image, const PixelClasses& classes, Rgb scale = Rgb(1.0f)) {
    FurnaceResult result;
    Rgbd sum(0.0), sum_sq(0.0);
    double count = 0;
    for (int i = 0; i < kSize * kSize; ++i) {
        const Rgb pixel = classes.body[i] ? image.pixels[i] * scale : image.pixels[i];
        if (classes.sky[i]) {
            for (int c = 0; c < 3; ++c)
                if (!(std::abs(pixel[c] - kSky[c]) <= 1e-5f * kSky[c])) result.passed = false;
        }
        if (!classes.body[i]) continue;
        sum += Rgbd(pixel), sum_sq += Rgbd(pixel) * Rgbd(pixel), count += 1;
    }
    for (int c = 0; c < 3; ++c) {
        const double mean = sum[c] / count;
        const double error = std::sqrt((sum_sq[c] / count - mean * mean) / (count - 1));
        const double expected = kAlbedo * kSky[c];
        const double z = (mean - expected) / error;
        result.worst_z = std::max(result.worst_z, std::abs(z));
        result.detectable = std::max(result.detectable, 5 * error / expected);
        result.passed &= std::abs(z) <= 5;
        result.text +=
            absl::StrFormat("%c %.5f (expected %.5f, z %.2f) ", "RGB"[c], mean, expected, z);
    }
    result.text += absl::StrFormat("over %d body pixels", int(count));
    return result;
}

// Every integrator, each test named after it.
auto EveryIntegrator() {
    return ::testing::Values(Integrator::kPpm, Integrator::kSppm, Integrator::kPm,
                             Integrator::kPath);
}
std::string IntegratorParamName(const ::testing::TestParamInfo<Integrator>& info) {
    return std::string(IntegratorName(info.param));
}

class EnvironmentFurnace : public ::testing::TestWithParam<Integrator> {};

TEST_P(EnvironmentFurnace, ConvexBodyReflectsAlbedoTimesTheSky) {
    RenderSettings settings;
    settings.scene_path = testing::WriteGltf(TurnedCube(), "environment-cube.gltf");
    settings.threads = 2;
    JobSpec& job = settings.job;
    job.integrator = GetParam();
    job.width = job.height = kSize;
    job.seed = 3;
    job.environment.color = kSky;
    // Photons carry nothing here (all light is direct): small batches, many epochs of camera
    // and light samples.
    job.layout = {1u << 12, 2};
    job.epoch_budget = 64;
    job.photon_map.global_photons = job.photon_map.caustic_photons = 1u << 16;
    const absl::StatusOr<RenderOutcome> outcome = RenderLocally(settings);
    ASSERT_TRUE(outcome.ok()) << outcome.status();
    EXPECT_NE(outcome->scene_features.find("environment light"), std::string::npos);

    SceneLoadOptions options;
    options.environment.color = kSky;
    const absl::StatusOr<Scene> scene = LoadScene(settings.scene_path, options);
    ASSERT_TRUE(scene.ok()) << scene.status();
    const PixelClasses classes = Classify(*scene);
    int body = 0, sky = 0;
    for (int i = 0; i < kSize * kSize; ++i) body += classes.body[i], sky += classes.sky[i];
    ASSERT_GE(body, 800);
    ASSERT_GE(sky, 800);

    const FurnaceResult result = Check(outcome->image, classes);
    std::printf("%s: %s, 2%% off detectable: %.2f%%\n",
                std::string(IntegratorName(GetParam())).c_str(), result.text.c_str(),
                100 * result.detectable);
    EXPECT_TRUE(result.passed) << result.text;
    // 5 standard errors must be well under 2%, so that a 2% bias fails.
    EXPECT_LT(result.detectable, 0.01);
    for (const Rgb& bias : {Rgb(1.02f), Rgb(0.98f), Rgb(1.0f, 1.02f, 1.0f)}) {
        const FurnaceResult biased = Check(outcome->image, classes, bias);
        EXPECT_FALSE(biased.passed) << "a biased image passed: " << biased.text;
    }
}

INSTANTIATE_TEST_SUITE_P(Integrators, EnvironmentFurnace, EveryIntegrator(), IntegratorParamName);

// The same cube under a smooth coat of index 1.5 and optical thickness 0.05 over the albedo
// (pbrt-v4's coateddiffuse), written as a pbrt file. A convex body under a uniform sky L
// reflects L A(mu) toward a viewer at cosine mu, A the surface's directional albedo
// (reciprocity): for a smooth coat the closed form of the layer, F(mu) + (1 - F(mu)) T(mu_t)
// rho E / (1 - rho R) (tests/core/scene/coat_test.cpp checks the walk against it). Light under
// the coat turned back to the base is stored by the photon mappers, so pixels are not
// independent: the z-test runs on 4x4 blocks of the ratio to the expected value.
constexpr float kCoatIor = 1.5f, kCoatThickness = 0.05f;

double CoatedAlbedo(double mu) {
    const auto integrate = [](auto&& f) {
        constexpr int kSteps = 4000;
        double sum = 0;
        for (int i = 0; i < kSteps; ++i) sum += f((i + 0.5) / kSteps);
        return sum / kSteps;
    };
    // Both hemisphere integrals are constants: computed once, not at each of the cube's rays.
    static const double escape = integrate([](double m) {
        return 2 * m * std::exp(-kCoatThickness / m) * (1 - gpu::FresnelDielectric(m, kCoatIor));
    });
    static const double turned_back = integrate([](double m) {
        return 2 * m * std::exp(-2 * kCoatThickness / m) * gpu::FresnelDielectric(m, kCoatIor);
    });
    const double fresnel = gpu::FresnelDielectric(mu, 1 / kCoatIor);
    const double mu_t = std::sqrt(1 - (1 - mu * mu) / (kCoatIor * kCoatIor));
    return fresnel + (1 - fresnel) * std::exp(-kCoatThickness / mu_t) * kAlbedo * escape /
                         (1 - kAlbedo * turned_back);
}

// The turned cube as a pbrt file under the sky, of the material `material` (its directives); a
// box pixel filter, as the expected images integrate each pixel's square.
std::string CubePbrt(const std::string& material) {
    std::string text = absl::StrFormat(
        "LookAt 0 0 2.6  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 45\n"
        "Film \"rgb\" \"integer xresolution\" %d \"integer yresolution\" %d\n"
        "PixelFilter \"box\"\nWorldBegin\n"
        "LightSource \"infinite\" \"rgb L\" [%g %g %g]\n",
        kSize, kSize, kSky.x, kSky.y, kSky.z);
    text += material + "Shape \"trianglemesh\" \"point3 P\" [";
    const testing::TestScene cube = TurnedCube();
    const testing::TestMesh& mesh = cube.meshes[0];
    for (const Vec3& p : mesh.positions) text += absl::StrFormat(" %g %g %g", p.x, p.y, p.z);
    text += " ] \"integer indices\" [";
    for (size_t i = 0; i < mesh.positions.size(); ++i) text += absl::StrFormat(" %d", int(i));
    return text + " ]\n";
}

// The body's pixels against sky x expected[pixel] (times `scale`, a bias to catch), by
// z-tests of the mean ratio per channel over 4x4 blocks wholly on the body: where photons are
// stored on the body or each point is one of two materials, pixels are not independent, blocks
// nearly are. Passes within 5 sigma and when 5 sigma is under 1.5%.
bool BlockRatioCheck(const Image& image, const PixelClasses& classes,
                     const std::vector<Rgbd>& expected, const Rgb& scale, std::string* text) {
    bool passed = true;
    double detectable = 0;
    for (int c = 0; c < 3; ++c) {
        std::vector<double> blocks;
        for (int by = 0; by < kSize; by += 4)
            for (int bx = 0; bx < kSize; bx += 4) {
                double sum = 0;
                int n = 0;
                for (int y = by; y < by + 4; ++y)
                    for (int x = bx; x < bx + 4; ++x) {
                        const int i = y * kSize + x;
                        if (!classes.body[i]) continue;
                        sum += image.pixels[i][c] * scale[c] / (kSky[c] * expected[i][c]);
                        ++n;
                    }
                if (n == 16) blocks.push_back(sum / n);
            }
        double mean = 0, var = 0;
        for (double b : blocks) mean += b / blocks.size();
        for (double b : blocks) var += (b - mean) * (b - mean) / (blocks.size() - 1);
        const double error = std::sqrt(var / blocks.size());
        const double z = (mean - 1) / error;
        passed &= std::abs(z) <= 5 && blocks.size() >= 30;
        detectable = std::max(detectable, 5 * error);
        *text += absl::StrFormat("%c ratio %.4f (z %.2f, %zu blocks) ", "RGB"[c], mean, z,
                                 blocks.size());
    }
    *text += absl::StrFormat("2%% off detectable: %.2f%%", 100 * detectable);
    return passed && detectable < 0.015;
}

// Renders the cube of scene file `scene_path` (under its own sky; or glTF, which has none,
// under the job's) by `integrator` and checks its pixels against sky x expected(mu) (mu the
// cosine at which the camera sees the face, averaged over 32x32 rays across each pixel), as
// BlockRatioCheck, and that the check fails 2% off. Per channel: expected(mu) is a colour.
// What the camera should see along a ray that meets the cube at `hit`, over the sky's radiance.
// `map_photons`: pm's photons a map, more where its maps' noise shows; `ppm_samples`: ppm's hit
// points a pixel, more where what its fixed camera paths choose shows.
using Expectation = std::function<Rgbd(const Scene&, const Tracer&, const Ray&, const RayHit&)>;
void ExpectCubeShows(const std::string& scene_path, Integrator integrator,
                     const std::string& feature, const Expectation& shows,
                     uint64_t map_photons = 1u << 19, uint32_t ppm_samples = 32) {
    RenderSettings settings;
    settings.scene_path = scene_path;
    settings.threads = 2;
    JobSpec& job = settings.job;
    SceneLoadOptions options;
    if (scene_path.ends_with(".gltf")) job.environment.color = options.environment.color = kSky;
    job.integrator = integrator;
    job.width = job.height = kSize;
    job.seed = 3;
    job.layout = {1u << 15, 2};
    job.epoch_budget = 48;
    job.photon_map.global_photons = job.photon_map.caustic_photons = map_photons;
    // ppm's hit points are fixed: where a point is one of two materials, each keeps its choice
    // for the whole render, so only more of them average it.
    if (integrator == Integrator::kPpm) job.samples_per_pixel = ppm_samples;
    const absl::StatusOr<RenderOutcome> outcome = RenderLocally(settings);
    ASSERT_TRUE(outcome.ok()) << outcome.status();
    EXPECT_NE(outcome->scene_features.find(feature), std::string::npos);
    const absl::StatusOr<Scene> scene = LoadScene(settings.scene_path, options);
    ASSERT_TRUE(scene.ok()) << scene.status();
    const PixelClasses classes = Classify(*scene);
    const absl::StatusOr<std::unique_ptr<embree::EmbreeTracer>> tracer =
        embree::EmbreeTracer::Create(*scene);
    ASSERT_TRUE(tracer.ok()) << tracer.status();
    std::vector<Rgbd> expected(kSize * kSize, Rgbd(0.0));
    for (int i = 0; i < kSize * kSize; ++i) {
        if (!classes.body[i]) continue;
        // 32 x 32 rays: the renders' stratified samples integrate the pixel more closely than
        // 8 x 8 would (their blocks then differ from it by 5 to 10 of their sigmas).
        constexpr int kRays = 32;
        for (int s = 0; s < kRays * kRays; ++s) {
            const Ray ray =
                scene->camera.GenerateRay((i % kSize + (s % kRays + 0.5f) / kRays) / kSize,
                                          (i / kSize + (s / kRays + 0.5f) / kRays) / kSize, 1.0f);
            RayHit hit;
            ASSERT_TRUE((*tracer)->Intersect(ray, &hit));
            expected[i] += shows(*scene, **tracer, ray, hit) / double(kRays * kRays);
        }
    }
    std::string text;
    EXPECT_TRUE(BlockRatioCheck(outcome->image, classes, expected, Rgb(1.0f), &text)) << text;
    std::printf("%s: %s\n", std::string(IntegratorName(integrator)).c_str(), text.c_str());
    for (const Rgb& bias : {Rgb(1.02f), Rgb(0.98f), Rgb(1.0f, 1.02f, 1.0f)}) {
        std::string biased;
        EXPECT_FALSE(BlockRatioCheck(outcome->image, classes, expected, bias, &biased))
            << "a biased image passed: " << biased;
    }
}

void ExpectCubeReflectsRgb(const std::string& scene_path, Integrator integrator,
                           const std::string& feature, const std::function<Rgbd(double)>& reflects,
                           uint64_t map_photons = 1u << 19, uint32_t ppm_samples = 32) {
    ExpectCubeShows(
        scene_path, integrator, feature,
        [&](const Scene& scene, const Tracer&, const Ray& ray, const RayHit& hit) {
            const Vec3 n = scene.Surface(hit).geometric_normal;
            return reflects(std::abs(Dot(ray.direction, n)));
        },
        map_photons, ppm_samples);
}

// The same where expected(mu) is grey.
void ExpectCubeReflects(const std::string& scene_path, Integrator integrator,
                        const std::string& feature, const std::function<double(double)>& reflects) {
    ExpectCubeReflectsRgb(scene_path, integrator, feature,
                          [&](double mu) { return Rgbd(reflects(mu)); });
}

class CoatedEnvironmentFurnace : public ::testing::TestWithParam<Integrator> {};

TEST_P(CoatedEnvironmentFurnace, ConvexBodyReflectsItsDirectionalAlbedo) {
    ExpectCubeReflects(
        testing::WriteTextFile(
            CubePbrt(absl::StrFormat("Material \"coateddiffuse\" \"rgb reflectance\" [%g %g %g] "
                                     "\"float eta\" %g \"float thickness\" %g\n",
                                     kAlbedo, kAlbedo, kAlbedo, kCoatIor, kCoatThickness)),
            "cube.pbrt"),
        GetParam(), "coated", CoatedAlbedo);
}

// glTF's dielectric, a smooth specular layer of index 1.5 and weight 0.8 over the albedo
// (core/shared/coat.h's Fresnel mix): the body reflects F(mu) + (1 - F(mu)) rho, F Schlick's
// times the weight, since the base's lobe is normalised.
class GltfDielectricEnvironmentFurnace : public ::testing::TestWithParam<Integrator> {};

TEST_P(GltfDielectricEnvironmentFurnace, ConvexBodyReflectsFresnelPlusTheRestOfTheBase) {
    constexpr float kWeight = 0.8f;
    testing::TestScene cube = TurnedCube();
    cube.materials[0].roughness = 0;
    cube.materials[0].extensions =
        absl::StrFormat(R"("KHR_materials_specular":{"specularFactor":%g})", kWeight);
    const gpu::Coat coat{gpu::kCoatFresnelMix, 1.5f, 0, 0, kWeight, 0};
    ExpectCubeReflects(testing::WriteGltf(cube, "plastic-cube.gltf"), GetParam(),
                       "specular over diffuse", [&](double mu) {
                           const double fresnel = gpu::MixFresnel(coat, float(mu));
                           return fresnel + (1 - fresnel) * kAlbedo;
                       });
}

// glTF's KHR_materials_sheen, colour c and roughness 0.5, over a Lambertian base (no specular
// layer): the sheen reflects c E(mu) (core/shared/sheen.h's table, within 1.5%), the base the
// rest, 1 - max(c) E(mu), times its albedo, its lobe normalised by 1 - max(c) E_avg.
class SheenEnvironmentFurnace : public ::testing::TestWithParam<Integrator> {};

TEST_P(SheenEnvironmentFurnace, ConvexBodyReflectsTheSheenPlusTheRestOfTheBase) {
    const Rgbd colour(1.0, 0.7, 0.4);
    constexpr float kRoughness = 0.5f;
    testing::TestScene cube = TurnedCube();
    cube.materials[0].extensions = absl::StrFormat(
        R"("KHR_materials_specular":{"specularFactor":0},)"
        R"("KHR_materials_sheen":{"sheenColorFactor":[%g,%g,%g],"sheenRoughnessFactor":%g})",
        colour.x, colour.y, colour.z, kRoughness);
    ExpectCubeReflectsRgb(
        testing::WriteGltf(cube, "velvet-cube.gltf"), GetParam(), "sheen",
        [&](double mu) {
            const double e = gpu::SheenAlbedo(float(mu), kRoughness);
            return colour * e + Rgbd((1 - e) * kAlbedo);
        },
        1u << 19,
        // ppm's hit points keep the direction their sheen reflection drew: more of them.
        128);
}

// A mix (pbrt's "mix", amount a) of two diffuse materials of albedo rho1 and rho2: each point
// is the second with probability a, so the body reflects ((1 - a) rho1 + a rho2) L.
class MixedEnvironmentFurnace : public ::testing::TestWithParam<Integrator> {};

TEST_P(MixedEnvironmentFurnace, ConvexBodyReflectsTheMixedAlbedo) {
    constexpr double kFirst = 0.9, kSecond = 0.2, kAmount = 0.3;
    ExpectCubeReflects(
        testing::WriteTextFile(
            CubePbrt(absl::StrFormat(
                "MakeNamedMaterial \"a\" \"string type\" \"diffuse\" \"rgb reflectance\" "
                "[%g %g %g]\nMakeNamedMaterial \"b\" \"string type\" \"diffuse\" \"rgb "
                "reflectance\" [%g %g %g]\nMaterial \"mix\" \"string materials\" [\"a\" "
                "\"b\"] \"float amount\" %g\n",
                kFirst, kFirst, kFirst, kSecond, kSecond, kSecond, kAmount)),
            "cube.pbrt"),
        GetParam(), "mixed materials",
        [](double) { return (1 - kAmount) * kFirst + kAmount * kSecond; });
}

// pbrt-v4's diffusetransmission, reflectance R and transmittance T per channel: light enters
// the closed cube through its faces, so its inside holds a uniform radiance L_i (each inner
// point sees only the inside: L_i = R L_i + T L), L_i = T L / (1 - R), and each face shows
// L (R + T^2 / (1 - R)) whatever the angle: L itself, the cube vanishing into the sky, where
// R + T = 1. Photons let in land inside, and the points on the far side of each face gather
// them.
class TranslucentEnvironmentFurnace : public ::testing::TestWithParam<Integrator> {};

TEST_P(TranslucentEnvironmentFurnace, ClosedBodyShowsReflectionPlusWhatItsInsideLetsOut) {
    const Rgbd r(0.5, 0.3, 0.2), t(0.3, 0.6, 0.4);
    ExpectCubeReflectsRgb(
        testing::WriteTextFile(
            CubePbrt(absl::StrFormat("Material \"diffusetransmission\" \"rgb reflectance\" "
                                     "[%g %g %g] \"rgb transmittance\" [%g %g %g] \"float "
                                     "scale\" 2\n",
                                     r.x / 2, r.y / 2, r.z / 2, t.x / 2, t.y / 2, t.z / 2)),
            "paper-cube.pbrt"),
        GetParam(), "diffuse transmission", [&](double) { return r + t * t / (Rgbd(1.0) - r); },
        // pm's final gathers through the faces read the inside's photons, from one map for
        // the whole render, whose noise every block shares and the blocks' sigma leaves out:
        // eight times the photons (at four, seeds 3 to 6 gave z 5.8, 3.9, 0.7, 2.8 in red; at
        // eight 5.0, 3.1, 1.3, 2.3, ratios 1.001 to 1.003).
        1u << 22);
}

// pbrt-v4's conductor, smooth gold: a convex mirror under a uniform sky L reflects L F(mu)
// toward a viewer at cosine mu, F the Fresnel reflectance of gold's complex index in each
// channel (core/shared/conductor.h), from 0.34 head-on in blue to 1 at grazing.
class ConductorEnvironmentFurnace : public ::testing::TestWithParam<Integrator> {};

TEST_P(ConductorEnvironmentFurnace, ConvexMirrorReflectsItsFresnelTerm) {
    const pbrt::ComplexIndex gold = *pbrt::NamedMetalIndex("metal-Au-eta");
    ExpectCubeReflectsRgb(
        testing::WriteTextFile(CubePbrt("Material \"conductor\" \"spectrum eta\" \"metal-Au-eta\" "
                                        "\"spectrum k\" \"metal-Au-k\"\n"),
                               "gold-cube.pbrt"),
        GetParam(), "metal Fresnel", [&](double mu) {
            Rgbd fresnel;
            for (int c = 0; c < 3; ++c)
                fresnel[c] = gpu::FresnelComplex(float(mu), gold.eta[c], gold.k[c]);
            return fresnel;
        });
}

// Absorbing glass of index 1 (nothing reflects or bends): the camera sees the sky through the
// cube attenuated by Beer-Lambert along the chord, exp(-sigma_a d), d from where the ray enters
// to where it leaves. pbrt-v4's homogeneous medium inside a dielectric (sigma_a x scale, its
// scattering noted and left out), and glTF's KHR_materials_volume (sigma_a = -ln(colour) /
// distance).
const Rgb kSigmaA(0.3f, 1.1f, 2.4f);

Rgbd ThroughTheChord(const Scene&, const Tracer& tracer, const Ray& ray, const RayHit& entry) {
    constexpr float kInside = 1e-5f;
    const Ray onward{ray.origin + ray.direction * (entry.t + kInside), ray.direction};
    RayHit exit;
    if (!tracer.Intersect(onward, &exit)) return Rgbd(1.0);
    const double chord = exit.t + kInside;
    return Rgbd(std::exp(-kSigmaA.x * chord), std::exp(-kSigmaA.y * chord),
                std::exp(-kSigmaA.z * chord));
}

class AbsorbingGlassEnvironment : public ::testing::TestWithParam<Integrator> {};

TEST_P(AbsorbingGlassEnvironment, PbrtMediumInsideGlassAttenuatesAlongTheChord) {
    ExpectCubeShows(
        testing::WriteTextFile(
            CubePbrt(absl::StrFormat(
                "MakeNamedMedium \"ink\" \"string type\" \"homogeneous\" \"rgb sigma_a\" "
                "[%g %g %g] \"rgb sigma_s\" [0 0 0] \"float scale\" 2\n"
                "MediumInterface \"ink\" \"\"\nMaterial \"dielectric\" \"float eta\" 1\n",
                kSigmaA.x / 2, kSigmaA.y / 2, kSigmaA.z / 2)),
            "ink-cube.pbrt"),
        GetParam(), "absorbing media", ThroughTheChord);
}

TEST_P(AbsorbingGlassEnvironment, GltfVolumeAttenuatesAlongTheChord) {
    constexpr double kDistance = 0.8;
    testing::TestScene cube = TurnedCube();
    cube.materials[0].base_color = Rgb(1.0f);  // glass is tinted by it
    cube.materials[0].roughness = 0;
    cube.materials[0].extensions = absl::StrFormat(
        R"("KHR_materials_transmission":{"transmissionFactor":1},"KHR_materials_ior":{"ior":1},)"
        R"("KHR_materials_volume":{"thicknessFactor":1,"attenuationDistance":%g,)"
        R"("attenuationColor":[%.9g,%.9g,%.9g]})",
        kDistance, std::exp(-kSigmaA.x * kDistance), std::exp(-kSigmaA.y * kDistance),
        std::exp(-kSigmaA.z * kDistance));
    ExpectCubeShows(testing::WriteGltf(cube, "ink-cube.gltf"), GetParam(), "absorbing media",
                    ThroughTheChord);
}

INSTANTIATE_TEST_SUITE_P(Integrators, AbsorbingGlassEnvironment, EveryIntegrator(),
                         IntegratorParamName);

INSTANTIATE_TEST_SUITE_P(Integrators, TranslucentEnvironmentFurnace, EveryIntegrator(),
                         IntegratorParamName);

INSTANTIATE_TEST_SUITE_P(Integrators, SheenEnvironmentFurnace, EveryIntegrator(),
                         IntegratorParamName);

INSTANTIATE_TEST_SUITE_P(Integrators, ConductorEnvironmentFurnace, EveryIntegrator(),
                         IntegratorParamName);

INSTANTIATE_TEST_SUITE_P(Integrators, MixedEnvironmentFurnace, EveryIntegrator(),
                         IntegratorParamName);

INSTANTIATE_TEST_SUITE_P(Integrators, GltfDielectricEnvironmentFurnace, EveryIntegrator(),
                         IntegratorParamName);

INSTANTIATE_TEST_SUITE_P(Integrators, CoatedEnvironmentFurnace, EveryIntegrator(),
                         IntegratorParamName);

}  // namespace
}  // namespace pf
