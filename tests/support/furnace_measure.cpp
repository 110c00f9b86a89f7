// Measuring a white furnace render (numerics_cases.h): the pixels that see one face of the box
// in a full disc, the standard deviation of their mean, the furnace pass traced and checked.
#include <absl/strings/str_format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "core/camera/camera_pass.h"
#include "core/estimate/estimator.h"
#include "core/film/image_metrics.h"
#include "core/scene_io/scene_loader.h"
#include "embedded/local_render.h"
#include "embree/embree_tracer.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/image_agreement.h"
#include "tests/support/numerics_cases.h"
#include "tests/support/test_env.h"

namespace pf::testing {

double FurnaceMeanSigma(double rho, double photons, double area_fraction, double direct_samples) {
    constexpr double kappa = 1;  // the relative variance of a deposit's weight, at most
    const double r = 1 / rho + ((1 + kappa) / area_fraction - 1) * (1 - rho) / rho;
    return std::sqrt(std::pow(rho, 4) * r / photons +
                     0.5 * rho * rho * (1 - rho) * (1 - rho) / direct_samples);
}

BoxInterior BoxInteriorPixels(const std::string& scene_path, int width, int height, double radius) {
    BoxInterior interior;
    interior.pixels.assign(static_cast<size_t>(width) * height, false);
    const absl::StatusOr<Scene> scene = LoadScene(scene_path);
    if (!scene.ok()) return interior;
    const Bounds& box = scene->bounds;
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    // Where the camera ray through film position (x, y) leaves the box: the point, its face
    // (axis and side) and the point's distance to the face's edges.
    struct Exit {
        Vec3 point;
        int face = -1;
        double edge_distance = 0;
    };
    const auto exit = [&](float x, float y) {
        const Ray ray = scene->camera.GenerateRay(x, y, aspect);
        Exit e;
        float nearest = std::numeric_limits<float>::infinity();
        for (int a = 0; a < 3; ++a) {
            if (ray.direction[a] == 0) continue;
            const bool upper = ray.direction[a] > 0;
            const float t =
                ((upper ? box.upper[a] : box.lower[a]) - ray.origin[a]) / ray.direction[a];
            if (t < nearest) nearest = t, e.face = 2 * a + upper;
        }
        e.point = ray.origin + ray.direction * nearest;
        e.edge_distance = std::numeric_limits<double>::infinity();
        for (int a = 0; a < 3; ++a)
            if (a != e.face / 2)
                e.edge_distance = std::min({e.edge_distance, double(e.point[a] - box.lower[a]),
                                            double(box.upper[a] - e.point[a])});
        return e;
    };
    const Vec3 extent = box.upper - box.lower;
    const double box_area = 2.0 * (double(extent.x) * extent.y + double(extent.y) * extent.z +
                                   double(extent.z) * extent.x);
    double area = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            // The distance to the edges is concave on a face, so its least over the pixel's
            // footprint (a convex quad, where the four corners meet one face) is at a corner.
            Exit corners[4];
            for (int c = 0; c < 4; ++c)
                corners[c] = exit(static_cast<float>(x + c % 2) / static_cast<float>(width),
                                  static_cast<float>(y + c / 2) / static_cast<float>(height));
            bool inside = true;
            for (const Exit& corner : corners)
                inside = inside && corner.face == corners[0].face && corner.edge_distance > radius;
            if (!inside) continue;
            interior.pixels[static_cast<size_t>(y) * width + x] = true;
            ++interior.count;
            // A planar quad's area: half the cross product of its diagonals.
            area += 0.5 * Length(Cross(corners[3].point - corners[0].point,
                                       corners[1].point - corners[2].point));
        }
    interior.area_fraction = area / box_area;
    return interior;
}

double FurnaceCheck::MeanError() const {
    return std::max({std::abs(mean.x / expected - 1), std::abs(mean.y / expected - 1),
                     std::abs(mean.z / expected - 1)});
}

bool FurnaceCheck::Passed() const {
    return MeanError() <= 4 * sigma && std::abs(median / expected - 1) <= median_bound;
}

std::string FurnaceCheck::Describe() const {
    return absl::StrFormat(
        "RGB means %.5f %.5f %.5f against %.5f (worst %.3f%%, allowed %.3f%%); median %.5f "
        "(allowed %.3f%%, pixel deviation %.3f%%); %d pixels",
        mean.x, mean.y, mean.z, expected, 100 * MeanError(), 400 * sigma, median,
        100 * median_bound, 100 * pixel_deviation, pixels);
}

FurnaceCheck CheckFurnace(const Image& image, const BoxInterior& interior, double expected,
                          double sigma, const Rgbd& bias) {
    FurnaceCheck check;
    check.expected = expected;
    check.pixels = interior.count;
    std::vector<double> values;
    for (size_t p = 0; p < image.pixels.size(); ++p) {
        if (!interior.pixels[p]) continue;
        const Rgbd pixel = Rgbd(image.pixels[p]) * bias;
        check.mean = check.mean + pixel;
        values.push_back((pixel.x + pixel.y + pixel.z) / 3);
    }
    if (values.size() < 2) return check;  // fails: no mean, no bound
    const double n = static_cast<double>(values.size());
    check.mean = check.mean / n;
    const double average = (check.mean.x + check.mean.y + check.mean.z) / 3;
    double squares = 0;
    for (double value : values) squares += (value - average) * (value - average);
    check.pixel_deviation = std::sqrt(squares / (n - 1)) / expected;
    check.sigma = sigma >= 0 ? sigma : check.pixel_deviation / std::sqrt(n);
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    check.median = values[values.size() / 2];
    check.median_bound = check.pixel_deviation * (1 + 4 * 1.2533 / std::sqrt(n));
    return check;
}

FurnacePass TraceFurnacePass(const std::string& scene_path, const JobSpec& job, double radius) {
    FurnacePass pass;
    const absl::StatusOr<Scene> scene = LoadScene(scene_path);
    if (!scene.ok()) return pass;
    const absl::StatusOr<std::unique_ptr<embree::EmbreeTracer>> tracer =
        embree::EmbreeTracer::Create(*scene);
    const absl::StatusOr<CameraPassSettings> film = FilmFor(job, *scene);
    if (!tracer.ok() || !film.ok()) return pass;
    const CameraPassResult camera_pass = RunCameraPass(*scene, Emitters(*scene), **tracer, *film);
    pass.hit_points = camera_pass.hit_points.size();
    pass.initial_radius = DefaultInitialRadius(camera_pass, *scene);
    pass.emission = camera_pass.emission;
    const int width = film->width, height = film->height;
    pass.flat.assign(static_cast<size_t>(width) * height, true);
    pass.through_glass.assign(pass.flat.size(), false);
    // A hit point lies on the wall it is nearest; its distance to that wall's edges is the least
    // over the other two axes of its distance to the box's faces.
    const Bounds& box = scene->bounds;
    for (const HitPoint& hit_point : camera_pass.hit_points) {
        const Vec3& p = hit_point.position;
        int wall = 0;
        float nearest = std::numeric_limits<float>::infinity();
        for (int a = 0; a < 3; ++a) {
            const float d = std::min(std::abs(p[a] - box.lower[a]), std::abs(box.upper[a] - p[a]));
            if (d < nearest) nearest = d, wall = a;
        }
        double edge = std::numeric_limits<double>::infinity();
        for (int a = 0; a < 3; ++a)
            if (a != wall)
                edge = std::min({edge, double(p[a] - box.lower[a]), double(box.upper[a] - p[a])});
        if (!(edge > radius)) pass.flat[hit_point.pixel] = false;
    }
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            bool glass = true;
            for (int c = 0; c < 5; ++c) {
                const float fx = c < 4 ? static_cast<float>(x + c % 2) : x + 0.5f;
                const float fy = c < 4 ? static_cast<float>(y + c / 2) : y + 0.5f;
                RayHit hit;
                const Ray ray = scene->camera.GenerateRay(fx / static_cast<float>(width),
                                                          fy / static_cast<float>(height), aspect);
                glass = glass && (*tracer)->Intersect(ray, &hit) &&
                        hit.instance == Instance::kNone &&
                        scene->materials[scene->triangles[hit.triangle].material].type ==
                            MaterialType::kDielectric;
            }
            pass.through_glass[static_cast<size_t>(y) * width + x] = glass;
        }
    return pass;
}

Rgbd MedianEmission(const FurnacePass& pass, const std::vector<bool>& region) {
    Rgbd median(0.0);
    for (int c = 0; c < 3; ++c) {
        std::vector<double> values;
        for (size_t p = 0; p < region.size(); ++p)
            if (region[p]) values.push_back(pass.emission.pixels[p][c]);
        if (values.empty()) continue;
        std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
        median[c] = values[values.size() / 2];
    }
    return median;
}

bool FurnaceStreamsCheck::Passed() const {
    if (renders < 2 || pixels == 0) return false;
    for (int c = 0; c < 3; ++c)
        if (!(std::abs(error[c]) <= Limit(c))) return false;
    return true;
}

double FurnaceStreamsCheck::DetectableBias() const {
    double worst = 0;
    for (int c = 0; c < 3; ++c) worst = std::max(worst, Limit(c) + 3.1 * sigma[c]);
    return worst;
}

std::string FurnaceStreamsCheck::Describe() const {
    return absl::StrFormat(
        "RGB %+.3f%% %+.3f%% %+.3f%% of emission/(1-rho) over %d pixels, allowed %.3f%% %.3f%% "
        "%.3f%% (sigma %.3f%% %.3f%% %.3f%% from %d draws, t %.2f, known bias %.3f%%); "
        "catches %.2f%%",
        100 * error.x, 100 * error.y, 100 * error.z, pixels, 100 * Limit(0), 100 * Limit(1),
        100 * Limit(2), 100 * sigma.x, 100 * sigma.y, 100 * sigma.z, renders, quantile,
        100 * known_bias, 100 * DetectableBias());
}

FurnaceStreamsCheck CheckFurnaceStreams(const std::vector<Image>& renders, const FurnacePass& pass,
                                        const std::vector<bool>& region, double rho,
                                        double known_bias, const Rgbd& bias) {
    FurnaceStreamsCheck check;
    check.renders = static_cast<int>(renders.size());
    check.known_bias = known_bias;
    Rgbd expected(0.0);
    for (size_t p = 0; p < region.size(); ++p)
        if (region[p]) expected += Rgbd(pass.emission.pixels[p]) / (1 - rho), ++check.pixels;
    if (check.renders < 2 || check.pixels == 0) return check;
    std::vector<Rgbd> errors;
    for (const Image& render : renders) {
        Rgbd sum(0.0);
        for (size_t p = 0; p < region.size(); ++p)
            if (region[p]) sum += Rgbd(render.pixels[p]) * bias;
        errors.push_back(sum / expected - Rgbd(1.0));
    }
    const double k = static_cast<double>(renders.size());
    for (const Rgbd& e : errors) check.error += e / k;
    Rgbd squares(0.0);
    for (const Rgbd& e : errors) squares += (e - check.error) * (e - check.error);
    for (int c = 0; c < 3; ++c) check.sigma[c] = std::sqrt(squares[c] / (k - 1) / k);
    check.quantile = StudentTQuantile(kFalseAlarm / 2, k - 1);
    return check;
}

absl::StatusOr<EpochDraws> RenderEpochDraws(RenderSettings settings) {
    JobSpec& job = settings.job;
    const uint64_t per_epoch = job.layout.PhotonsPerEpoch();
    if (job.integrator != Integrator::kPpm || job.alpha != 1.0 || per_epoch == 0 ||
        job.photon_budget % per_epoch != 0)
        return absl::InvalidArgumentError("epoch draws need ppm, alpha 1 and whole epochs");
    job.layout.first_epoch_photons = per_epoch;  // every epoch full, none growing
    EpochDraws draws;
    std::vector<Rgbd> previous;  // k - 1 times I_k-1, per pixel
    bool whole_epochs = true;
    const absl::StatusOr<RenderOutcome> outcome =
        RenderLocally(settings, [&](const RenderProgress& progress, const Job& rendering) {
            const std::shared_ptr<const Image> image = rendering.CurrentImage();
            const uint64_t k = progress.epochs;
            whole_epochs = whole_epochs && image && k == draws.epochs.size() + 1 &&
                           progress.photons == k * per_epoch;
            if (!whole_epochs) return;
            if (previous.empty()) previous.assign(image->pixels.size(), Rgbd(0.0));
            Image draw(image->width, image->height);
            for (size_t p = 0; p < image->pixels.size(); ++p) {
                const Rgbd sum = Rgbd(image->pixels[p]) * static_cast<double>(k);
                draw.pixels[p] = Rgb(sum - previous[p]);
                previous[p] = sum;
            }
            draws.epochs.push_back(std::move(draw));
        });
    if (!outcome.ok()) return outcome.status();
    if (!whole_epochs || draws.epochs.size() != outcome->progress.epochs)
        return absl::InternalError("an epoch's image was missed or held a part of an epoch");
    draws.outcome = *outcome;
    return draws;
}

}  // namespace pf::testing
