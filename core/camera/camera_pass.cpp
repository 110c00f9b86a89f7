// Tracing camera paths to hit points.
#include "core/camera/camera_pass.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/camera/gather_ray.h"
#include "core/camera/pixel_sample.h"
#include "core/math/morton.h"
#include "core/sampling/rng.h"
#include "core/sampling/sampling.h"
#include "core/scene/glossy_lights.h"
#include "core/scene/scattering.h"
#include "core/util/check.h"

namespace pf {
namespace {

// The random numbers of camera paths past their first pair or two (PixelSampler), and the
// camera samples of the fixed, the stochastic and the emission passes.
constexpr uint64_t kCameraStream = 0x63616d657261ull;
constexpr uint64_t kFixedSampleStream = 0x6669786564ull;
constexpr uint64_t kStochasticSampleStream = 0x73707070ull;
constexpr uint64_t kEmissionSampleStream = 0x656d6974ull;

// A camera path in flight: where it goes and what it carries.
struct CameraPath {
    Ray ray;
    Rgb throughput;
    float length = 0;  // distance travelled, for the pixel footprint
    int depth = 0;
    int splits_left = 0;  // glass interfaces still to split rather than choose at random
    // The product of the refractions' scales of radiance in throughput (RefractionScale), which
    // Russian roulette leaves out: a path inside glass is not less worth following (pbrt-v4's
    // etaScale).
    float refraction = 1.0f;
};

// Reverse photon mapping's gather hits of the camera hit point just appended (hit_points'
// last): `rays` cosine-weighted final-gather rays about its normal, each leaving one slot,
// where it lands on a diffuse surface (FollowToDiffuse), weighted so that the slot's photon
// estimate is the ray's share of the light the camera hit point reflects; black where it finds
// none. The camera hit point keeps the caustics alone (direct light is sampled there); under
// a coat, which gather rays would have to cross, it keeps every scattered photon as ppm's do
// and its gather slots stay black.
void TraceGatherHits(const Scene& scene, const Tracer& tracer, const Vec3& geometric_normal,
                     int rays, Rng& rng, std::vector<HitPoint>& hit_points,
                     std::vector<float>& footprints) {
    HitPoint& camera_hit = hit_points.back();
    const HitPoint origin_point = camera_hit;
    const float footprint = footprints.back();
    const bool coated = camera_hit.coat != kNoCoat;
    camera_hit.gathers = coated ? kScatteredPhotons : kCausticPhoton;
    const Vec3 geometric =
        Dot(origin_point.normal, geometric_normal) >= 0 ? geometric_normal : -geometric_normal;
    const Vec3 origin = OffsetRayOrigin(origin_point.position, geometric, scene.bounds.Magnitude());
    const Frame frame = FrameFromNormal(origin_point.normal);
    // camera weight x albedo / pi x (pi / rays) x the landing's albedo / pi, per unit of the
    // landing's photon flux density: the estimate of one gather ray's light.
    const Rgb weight = origin_point.weight / static_cast<float>(rays);
    for (int i = 0; i < rays; ++i) {
        std::optional<DiffuseLanding> landing;
        if (!coated) {
            const float u1 = rng.NextFloat();
            const float u2 = rng.NextFloat();
            const Vec3 direction = ToWorld(frame, SampleCosineHemisphere(u1, u2));
            if (Dot(direction, geometric) > 0)
                landing = FollowToDiffuse(scene, tracer, {origin, direction}, rng);
        }
        if (landing)
            hit_points.push_back({landing->position, landing->normal,
                                  weight * landing->weight * landing->albedo, origin_point.pixel,
                                  landing->coat, kAllPhotons});
        else
            hit_points.push_back({Vec3(0.0f), Vec3(0.0f, 0.0f, 1.0f), Rgb(0.0f), origin_point.pixel,
                                  kNoCoat, kAllPhotons});
        footprints.push_back(footprint);
    }
}

// Traces one camera sample; appends the hit points it reaches and returns the emission it saw.
// At its first `splits` (up to kCameraSplits) glass interfaces the path follows both reflection and
// transmission, each weighted by its probability, instead of choosing one at random: the few
// percent of reflection on glass would otherwise show as speckle, since hit points are kept.
// Instantiated for the scene's features: without specular materials every path ends at its
// first hit, without textures every base colour is the material's. A translucent surface
// gives a hit point on each side (the one facing away gathers the light let through), both
// where the path still splits, else one chosen (ChooseDiffuseSide).
// Textures are filtered over the sample's share of the pixel's cone (the pixel's angle over
// the square root of its samples, as pbrt-v4 scales its ray differentials).
// Where the scene has punctual lights (`punctual`), a path at a glossy surface takes them by
// light sampling (core/scene/glossy_lights.h), added to the emission it saw.
template <bool kSpecular, bool kTextures>
Rgb TraceCameraSample(const Scene& scene, const Emitters& emitters, bool punctual,
                      const Tracer& tracer, const CameraRay& primary, uint32_t pixel,
                      PixelFootprint pixel_width, PixelFootprint filter_width, int splits,
                      int max_depth, int gather_rays, Rng& rng, std::vector<HitPoint>& hit_points,
                      std::vector<float>& footprints) {
    Rgb emission(0.0f);
    CameraPath stack[kCameraSplits + 1];
    int pending = 0;
    stack[pending++] = {primary.ray, Rgb(primary.weight), 0.0f, 0, splits};
    while (pending > 0) {
        CameraPath path = stack[--pending];
        for (; path.depth < max_depth; ++path.depth) {
            RayHit hit;
            if (!tracer.Intersect(path.ray, &hit)) {
                // Escaped: the environment, seen directly or through specular bounces.
                if (scene.environment)
                    emission += path.throughput * scene.environment->RadianceFrom(
                                                      path.ray.origin, path.ray.direction);
                break;
            }
            path.length += hit.t;
            const SurfacePoint surface = scene.Surface(hit);
            std::optional<Material> shading;  // where a texture sets the roughness
            const Material& material = scene.ShadingMaterial(surface, shading);
            const Bsdf bsdf = BsdfOf(material);
            const bool front_facing = Dot(path.ray.direction, surface.geometric_normal) < 0;
            if (kSpecular)
                path.throughput *= SegmentTransmittance(
                    material.absorption, material.outside_absorption, front_facing, hit.t);
            if (material.EmitsToward(front_facing))
                emission += path.throughput * scene.Emission(surface);
            const Rgb base_color =
                kTextures
                    ? scene.BaseColor(surface, filter_width.base + path.length * filter_width.angle)
                    : material.base_color;
            const Vec3& n = surface.shading_normal;
            if (kSpecular && punctual && GlossyToPunctualLights(bsdf))
                emission += path.throughput * PunctualLightOnGloss(emitters, tracer, surface, bsdf,
                                                                   base_color, front_facing,
                                                                   -path.ray.direction, rng);
            SpecularBounce bounce;
            if (!kSpecular || material.type == MaterialType::kDiffuse) {
                CoatArrival arrival;
                if (kSpecular && material.HasCoat() && path.splits_left > 0) {
                    // A hit point on the base and the coat's reflection both, each weighed by
                    // its probability, rather than one of them.
                    const Frame frame = FrameFromNormal(front_facing ? n : -n);
                    const float u1 = rng.NextFloat();
                    const float u2 = rng.NextFloat();
                    // Which reflection, the sheen's or the coat's: drawn only under a sheen.
                    const float u_branch = material.HasSheen() ? rng.NextFloat() : 1.0f;
                    Vec3 wi;
                    Rgb reflected;
                    const gpu::Coat& coat = bsdf.coat;
                    const float entered = gpu::SplitAtCoat(
                        coat, ToLocal(frame, -path.ray.direction), u_branch, u1, u2, wi, reflected);
                    hit_points.push_back(
                        {surface.position, frame.n,
                         path.throughput * base_color * (entered * CoatInside(coat) / kPi), pixel,
                         surface.material});
                    footprints.push_back(pixel_width.base + path.length * pixel_width.angle);
                    --path.splits_left;
                    arrival = {false, 0.0f, {ToWorld(frame, wi), reflected, false}};
                } else if (kSpecular) {
                    arrival = ArriveAtCoat(bsdf, path.ray.direction, n, front_facing, rng.State());
                }
                if (arrival.at_base) {
                    // What the radiance at the base is worth under a coat (CoatInside).
                    const float coat =
                        material.HasCoat() ? arrival.weight * CoatInside(bsdf.coat) : 1.0f;
                    const Vec3 normal = front_facing ? n : -n;
                    const auto add = [&](const Vec3& facing, const Rgb& albedo) {
                        hit_points.push_back({surface.position, facing,
                                              path.throughput * albedo * (coat / kPi), pixel,
                                              material.HasCoat() ? surface.material : kNoCoat});
                        footprints.push_back(pixel_width.base + path.length * pixel_width.angle);
                    };
                    if (!kSpecular || !material.IsTranslucent()) {
                        add(normal, base_color);
                    } else if (path.splits_left > 0) {
                        // Both sides of a translucent surface, rather than one of them.
                        add(normal, base_color);
                        add(-normal, material.transmittance);
                    } else {
                        const DiffuseSide side = ChooseDiffuseSide(bsdf, base_color, rng.State());
                        add(side.through ? -normal : normal, side.albedo);
                    }
                    if (gather_rays > 0)
                        TraceGatherHits(scene, tracer, surface.geometric_normal, gather_rays, rng,
                                        hit_points, footprints);
                    break;
                }
                bounce = arrival.reflected;
            } else if (const float reflect =
                           ReflectionProbability(bsdf, path.ray.direction, n, front_facing);
                       path.splits_left > 0 && reflect > 0 && reflect < 1) {
                // Continue with the reflection; the transmission waits on the stack.
                const SpecularBounce transmitted = TransmitSpecular(
                    bsdf, path.ray.direction, n, front_facing, base_color, kCarriesRadiance);
                CameraPath& other = stack[pending++];
                other = path;
                other.throughput *= transmitted.weight * (1.0f - reflect);
                if (transmitted.transmitted) other.refraction *= RefractionOf(bsdf, front_facing);
                other.ray = {OffsetRayOrigin(surface.position,
                                             front_facing ? -surface.geometric_normal
                                                          : surface.geometric_normal,
                                             scene.bounds.Magnitude()),
                             transmitted.direction};
                ++other.depth;
                --other.splits_left;
                --path.splits_left;
                bounce = ReflectSpecular(bsdf, path.ray.direction, n, front_facing, base_color);
                bounce.weight *= reflect;
            } else {
                bounce = ScatterNonDiffuse(bsdf, path.ray.direction, n, front_facing, base_color,
                                           rng.State(), kCarriesRadiance);
            }
            path.throughput *= bounce.weight;
            if (bounce.transmitted) path.refraction *= RefractionOf(bsdf, front_facing);
            if (path.depth >= kCameraRouletteDepth) {
                const float survive =
                    std::min(1.0f, MaxComponent(path.throughput) / path.refraction);
                if (!(rng.NextFloat() < survive)) break;
                path.throughput /= survive;
            }
            if (IsBlack(path.throughput)) break;
            const Vec3 side = front_facing == bounce.transmitted ? -surface.geometric_normal
                                                                 : surface.geometric_normal;
            path.ray = {OffsetRayOrigin(surface.position, side, scene.bounds.Magnitude()),
                        bounce.direction};
        }
    }
    return emission;
}

// Indices of hit_points sorted by the Morton code of their position in bounds (ties by index,
// so the order is deterministic).
std::vector<uint32_t> MortonOrder(const std::vector<HitPoint>& hit_points, const Bounds& bounds) {
    const Vec3 extent = Max(bounds.upper - bounds.lower, Vec3(1e-30f));
    std::vector<std::pair<uint64_t, uint32_t>> keys(hit_points.size());
    for (size_t i = 0; i < hit_points.size(); ++i) {
        keys[i] = {MortonCode(hit_points[i].position, bounds.lower, extent),
                   static_cast<uint32_t>(i)};
    }
    std::sort(keys.begin(), keys.end());
    std::vector<uint32_t> order(keys.size());
    for (size_t i = 0; i < keys.size(); ++i) order[i] = keys[i].second;
    return order;
}

}  // namespace

PixelHitPoints PixelHitPoints::Index(std::shared_ptr<const std::vector<HitPoint>> points,
                                     size_t pixels) {
    PixelHitPoints index = Index(std::span<const HitPoint>(*points), pixels);
    index.owner = std::move(points);
    return index;
}

PixelHitPoints PixelHitPoints::Index(std::span<const HitPoint> points, size_t pixels) {
    PixelHitPoints index;
    index.points = points;
    const std::span<const HitPoint> all = points;
    // A counting sort by pixel, stable.
    index.begin.assign(pixels + 1, 0);
    for (const HitPoint& point : all) {
        PF_CHECK(point.pixel < pixels);
        ++index.begin[point.pixel + 1];
    }
    std::partial_sum(index.begin.begin(), index.begin.end(), index.begin.begin());
    const auto by_pixel = [](const HitPoint& a, const HitPoint& b) { return a.pixel < b.pixel; };
    if (std::is_sorted(all.begin(), all.end(), by_pixel)) return index;
    index.order.resize(all.size());
    std::vector<uint32_t> cursor(index.begin.begin(), index.begin.end() - 1);
    for (size_t i = 0; i < all.size(); ++i)
        index.order[cursor[all[i].pixel]++] = static_cast<uint32_t>(i);
    return index;
}

std::optional<uint32_t> CoveringHitPoint(const PixelHitPoints& fixed, uint32_t pixel,
                                         const HitPoint& hit) {
    std::optional<uint32_t> nearest, nearest_facing;
    float distance = 0, distance_facing = 0;
    for (uint32_t k = fixed.begin[pixel]; k < fixed.begin[pixel + 1]; ++k) {
        const HitPoint& candidate = fixed.points[fixed.At(k)];
        if (IsBlack(candidate.weight)) continue;
        const float d = LengthSquared(candidate.position - hit.position);
        if (!nearest || d < distance) nearest = k, distance = d;
        if (Dot(candidate.normal, hit.normal) >= 0.5f && (!nearest_facing || d < distance_facing))
            nearest_facing = k, distance_facing = d;
    }
    return nearest_facing ? nearest_facing : nearest;
}

CameraPassResult RunCameraPass(const Scene& scene, const Emitters& emitters, const Tracer& tracer,
                               const CameraPassSettings& settings, const PixelHitPoints* fixed) {
    const int width = settings.width, height = settings.height, spp = settings.samples_per_pixel;
    const Film film{width, height, spp};
    const FilterSampler filter(scene.camera.filter);
    // Textures are filtered over a sample's share of the pixel.
    const PixelFootprint pixel_width = scene.camera.Footprint(height);
    const float share = 1.0f / std::sqrt(static_cast<float>(settings.samples_per_pixel));
    const PixelFootprint filter_width{pixel_width.base * share, pixel_width.angle * share};
    const int splits = settings.stochastic ? 0 : kCameraSplits;
    PF_CHECK(settings.gather_rays == 0 || (settings.stochastic && !settings.emission_only));
    const int gather_rays = settings.gather_rays;
    const int max_depth = DepthLimit(settings.max_depth, kMaxCameraDepth);
    const uint64_t sample_stream = settings.stochastic      ? kStochasticSampleStream
                                   : settings.emission_only ? kEmissionSampleStream
                                                            : kFixedSampleStream;

    // The pixels traced: all, or a part (CameraPassSettings::first_pixel) of a stochastic pass
    // or of an emission pass.
    const uint64_t pixels = uint64_t(width) * uint64_t(height);
    const uint64_t first_pixel = settings.first_pixel;
    const uint64_t end_pixel =
        settings.pixel_count == 0 ? pixels : first_pixel + settings.pixel_count;
    const bool part = end_pixel - first_pixel < pixels;
    PF_CHECK(first_pixel <= end_pixel && end_pixel <= pixels &&
             (!part || settings.stochastic || settings.emission_only));
    std::vector<std::vector<HitPoint>> row_hit_points(height);
    std::vector<std::vector<float>> row_footprints(height);
    CameraPassResult result;
    // A part's emission is a row of its pixels.
    result.emission =
        part ? Image(static_cast<int>(end_pixel - first_pixel), 1) : Image(width, height);
    PF_CHECK(fixed == nullptr || (settings.emission_only && fixed->begin.size() == pixels + 1));
    // Each fixed hit point lies in one pixel, so rows in parallel credit disjoint ones.
    const uint32_t first_covered = fixed != nullptr ? fixed->begin[first_pixel] : 0;
    if (fixed != nullptr)
        result.coverage.assign(fixed->begin[end_pixel] - first_covered, Rgb(0.0f));
    // The camera path for the scene's features, chosen once.
    const SceneFeatures& features = settings.features;
    const auto trace = features.GeneralSurfaces()
                           ? (features.VaryingBaseColor() ? TraceCameraSample<true, true>
                                                          : TraceCameraSample<true, false>)
                           : (features.VaryingBaseColor() ? TraceCameraSample<false, true>
                                                          : TraceCameraSample<false, false>);
    const auto first_row = static_cast<int>(first_pixel / width);
    const auto end_row = static_cast<int>((end_pixel + width - 1) / width);
    tbb::parallel_for(
        tbb::blocked_range<int>(first_row, end_row), [&](const tbb::blocked_range<int>& rows) {
            for (int y = rows.begin(); y < rows.end(); ++y) {
                const uint64_t row = uint64_t(y) * width;
                const auto x_begin = static_cast<int>(std::max(first_pixel, row) - row);
                const auto x_end = static_cast<int>(std::min(end_pixel, row + width) - row);
                for (int x = x_begin; x < x_end; ++x) {
                    const auto pixel = static_cast<uint32_t>(y * width + x);
                    Rng rng(HashSeed(settings.seed, kCameraStream ^ sample_stream, settings.epoch,
                                     pixel));
                    Rgb emission(0.0f);
                    for (int s = 0; s < spp; ++s) {
                        PixelSampler sampler = PixelSampler::InEpochSequence(
                            settings.seed, sample_stream, pixel, settings.epoch,
                            settings.first_sample + uint64_t(s));
                        const CameraRay ray =
                            PixelSampleRay(scene.camera, film, filter, x, y, sampler);
                        const size_t before = row_hit_points[y].size();
                        emission += trace(scene, emitters, features.PunctualLights(), tracer, ray,
                                          pixel, pixel_width, filter_width, splits, max_depth,
                                          gather_rays, rng, row_hit_points[y], row_footprints[y]);
                        // A stochastic pass keeps 1 + gather_rays slots per sample (one without
                        // gather rays), black where it found nothing.
                        if (settings.stochastic && row_hit_points[y].size() == before) {
                            for (int slot = 0; slot <= gather_rays; ++slot) {
                                row_hit_points[y].push_back(
                                    {Vec3(0.0f), Vec3(0.0f, 0.0f, 1.0f), Rgb(0.0f), pixel, kNoCoat,
                                     slot == 0 && gather_rays > 0 ? kCausticPhoton : kAllPhotons});
                                row_footprints[y].push_back(0.0f);
                            }
                        }
                    }
                    result.emission.pixels[pixel - first_pixel] =
                        emission / static_cast<float>(spp);
                    if (settings.emission_only) {  // no hit points kept
                        if (fixed != nullptr) {
                            for (const HitPoint& hit : row_hit_points[y])
                                if (const std::optional<uint32_t> k =
                                        CoveringHitPoint(*fixed, pixel, hit))
                                    result.coverage[*k - first_covered] += hit.weight;
                            // averaged over the pixel's samples
                            for (uint32_t k = fixed->begin[pixel]; k < fixed->begin[pixel + 1]; ++k)
                                result.coverage[k - first_covered] /= static_cast<float>(spp);
                        }
                        row_hit_points[y].clear();
                        row_footprints[y].clear();
                    }
                }
            }
        });
    if (settings.emission_only) return result;
    std::vector<HitPoint> hit_points;
    std::vector<float> footprints;
    for (int y = 0; y < height; ++y) {
        hit_points.insert(hit_points.end(), row_hit_points[y].begin(), row_hit_points[y].end());
        footprints.insert(footprints.end(), row_footprints[y].begin(), row_footprints[y].end());
    }
    if (settings.stochastic) {  // slots stay in pixel order: slot i is the state's index i
        result.hit_points = std::move(hit_points);
        result.footprint = std::move(footprints);
        return result;
    }
    // Order hit points along a Morton curve: those a photon finds together then lie together
    // in memory, for the grid's candidates and the tally's sums alike.
    const std::vector<uint32_t> order = MortonOrder(hit_points, scene.bounds);
    result.hit_points.reserve(order.size());
    result.footprint.reserve(order.size());
    for (uint32_t index : order) {
        result.hit_points.push_back(hit_points[index]);
        result.footprint.push_back(footprints[index]);
    }
    return result;
}

namespace {

// `film` with the camera samples of epoch `epoch` of job `spec`.
CameraPassSettings EpochPass(const CameraPassSettings& film, const JobSpec& spec, uint64_t epoch) {
    const uint64_t pixels = uint64_t(film.width) * uint64_t(film.height);
    const EpochSamples samples = EpochCameraSamples(spec.integrator, film.samples_per_pixel,
                                                    ResolvedLayout(spec, pixels), pixels, epoch);
    CameraPassSettings settings = film;
    settings.samples_per_pixel = samples.per_pixel;
    settings.epoch = epoch;
    settings.first_sample = samples.first;
    return settings;
}

}  // namespace

CameraPassSettings StochasticCameraPass(const CameraPassSettings& film, const JobSpec& spec,
                                        uint64_t epoch) {
    CameraPassSettings settings = EpochPass(film, spec, epoch);
    settings.stochastic = true;
    return settings;
}

void CameraPassPart::Reset(const CameraPassSettings& pass) {
    PF_CHECK(pass.stochastic && pass.pixel_count == 0);
    pass_ = pass;
    slots_per_pixel_ = uint64_t(pass.samples_per_pixel) * uint64_t(1 + pass.gather_rays);
    points_.clear();
    first_pixel_ = end_pixel_ = 0;
}

bool CameraPassPart::Cover(const Scene& scene, const Emitters& emitters, const Tracer& tracer,
                           std::span<const BatchSpec> specs) {
    uint64_t begin = UINT64_MAX, end = 0;
    for (const BatchSpec& spec : specs)
        if (spec.sample_end > spec.sample_begin) {
            begin = std::min<uint64_t>(begin, spec.sample_begin);
            end = std::max<uint64_t>(end, spec.sample_end);
        }
    if (begin >= end) return false;
    const uint64_t first_pixel = begin / slots_per_pixel_;
    const uint64_t end_pixel = (end + slots_per_pixel_ - 1) / slots_per_pixel_;
    if (first_pixel >= first_pixel_ && end_pixel <= end_pixel_) return false;
    CameraPassSettings part = pass_;
    part.first_pixel = static_cast<uint32_t>(first_pixel);
    part.pixel_count = static_cast<uint32_t>(end_pixel - first_pixel);
    points_ = RunCameraPass(scene, emitters, tracer, part).hit_points;
    PF_CHECK(points_.size() == (end_pixel - first_pixel) * slots_per_pixel_);
    first_pixel_ = first_pixel;
    end_pixel_ = end_pixel;
    return true;
}

absl::StatusOr<PixelHitPoints> IndexFixedHitPoints(std::span<const HitPoint> points,
                                                   const CameraPassSettings& film) {
    const uint64_t pixels = uint64_t(film.width) * uint64_t(film.height);
    for (size_t i = 0; i < points.size(); ++i)
        if (points[i].pixel >= pixels)
            return absl::InvalidArgumentError(
                absl::StrCat("hit point ", i, " lies in pixel ", points[i].pixel, " of ", pixels));
    return PixelHitPoints::Index(points, pixels);
}

void TraceBatchEmission(const Scene& scene, const Emitters& emitters, const Tracer& tracer,
                        const CameraPassSettings& pass, const PixelHitPoints& fixed,
                        std::span<BatchResult> results) {
    PF_CHECK(pass.emission_only && pass.gather_rays == 0);
    const auto slots_per_pixel = static_cast<uint64_t>(pass.samples_per_pixel);  // one a sample
    uint64_t first = UINT64_MAX, end = 0;
    for (const BatchResult& result : results) {
        const auto [begin, stop] = SlicePixels(result.spec, slots_per_pixel);
        if (begin < stop) first = std::min(first, begin), end = std::max(end, stop);
    }
    CameraPassResult traced;
    if (first < end) {
        CameraPassSettings part = pass;
        part.first_pixel = static_cast<uint32_t>(first);
        part.pixel_count = static_cast<uint32_t>(end - first);
        traced = RunCameraPass(scene, emitters, tracer, part, &fixed);
    }
    for (BatchResult& result : results) {
        const auto [begin, stop] = SlicePixels(result.spec, slots_per_pixel);
        result.emission.clear();
        result.coverage.clear();
        if (begin >= stop) continue;
        const auto pixels = traced.emission.pixels.begin();
        result.emission.assign(pixels + static_cast<ptrdiff_t>(begin - first),
                               pixels + static_cast<ptrdiff_t>(stop - first));
        const auto covered = traced.coverage.begin();
        result.coverage.assign(covered + (fixed.begin[begin] - fixed.begin[first]),
                               covered + (fixed.begin[stop] - fixed.begin[first]));
    }
}

CameraPassSettings EmissionCameraPass(const CameraPassSettings& film, const JobSpec& spec,
                                      uint64_t epoch) {
    CameraPassSettings settings = EpochPass(film, spec, epoch);
    settings.emission_only = true;
    return settings;
}

EpochCameraPass TracedCameraPasses(const Scene& scene, const Emitters& emitters,
                                   std::shared_ptr<const Tracer> tracer,
                                   const CameraPassSettings& film, const JobSpec& spec,
                                   SlotRadii radii) {
    PF_CHECK(TracesHitPointsEachEpoch(spec.integrator));
    return [&scene, &emitters, tracer = std::move(tracer), film, spec,
            radii = std::move(radii)](uint64_t epoch) {
        CameraPassResult pass =
            RunCameraPass(scene, emitters, *tracer, StochasticCameraPass(film, spec, epoch));
        if (radii) pass.radius = radii(pass.hit_points, pass.footprint);
        return pass;
    };
}

float DefaultInitialRadius(const CameraPassResult& camera_pass, const Scene& scene) {
    return std::min(MedianRadius(camera_pass.footprint, camera_pass.footprint),
                    0.01f * scene.bounds.Diagonal());
}

float MedianRadius(std::span<const float> radii, std::span<const float> footprint) {
    PF_CHECK(radii.size() == footprint.size());
    std::vector<float> kept;  // of the slots that hold a hit point
    for (size_t i = 0; i < radii.size(); ++i)
        if (footprint[i] > 0) kept.push_back(radii[i]);
    if (kept.empty()) return 0.0f;
    const auto middle = kept.begin() + static_cast<std::ptrdiff_t>(kept.size() / 2);
    std::nth_element(kept.begin(), middle, kept.end());
    return *middle;
}

absl::StatusOr<CameraPassSettings> FilmFor(const JobSpec& spec, const Scene& scene) {
    CameraPassSettings film{spec.width, spec.height, spec.samples_per_pixel, spec.seed};
    film.max_depth = spec.max_depth;
    if (spec.integrator == Integrator::kRpm)
        film.gather_rays = static_cast<int>(RpmGatherRays(spec.photon_map));
    const double aspect = scene.camera.aspect_ratio > 0 ? scene.camera.aspect_ratio : 1.0;
    if (film.width == 0 && film.height == 0) {
        film.width = scene.hints.width > 0 ? scene.hints.width : 512;
        film.height = scene.hints.height;
    }
    if (film.width == 0)
        film.width = std::max(1, static_cast<int>(std::lround(film.height * aspect)));
    if (film.height == 0)
        film.height = std::max(1, static_cast<int>(std::lround(film.width / aspect)));
    const uint64_t pixels = uint64_t(film.width) * uint64_t(film.height);
    if (!GathersAtHitPoints(spec.integrator)) {  // they keep a sum per pixel, whatever the spp
        if (pixels > kMaxHitPoints)
            return absl::ResourceExhaustedError(
                absl::StrFormat("%dx%d = %d pixels exceeds the limit of %d", film.width,
                                film.height, pixels, kMaxHitPoints));
        return film;
    }
    const uint64_t most_hit_points =
        pixels * uint64_t(film.samples_per_pixel) * uint64_t(1 + film.gather_rays);
    if (most_hit_points > kMaxHitPoints)
        return absl::ResourceExhaustedError(absl::StrFormat(
            "%dx%d pixels x %d spp%s = %d hit points exceeds the limit of %d (about %d bytes each)",
            film.width, film.height, film.samples_per_pixel,
            film.gather_rays > 0 ? absl::StrFormat(" x (1 + %d gather rays)", film.gather_rays)
                                 : std::string(),
            most_hit_points, kMaxHitPoints, kBytesPerHitPoint));
    return film;
}

}  // namespace pf
