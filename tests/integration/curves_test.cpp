// Curves through the renderers: the CPU tracer (Embree's curve primitives) meets what the
// Vulkan backend's ray test (core/shared/curve.h) meets, instances included; black curves
// before an emitter hide the share of it their width x length covers. (The Vulkan backend's
// images of curves against the CPU's: tests/worker/vulkan_pixel_test.cpp.)
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "absl/strings/str_format.h"
#include "core/scene_io/scene_loader.h"
#include "core/shared/curve.h"
#include "embedded/local_render.h"
#include "embree/embree_tracer.h"
#include "tests/support/test_env.h"

namespace pf {
namespace {

const std::string kCurvesScene = std::string(PF_SOURCE_DIR) + "/scenes/pbrt/cornell-curves.pbrt";

// The closest curve along `ray` by the Vulkan backend's test, every curve of every instance
// tried: its t and u, and whether it is the curve (and instance) `hit` names.
struct Found {
    float t = -1, u = 0, v = 0;
    uint32_t curve = 0, instance = Instance::kNone;
};
Found ClosestCurve(const Scene& scene, const Ray& ray) {
    Found found;
    float t_max = ray.t_max;
    const auto test = [&](uint32_t c, uint32_t instance) {
        const Curve curve = scene.WorldCurve(c, instance);
        const std::array<Vec3, 4>& p = curve.control;
        float t = 0, u = 0, v = 0;
        if (gpu::IntersectCurve(ray.origin, ray.direction, t_max, p[0], p[1], p[2], p[3],
                                curve.width[0], curve.width[1], static_cast<uint32_t>(curve.type),
                                curve.normal[0], curve.normal[1], t, u, v))
            t_max = t, found = {t, u, v, c, instance};
    };
    for (uint32_t c = 0; c < scene.WorldCurveCount(); ++c) test(c, Instance::kNone);
    for (uint32_t i = 0; i < scene.instances.size(); ++i) {
        const Prototype& prototype = scene.prototypes[scene.instances[i].prototype];
        for (uint32_t c = prototype.first_curve; c < prototype.first_curve + prototype.curve_count;
             ++c)
            test(c, i);
    }
    return found;
}

TEST(CurvesTracingTest, EmbreeMeetsTheCurvesTheVulkanTestMeets) {
    // Rays from the camera's side toward points on the scene's curves (grass instanced three
    // times, strands, ribbons), a little off each, so that some pass beside: Embree's first
    // curve hit (where no triangle is nearer) is the one the Vulkan test finds, at the same
    // place along it, with the same surface.
    const absl::StatusOr<Scene> loaded = LoadScene(kCurvesScene);
    ASSERT_TRUE(loaded.ok()) << loaded.status();
    const Scene& scene = *loaded;
    ASSERT_GT(scene.prototypes.size(), 0u);
    ASSERT_GT(scene.WorldCurveCount(), 0u);
    auto tracer = embree::EmbreeTracer::Create(scene);
    ASSERT_TRUE(tracer.ok()) << tracer.status();
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    int curve_hits = 0, agreeing = 0, instanced = 0;
    constexpr int kRays = 3000;
    for (int i = 0; i < kRays; ++i) {
        // A point on a random curve of a random placement, the ray from near the camera.
        const bool in_instance = i % 2 == 0;
        uint32_t instance = Instance::kNone, c = 0;
        if (in_instance) {
            instance = static_cast<uint32_t>(unit(rng) * scene.instances.size());
            const Prototype& p = scene.prototypes[scene.instances[instance].prototype];
            c = p.first_curve + static_cast<uint32_t>(unit(rng) * p.curve_count);
        } else {
            c = static_cast<uint32_t>(unit(rng) * scene.WorldCurveCount());
        }
        const Curve curve = scene.WorldCurve(c, instance);
        const float u = unit(rng);
        const Vec3 target = gpu::BezierPoint(curve.control[0], curve.control[1], curve.control[2],
                                             curve.control[3], u) +
                            Vec3(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f) *
                                (1.5f * std::max(curve.width[0], curve.width[1]));
        Ray ray;
        ray.origin = Vec3(0.2f + 0.15f * unit(rng), 0.2f + 0.15f * unit(rng), -0.5f);
        ray.direction = Normalize(target - ray.origin);
        RayHit hit;
        const bool embree_hit = (*tracer)->Intersect(ray, &hit);
        Ray to_hit = ray;
        if (embree_hit && !hit.IsCurve()) to_hit.t_max = hit.t;  // a triangle in front
        const Found found = ClosestCurve(scene, to_hit);
        const bool embree_curve = embree_hit && hit.IsCurve();
        if (!embree_curve && found.t < 0) continue;
        ++curve_hits;
        if (embree_curve != (found.t >= 0)) continue;  // one saw the curve's edge, the other not
        if (hit.CurveIndex() != found.curve || hit.instance != found.instance) continue;
        ++agreeing;
        instanced += hit.instance != Instance::kNone;
        // The depths agree within a width, more where the ray runs along the curve: within
        // a width over the sine of the angle between them.
        const Curve met = scene.WorldCurve(found.curve, found.instance);
        const Vec3 tangent = gpu::CurveTangent(met.control[0], met.control[1], met.control[2],
                                               met.control[3], found.u, ray.direction);
        const float sine = std::max(Length(Cross(tangent, ray.direction)), 0.05f);
        EXPECT_NEAR(hit.t, found.t, std::max(met.width[0], met.width[1]) / sine) << "ray " << i;
        // A ribbon met obliquely: Embree's u is the band's point the ray meets, pbrt-v4's test
        // takes the centre line's nearest to the ray, up to half a width along the curve away
        // (its length at least its chord's).
        const float along =
            met.type == CurveType::kRibbon
                ? met.Radius() / std::max(Length(met.control[3] - met.control[0]), 1e-6f)
                : 0.0f;
        EXPECT_NEAR(hit.b1, found.u, 0.02f / sine + along) << "ray " << i;
        EXPECT_TRUE(hit.origin == ray.origin && hit.direction == ray.direction);
        const SurfacePoint surface = scene.Surface(hit);
        EXPECT_LT(Dot(surface.shading_normal, surface.geometric_normal), 1.0001f);
        EXPECT_GT(Dot(surface.shading_normal, surface.geometric_normal), 0.0f) << "ray " << i;
        EXPECT_EQ(surface.material, scene.curves[hit.CurveIndex()].material);
    }
    EXPECT_GT(curve_hits, kRays / 3) << "the rays must meet curves";
    EXPECT_GE(agreeing, 0.97 * curve_hits) << agreeing << " of " << curve_hits;
    EXPECT_GT(instanced, kRays / 10) << "instances' curves must be met too";
}

// A scene of a twosided emitter (L = 1) filling the view of a camera 10 away, with black
// `curves` (pbrt shapes) before it; a box filter, so that the image's mean is the view's.
std::string EmitterBehind(const std::string& curves) {
    return "LookAt 0 0 -10  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 10\n"
           "PixelFilter \"box\"\nWorldBegin\n"
           "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 1] \"bool twosided\" true\n"
           "Shape \"bilinearmesh\" \"point3 P\" [-3 -3 0  3 -3 0  -3 3 0  3 3 0]\nAttributeEnd\n"
           "Material \"diffuse\" \"rgb reflectance\" [0 0 0]\n" +
           curves;
}

// A render of the scene at `path` by `integrator` on `backend`, `size` pixels square.
Image Render(const std::string& path, const std::string& backend, Integrator integrator,
             uint64_t seed, int size, uint32_t samples) {
    RenderSettings settings;
    settings.scene_path = path;
    settings.backend = backend;
    settings.threads = 2;
    settings.job.integrator = integrator;
    settings.job.seed = seed;
    settings.job.width = settings.job.height = size;
    settings.job.samples_per_pixel = samples;
    const absl::StatusOr<RenderOutcome> outcome = RenderLocally(settings);
    EXPECT_TRUE(outcome.ok()) << outcome.status();
    return outcome.ok() ? outcome->image : Image();
}

Image RenderText(const std::string& text, const std::string& backend) {
    const std::filesystem::path folder = testing::FreshTempDir("curves-emitter");
    std::ofstream(folder / "scene.pbrt") << text;
    return Render((folder / "scene.pbrt").string(), backend, Integrator::kPath, 1, 40, 64);
}

double MeanOf(const Image& image) {
    double sum = 0;
    for (const Rgb& p : image.pixels) sum += p.y;
    return image.pixels.empty() ? 0 : sum / double(image.pixels.size());
}

TEST(CurvesRenderTest, BlackCurvesHideTheShareOfAnEmitterTheirWidthCovers) {
    // Straight horizontal curves 1.2 long, 0.05 wide, 0.1 before the emitter: each hides
    // 0.05 x 1.2 of the 2 x 9.9 x tan(5 degrees) square the view spans there, against the
    // emitter alone: a flat curve, a cylinder, a ribbon facing the camera, and two ribbons
    // turned 60 degrees from the view, each showing half its width (one above the axis, one
    // below, so that the perspective's tilt cancels). By the path tracer on the CPU (the Vulkan
    // backend follows its paths on the scene of curves: tests/worker/vulkan_pixel_test.cpp).
    const double side = 2 * 9.9 * std::tan(5.0 * M_PI / 180);
    const auto row = [](float y, const std::string& type) {
        return absl::StrFormat(
            "Shape \"curve\" \"point3 P\" [-0.6 %g -0.1  -0.2 %g -0.1  0.2 %g -0.1  0.6 %g "
            "-0.1] \"float width\" 0.05 %s\n",
            y, y, y, y, type);
    };
    const std::string turned =
        "\"string type\" \"ribbon\" \"normal N\" [0 0.8660254 -0.5  0 0.8660254 -0.5]";
    const std::string curves =
        row(-0.6f, "\"string type\" \"flat\"") + row(-0.3f, turned) +
        row(0.0f, "\"string type\" \"cylinder\"") + row(0.3f, turned) +
        row(0.6f, "\"string type\" \"ribbon\" \"normal N\" [0 0 -1  0 0 -1]");
    const double hidden = 4 * 0.05 * 1.2 / (side * side);
    // The emitter alone (its radiance, which the view holds everywhere: the same on both).
    const double open = MeanOf(RenderText(EmitterBehind(""), "cpu"));
    ASSERT_GT(open, 0.0);
    // 64 samples a pixel, each seeing the emitter or a curve: the mean's error is below
    // sqrt(h (1 - h) / samples) ~ 3e-3 h, a third of the 1% allowed.
    const double seen = MeanOf(RenderText(EmitterBehind(curves), "cpu")) / open;
    EXPECT_NEAR(seen, 1 - hidden, 0.01 * hidden) << "hidden " << hidden;
}

}  // namespace
}  // namespace pf
