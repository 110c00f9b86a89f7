// Progressive photon mapping's image converges at its sharp edges too: what photons do not
// carry -- the emission the camera sees and direct light -- is sampled afresh every epoch at
// stratified camera samples, so a pixel on the light's outline, an object's silhouette or a
// shadow's edge converges to its integral, where with the fixed hit points alone it kept the
// error of their k positions for ever. And the photons' estimate at the fixed hit points counts
// in a pixel by the share of those fresh samples each hit point stands for, so that a pixel
// across an edge between surfaces lit differently takes them by area, not by how its k fixed
// samples fell.
//
// The first scene holds no indirect light at all (one grey floor; the occluder over it and the
// light are black), so the photons add nothing and every pixel is emission plus direct light, which
// the path tracer's long render gives without bias.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "core/camera/camera_pass.h"
#include "embedded/local_render.h"
#include "tests/support/epoch_render.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/lit_scene.h"

namespace pf {
namespace {

constexpr int kSize = 32;

std::string EdgesScene() {
    return "LookAt 0 3 3  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 50\nWorldBegin\n"
           "AttributeBegin\nMaterial \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]\n"
           "Shape \"bilinearmesh\" \"point3 P\" [-2 0 -2  2 0 -2  -2 0 2  2 0 2]\nAttributeEnd\n"
           "AttributeBegin\nMaterial \"diffuse\" \"rgb reflectance\" [0 0 0]\n"
           "Shape \"bilinearmesh\" \"point3 P\" [-0.35 0.5 -0.2  0.25 0.5 -0.3  -0.3 0.5 0.35  "
           "0.3 0.5 0.3]\n"
           "AreaLightSource \"diffuse\" \"rgb L\" [30 30 30] \"bool twosided\" true\n"
           "Shape \"bilinearmesh\" \"point3 P\" [0.3 1.2 -0.8  0.9 1.2 -0.7  0.3 1.2 -0.3  "
           "0.9 1.2 -0.2]\nAttributeEnd\n";
}

RenderSettings Settings(const std::string& scene, Integrator integrator, uint64_t epochs) {
    RenderSettings settings = testing::EpochRender(scene, integrator, kSize, 3, epochs);
    if (integrator == Integrator::kPpm) settings.job.layout = {1u << 12, 2};
    return settings;
}

double Luminance(const Rgb& v) { return (v.x + v.y + v.z) / 3; }

TEST(PpmEdges, EmissionAndDirectLightConvergeAtEveryEdge) {
    const std::string scene = testing::WriteTextFile(EdgesScene(), "ppm-edges.pbrt");
    RenderSettings reference_settings = Settings(scene, Integrator::kPath, 256);
    reference_settings.job.samples_per_pixel = 64;
    const absl::StatusOr<RenderOutcome> reference = RenderLocally(reference_settings);
    ASSERT_TRUE(reference.ok()) << reference.status();
    const absl::StatusOr<RenderOutcome> early = RenderLocally(Settings(scene, Integrator::kPpm, 4));
    const absl::StatusOr<RenderOutcome> late = RenderLocally(Settings(scene, Integrator::kPpm, 64));
    ASSERT_TRUE(early.ok() && late.ok());

    // The edges: pixels whose reference differs from a neighbour's by a fifth of the brightest
    // floor pixel's value or more (the light's own pixels, 30, clamped to 1 for this).
    const auto value = [&](int x, int y) {
        return std::min(1.0, Luminance(reference->image.At(x, y)));
    };
    std::vector<std::pair<int, int>> edges;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            double step = 0;
            for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
                const int nx = x + dx, ny = y + dy;
                if (nx >= 0 && ny >= 0 && nx < kSize && ny < kSize)
                    step = std::max(step, std::abs(value(x, y) - value(nx, ny)));
            }
            if (step > 0.2) edges.emplace_back(x, y);
        }
    ASSERT_GE(edges.size(), 40u) << "the scene's outlines and shadow edges";
    const auto edge_mse = [&](const Image& image) {
        double sum = 0;
        for (const auto& [x, y] : edges) {
            const double d = Luminance(image.At(x, y)) - Luminance(reference->image.At(x, y));
            sum += d * d;
        }
        return sum / static_cast<double>(edges.size());
    };
    const double mse_early = edge_mse(early->image), mse_late = edge_mse(late->image);
    std::printf("%zu edge pixels: MSE %.3g after 4 epochs, %.3g after 64 (ratio %.3f)\n",
                edges.size(), mse_early, mse_late, mse_late / mse_early);
    // 16 times the samples: 1/16 of the squared error for independent samples, less for
    // stratified ones; fixed hit points kept their edge error (a ratio near 1).
    EXPECT_LT(mse_late, mse_early / 6);
    // And the image is the path tracer's: the mean over the edges within 2%.
    double ppm = 0, path = 0;
    for (const auto& [x, y] : edges)
        ppm += Luminance(late->image.At(x, y)), path += Luminance(reference->image.At(x, y));
    EXPECT_NEAR(ppm / path, 1.0, 0.02);
}

// In the Cornell box, at 24x24 pixels with k = 2 fixed hit points a pixel, the pixels whose
// hit points lie on two surfaces facing different ways (the walls' corners, the blocks'
// outlines) and that see no third: each surface's hit points' shares of the pixel, summed (the
// fresh samples they stand for, weighted by the samples' weights over their own: untextured
// surfaces, so each sample on the surface counts 1), against the fraction of the pixel that sees
// that surface, measured by a fixed pass of 1024 samples a pixel with a seed of its own. Each share
// is a fraction of n = 16 x 64 stratified samples, within 4 binomial sigmas of it (sqrt(f (1 - f) /
// n), which stratified samples beat) and the reference's own; the k-sample split the fixed hit
// points had alone (1/2 or 1) is off by far more.
TEST(PpmEdges, FixedHitPointsStandForTheirShareOfEachPixel) {
    constexpr int kPixels = 24, kEpochs = 16, kFixed = 2, kReferenceSamples = 1024;
    const std::unique_ptr<const testing::LitScene> lit = testing::LoadLitScene("cornell-box.gltf");
    ASSERT_TRUE(lit);
    JobSpec spec;
    spec.integrator = Integrator::kPpm;
    spec.width = spec.height = kPixels;
    spec.samples_per_pixel = kFixed;
    spec.seed = 5;
    spec.layout = {1u << 17, 1, 1u << 17};  // every epoch full: 64 camera samples a pixel
    CameraPassSettings film = *FilmFor(spec, lit->scene);
    film.features = lit->features;
    const auto fixed = std::make_shared<const PixelHitPoints>(PixelHitPoints::Index(
        std::make_shared<const std::vector<HitPoint>>(
            RunCameraPass(lit->scene, *lit->emitters, *lit->tracer, film).hit_points),
        size_t(kPixels) * kPixels));
    const std::span<const HitPoint> points = fixed->points;
    std::vector<double> share(points.size(), 0.0);
    double samples = 0;
    for (uint64_t epoch = 0; epoch < kEpochs; ++epoch) {
        const CameraPassSettings pass = EmissionCameraPass(film, spec, epoch);
        const CameraPassResult result =
            RunCameraPass(lit->scene, *lit->emitters, *lit->tracer, pass, fixed.get());
        ASSERT_EQ(result.coverage.size(), points.size());
        for (size_t k = 0; k < points.size(); ++k) {  // in pixel order
            const uint32_t i = fixed->At(k);
            share[i] += double(result.coverage[k].y) / points[i].weight.y * pass.samples_per_pixel;
        }
        samples += pass.samples_per_pixel;
    }
    ASSERT_EQ(samples, kEpochs * 64.0);
    CameraPassSettings dense = film;
    dense.samples_per_pixel = kReferenceSamples;
    dense.seed = 77;
    const std::vector<HitPoint> reference =
        RunCameraPass(lit->scene, *lit->emitters, *lit->tracer, dense).hit_points;
    // Which way a hit point faces, as CoveringHitPoint tells surfaces apart: by the six axes
    // the Cornell box's faces and the blocks' near faces lie closest to.
    const auto facing = [](const HitPoint& point) {
        const Vec3 n = point.normal;
        const Vec3 a(std::abs(n.x), std::abs(n.y), std::abs(n.z));
        const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
        return 2 * axis + (n[axis] < 0 ? 1 : 0);
    };
    std::vector<std::array<double, 6>> fraction(size_t(kPixels) * kPixels, std::array<double, 6>{});
    for (const HitPoint& point : reference)
        fraction[point.pixel][facing(point)] += 1.0 / kReferenceSamples;
    int edge_pixels = 0;
    double old_error = 0, new_error = 0;
    for (uint32_t p = 0; p < uint32_t(kPixels * kPixels); ++p) {
        std::array<double, 6> shares{}, split{};
        std::array<int, 6> count{};
        fixed->ForEachOf(p, [&](uint32_t i) {
            shares[facing(points[i])] += share[i] / samples;
            split[facing(points[i])] += 1.0 / kFixed;
            ++count[facing(points[i])];
        });
        // Pixels that see those two surfaces alone (a sample on a third stands for the nearest
        // hit point of another).
        double seen = 0;
        for (int f = 0; f < 6; ++f)
            if (count[f] > 0) seen += fraction[p][f];
        if (std::count_if(count.begin(), count.end(), [](int c) { return c > 0; }) != 2 ||
            seen < 1 - 1e-9)
            continue;
        ++edge_pixels;
        for (int f = 0; f < 6; ++f) {
            if (count[f] == 0) continue;
            const double expected = fraction[p][f];
            const double sigma = std::sqrt(expected * (1 - expected) / samples) +
                                 std::sqrt(expected * (1 - expected) / kReferenceSamples);
            EXPECT_NEAR(shares[f], expected, 4 * sigma + 1e-3)
                << "pixel " << p % kPixels << ", " << p / kPixels << ", facing " << f;
            new_error += (shares[f] - expected) * (shares[f] - expected);
            old_error += (split[f] - expected) * (split[f] - expected);
        }
    }
    std::printf(
        "%d pixels on two surfaces: squared error of the shares %.3g, of the k-split %.3g\n",
        edge_pixels, new_error, old_error);
    EXPECT_GE(edge_pixels, 20);
    EXPECT_LT(new_error, old_error / 20);
}

// A camera that sees only glossy surfaces (glTF's default material, a rough metal: corpus run
// 1's SimpleMeshes) gets no hit points, and photons add nothing; but its paths find the sky
// through the glossy bounce, and that image is right: no warning that it is "emission only".
// Where those paths find no light either (a point light under the metal), the image is black,
// and the render says so.
TEST(PpmEdges, ACameraSeeingOnlyGlossSaysSoOnlyWhereTheImageIsBlack) {
    const auto render = [](const std::string& light, const std::string& name) {
        const std::string scene = testing::WriteTextFile(
            "LookAt 0 3 3  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 30\nWorldBegin\n" +
                light +
                "Material \"conductor\" \"rgb reflectance\" [0.8 0.8 0.8] \"float roughness\" "
                "0.3\nShape \"bilinearmesh\" \"point3 P\" [-2 0 -2  2 0 -2  -2 0 2  2 0 2]\n",
            name);
        RenderSettings settings = Settings(scene, Integrator::kPpm, 2);
        settings.job.width = settings.job.height = 8;
        const absl::StatusOr<RenderOutcome> outcome = RenderLocally(settings);
        EXPECT_TRUE(outcome.ok()) << outcome.status();
        return outcome.ok() ? *outcome : RenderOutcome{};
    };
    const auto mentions = [](const RenderOutcome& outcome, const std::string& fragment) {
        return std::any_of(
            outcome.warnings.begin(), outcome.warnings.end(),
            [&](const std::string& w) { return w.find(fragment) != std::string::npos; });
    };
    const RenderOutcome sky =
        render("LightSource \"infinite\" \"rgb L\" [1 1 1]\n", "gloss-sky.pbrt");
    EXPECT_EQ(sky.hit_points, 0u);
    double mean = 0;
    for (const Rgb& pixel : sky.image.pixels) mean += Luminance(pixel) / sky.image.pixels.size();
    EXPECT_GT(mean, 0.1) << "the sky, through the metal";
    EXPECT_FALSE(mentions(sky, "emission only"));
    EXPECT_FALSE(mentions(sky, "black"));

    const RenderOutcome dark = render(
        "LightSource \"point\" \"point3 from\" [0 -1 0] \"rgb I\" [5 5 5]\n", "gloss-dark.pbrt");
    EXPECT_EQ(dark.hit_points, 0u);
    EXPECT_TRUE(std::all_of(dark.image.pixels.begin(), dark.image.pixels.end(),
                            [](const Rgb& pixel) { return IsBlack(pixel); }));
    EXPECT_TRUE(mentions(dark, "the camera sees no diffuse surface, and its paths found no light"));
}

}  // namespace
}  // namespace pf
