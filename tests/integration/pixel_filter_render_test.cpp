// A pbrt file's PixelFilter shapes the image as pbrt-v4's does: an orthographic camera, one
// pixel a world unit, looks at an emitter that ends at a vertical line on a pixel boundary. A
// pixel whose centre lies s pixels inside the emitter then reads L times the share of the
// filter's integral on the emitter's side, F(s) = integral of f from -r to s over the integral
// from -r to r -- for the box of one pixel a hard step, for wider filters a ramp, and for a
// Mitchell filter with B = 0, C = 1 (strong lobes) below zero just outside the edge and above L
// just inside it. Every integrator places its camera samples the same way.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/scene/pixel_filter.h"
#include "embedded/local_render.h"
#include "tests/support/epoch_render.h"
#include "tests/support/gltf_builder.h"

namespace pf {
namespace {

constexpr int kWidth = 16, kHeight = 4;

std::string EdgeScene(const std::string& filter) {
    return "LookAt 0 0 5  0 0 0  0 1 0\n"
           "Camera \"orthographic\" \"float screenwindow\" [-8 8 -2 2]\n"
           "Film \"rgb\" \"integer xresolution\" 16 \"integer yresolution\" 4\n" +
           filter +
           "\nWorldBegin\nAttributeBegin\nMaterial \"diffuse\" \"rgb reflectance\" [0 0 0]\n"
           "AreaLightSource \"diffuse\" \"rgb L\" [1 1 1] \"bool twosided\" true\n"
           "Shape \"bilinearmesh\" \"point3 P\" [-100 -100 0  0 -100 0  -100 100 0  0 100 0]\n"
           "AttributeEnd\n";
}

// F(s): the filter's share on the emitter's side, by Simpson's rule.
double Share(const PixelFilter& filter, double s) {
    const double r = filter.radius_x;
    const auto integral = [&](double a, double b) {
        constexpr int kSteps = 4000;
        const double h = (b - a) / kSteps;
        double sum = FilterSampler::Evaluate(filter, a, r) + FilterSampler::Evaluate(filter, b, r);
        for (int i = 1; i < kSteps; ++i)
            sum += (i % 2 ? 4 : 2) * FilterSampler::Evaluate(filter, a + i * h, r);
        return sum * h / 3;
    };
    return s <= -r ? 0.0 : integral(-r, std::min(s, r)) / integral(-r, r);
}

struct Case {
    std::string directive;
    PixelFilter filter;
};

TEST(PixelFilterRender, TheEdgeOfAnEmitterIsTheFiltersIntegral) {
    const Case cases[] = {
        {"PixelFilter \"box\"", {FilterKind::kBox, 0.5f, 0.5f}},
        {"PixelFilter \"triangle\"", {FilterKind::kTriangle, 2, 2}},
        {"PixelFilter \"gaussian\" \"float xradius\" 2 \"float yradius\" 2 \"float sigma\" 1",
         {FilterKind::kGaussian, 2, 2, 1}},
        {"PixelFilter \"mitchell\" \"float B\" 0 \"float C\" 1",
         {FilterKind::kMitchell, 2, 2, 0.5f, 0, 1}},
    };
    for (const Case& c : cases) {
        const std::string scene =
            testing::WriteTextFile(EdgeScene(c.directive), "filter-edge.pbrt");
        for (const Integrator integrator :
             {Integrator::kPath, Integrator::kPpm, Integrator::kSppm}) {
            // 4096 samples a pixel: 64 an epoch (ppm's emission takes one per two photons).
            RenderSettings settings = testing::EpochRender(scene, integrator, kWidth, 5, 64);
            settings.job.height = kHeight;
            settings.job.samples_per_pixel = 64;
            if (integrator != Integrator::kPath) settings.job.layout = {1u << 13, 1};
            const absl::StatusOr<RenderOutcome> outcome = RenderLocally(settings);
            ASSERT_TRUE(outcome.ok()) << outcome.status();
            const Image& image = outcome->image;
            // Which way the image runs: the emitter's side is bright in the first column.
            const bool emitter_left = image.At(0, 1).x > 0.5f;
            for (int y = 0; y < kHeight; ++y)
                for (int x = 0; x < kWidth; ++x) {
                    const double centre = x + 0.5 - kWidth / 2;  // pixels right of the edge
                    const double inside = emitter_left ? -centre : centre;
                    EXPECT_NEAR(image.At(x, y).x, Share(c.filter, inside), 0.008)
                        << c.directive << ", " << IntegratorName(integrator) << ", pixel (" << x
                        << ", " << y << ")";
                }
            if (c.filter.kind == FilterKind::kMitchell) {
                // The lobes: -0.026 one and a half pixels outside, 1.026 as far inside.
                const int outside = emitter_left ? 9 : 6, inside = emitter_left ? 6 : 9;
                EXPECT_LT(image.At(outside, 1).x, -0.015f) << IntegratorName(integrator);
                EXPECT_GT(image.At(inside, 1).x, 1.015f) << IntegratorName(integrator);
            }
        }
    }
}

// Negative weights through ppm's photons: with Mitchell's strong lobes (B 0, C 1) some fixed hit
// points weigh below zero, and a pixel's photon estimate takes them by their signed shares of
// its fresh samples. Inside a white sphere (albedo 0.8) with a ball and a panel light, where
// photons carry five sixths of the image: ppm's image agrees with the path tracer's (mean
// within 1%; each 4x4 block within 10%). Dropping the negative weights' shares, as ppm once
// did (weights were never negative then), leaves it 2.5% bright.
TEST(PixelFilterRender, MitchellsNegativeWeightsCarryPpmsPhotons) {
    constexpr int kSize = 32, kBlock = 4;
    const std::string scene = testing::WriteTextFile(
        "LookAt 0 0.5 2  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 60\n"
        "PixelFilter \"mitchell\" \"float B\" 0 \"float C\" 1\nWorldBegin\n"
        "AttributeBegin\nMaterial \"diffuse\" \"rgb reflectance\" [0.8 0.8 0.8]\n"
        "Shape \"sphere\" \"float radius\" 3\n"
        "Translate 0 -0.4 0\nShape \"sphere\" \"float radius\" 0.5\nAttributeEnd\n"
        "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [20 20 20] \"bool twosided\" "
        "true\nMaterial \"diffuse\" \"rgb reflectance\" [0 0 0]\n"
        "Shape \"bilinearmesh\" \"point3 P\" [0.3 1.5 -0.8  0.9 1.5 -0.8  0.3 1.5 -0.2  "
        "0.9 1.5 -0.2]\nAttributeEnd\n",
        "mitchell-ppm.pbrt");
    RenderSettings path = testing::EpochRender(scene, Integrator::kPath, kSize, 7, 64);
    path.job.samples_per_pixel = 64;
    RenderSettings ppm = testing::EpochRender(scene, Integrator::kPpm, kSize, 8, 64);
    ppm.job.layout = {1u << 15, 2};
    const absl::StatusOr<RenderOutcome> reference = RenderLocally(path);
    const absl::StatusOr<RenderOutcome> photons = RenderLocally(ppm);
    ASSERT_TRUE(reference.ok() && photons.ok());
    const auto luminance = [](const Rgb& v) { return (double(v.x) + v.y + v.z) / 3; };
    double mean_reference = 0, mean_ppm = 0, brightest = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            mean_reference += luminance(reference->image.At(x, y));
            mean_ppm += luminance(photons->image.At(x, y));
        }
    EXPECT_NEAR(mean_ppm / mean_reference, 1.0, 0.01);
    std::printf("ppm / path mean: %.4f\n", mean_ppm / mean_reference);
    std::vector<double> blocks_reference, blocks_ppm;
    for (int by = 0; by < kSize; by += kBlock)
        for (int bx = 0; bx < kSize; bx += kBlock) {
            double a = 0, b = 0;
            for (int y = by; y < by + kBlock; ++y)
                for (int x = bx; x < bx + kBlock; ++x) {
                    a += luminance(reference->image.At(x, y));
                    b += luminance(photons->image.At(x, y));
                }
            blocks_reference.push_back(a), blocks_ppm.push_back(b);
            brightest = std::max(brightest, a);
        }
    for (size_t i = 0; i < blocks_reference.size(); ++i) {
        if (blocks_reference[i] > 0.05 * brightest) {
            EXPECT_NEAR(blocks_ppm[i] / blocks_reference[i], 1.0, 0.1) << "block " << i;
        }
    }
}

}  // namespace
}  // namespace pf
