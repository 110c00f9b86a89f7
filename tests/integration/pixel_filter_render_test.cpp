// A pbrt file's PixelFilter shapes the image as pbrt-v4's does: an orthographic camera, one
// pixel a world unit, looks at an emitter that ends at a vertical line on a pixel boundary. A
// pixel whose centre lies s pixels inside the emitter then reads L times the share of the
// filter's integral on the emitter's side, F(s) = integral of f from -r to s over the integral
// from -r to r -- for the box of one pixel a hard step, for wider filters a ramp, and for a
// Mitchell filter with B = 0, C = 1 (strong lobes) below zero just outside the edge and above L
// just inside it. Every integrator places its camera samples the same way.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

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

}  // namespace
}  // namespace pf
