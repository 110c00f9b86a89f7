// The camera pass (Hachisuka et al. 2008, section 4.1): k jittered paths per pixel follow
// specular chains to the first diffuse surface, where each leaves a hit point (a path split at
// glass leaves one per branch, weighted by the branch's probability). Emission seen directly
// or through specular chains goes straight to the pixel.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "core/camera/surface_extent.h"
#include "core/film/image.h"
#include "core/geometry/tracer.h"
#include "core/job/batch.h"
#include "core/job/hit_point.h"
#include "core/job/job_spec.h"
#include "core/scene/emitters.h"
#include "core/scene/scene.h"
#include "core/scene/scene_features.h"

namespace pf {

struct CameraPassSettings {
    int width = 512, height = 512;
    int samples_per_pixel = 4;  // k: hit points traced per pixel
    uint64_t seed = 0;
    // The pass's place in the run: its epoch, and its first sample's index in each pixel's
    // sequence for the epoch's parity (EpochCameraSamples, PixelSampler::InEpochSequence), so
    // that the passes of successive epochs stay stratified together.
    uint64_t epoch = 0;
    uint64_t first_sample = 0;
    // Stochastic progressive photon mapping's pass (Hachisuka & Jensen 2009), traced anew
    // every epoch: each sample follows one branch at glass rather than splitting, and leaves
    // exactly one hit point (1 + gather_rays for rpm), in slot order (pixel * k + sample), black
    // where the path found no diffuse surface, so that slot i carries N, R, tau across epochs.
    bool stochastic = false;
    // ppm's emission, sampled afresh every epoch (EmissionCameraPass): the fixed pass's paths,
    // split at glass as they are, from samples of their own, keeping no hit points.
    bool emission_only = false;
    // What the scene uses (AnalyseFeatures): camera paths run code instantiated for it. All
    // by default.
    SceneFeatures features = SceneFeatures::All();
    int max_depth = 0;  // JobSpec::max_depth: surfaces a path meets at most (0: kMaxCameraDepth)
    // Reverse photon mapping's (a stochastic pass): each sample's final-gather rays, each a slot
    // of its own after the sample's, so a sample keeps 1 + gather_rays slots in a fixed order
    // (pixel, sample, ray); the camera hit point then gathers caustics alone. 0: none.
    int gather_rays = 0;
    // The pixels traced, [first_pixel, first_pixel + pixel_count) in row order; 0: all. A part
    // of a pass holds what the whole pass holds for those pixels (each pixel's paths draw from
    // streams of its own): a stochastic pass's slots from slot first_pixel * k * (1 +
    // gather_rays), an emission pass's emission and coverage (CameraPassResult).
    uint32_t first_pixel = 0, pixel_count = 0;
};

// Hit points indexed by pixel: pixel p's are points[order[begin[p] .. begin[p + 1])] in index
// order; `order` is empty where the points are in pixel order already (sppm's slots).
struct PixelHitPoints {
    std::span<const HitPoint> points;
    std::shared_ptr<const std::vector<HitPoint>> owner;  // holds `points`, where it was given
    std::vector<uint32_t> begin, order;

    // Indexes `points` (each in one of `pixels` pixels) by pixel, stably, keeping them.
    static PixelHitPoints Index(std::shared_ptr<const std::vector<HitPoint>> points, size_t pixels);
    // The same over points held elsewhere, which must outlive the index.
    static PixelHitPoints Index(std::span<const HitPoint> points, size_t pixels);
    // The hit point at place k of the pixel order (pixel p's are at places begin[p] ..).
    uint32_t At(size_t k) const { return order.empty() ? static_cast<uint32_t>(k) : order[k]; }
    // Calls visit(i) for each hit point i of pixel p, in index order.
    template <typename Visit>
    void ForEachOf(size_t p, Visit&& visit) const {
        for (uint32_t k = begin[p]; k < begin[p + 1]; ++k) visit(At(k));
    }
};

struct CameraPassResult {
    // Ordered along a Morton curve through the scene; in slot order for a stochastic pass.
    std::vector<HitPoint> hit_points;
    // Per hit point: a pixel's width at its distance, world units (0 for an empty slot).
    std::vector<float> footprint;
    // Emission reaching each pixel, averaged over its k paths; a part's (first_pixel,
    // pixel_count) is one row of its pixels.
    Image emission;
    // ppm's emission pass: per fixed hit point of the pixels traced, in pixel order (place k of
    // PixelHitPoints, from the first pixel's first), the weights of the pass's hit points it
    // stands for (CoveringHitPoint), averaged over the pass's samples of its pixel as
    // `emission` is. Over its own weight, it is the share of the pixel that its
    // estimate stands for this epoch: fixed hit points alone would give each 1/k for good, so
    // that a pixel across an edge between surfaces lit differently kept the split of its k
    // samples, never its area's (docs/design.md).
    std::vector<Rgb> coverage;
    // rpm's, per slot: the radius its place and kind call for this epoch (EpochCameraPasses'
    // SlotRadii; 0 for an empty slot); empty where radii are kept from epoch to epoch.
    std::vector<float> radius;
    // Per hit point, for the coordinator's estimate: how far its surface reaches about it
    // (ProbeSurfaceExtents: ppm's fixed hit points, probed when the job is prepared); empty
    // where not probed (every surface then counts as filling its disc).
    std::vector<SurfaceExtent> extent;
};

// Of the hit points of `pixel` in `fixed` whose weight is not black, the one that stands for a
// fresh camera sample's `hit` there: the nearest of those facing the same way (normals within
// 60 degrees: the same surface, or the same side of a translucent one), else the nearest of
// all; its place in the pixel order (PixelHitPoints::At); none where the pixel has no such
// hit point.
std::optional<uint32_t> CoveringHitPoint(const PixelHitPoints& fixed, uint32_t pixel,
                                         const HitPoint& hit);

// Longest specular chain followed; Russian roulette applies after kCameraRouletteDepth; the
// first kCameraSplits glass interfaces of a sample are split into both branches.
inline constexpr int kMaxCameraDepth = 64;
inline constexpr int kCameraRouletteDepth = 4;
inline constexpr int kCameraSplits = 2;

// Runs in parallel over rows (on the calling TBB arena); the result does not depend on the
// thread count. An emission pass (settings.emission_only) given ppm's `fixed` hit points
// credits each of its samples' hit points to one of them (CameraPassResult::coverage).
// `emitters` (the scene's) light the glossy surfaces paths meet with punctual lights, which
// no path finds by itself (core/scene/glossy_lights.h): their light counts as emission seen.
CameraPassResult RunCameraPass(const Scene& scene, const Emitters& emitters, const Tracer& tracer,
                               const CameraPassSettings& settings,
                               const PixelHitPoints* fixed = nullptr);

// Stochastic progressive photon mapping's pass of `epoch` for job `spec`: `film` (FilmFor)
// with the epoch's camera samples (EpochCameraSamples: the pixel's next k). The coordinator
// and every worker trace the same hit points from it; ppm's workers sample direct light at its
// slots.
CameraPassSettings StochasticCameraPass(const CameraPassSettings& film, const JobSpec& spec,
                                        uint64_t epoch);

// The slots of a stochastic pass a worker's batches sample ppm's direct light at: the pixels
// their sample slices lie in, traced when batches need them, rather than the whole pass on
// every worker. Each pixel's paths draw from streams of their own, so a part's slots are the
// whole pass's, bit for bit.
class CameraPassPart {
public:
    // Forgets the part held; the next Cover traces from `pass` (a StochasticCameraPass).
    void Reset(const CameraPassSettings& pass);
    // Holds the slots of `specs`' sample slices, with the rest of their pixels' (the pixels
    // from the first's to the last's), tracing them unless held already. Returns whether it
    // traced.
    bool Cover(const Scene& scene, const Emitters& emitters, const Tracer& tracer,
               std::span<const BatchSpec> specs);
    std::span<const HitPoint> Points() const { return points_; }
    uint64_t FirstSlot() const { return first_pixel_ * slots_per_pixel_; }

private:
    CameraPassSettings pass_;
    uint64_t slots_per_pixel_ = 1;
    std::vector<HitPoint> points_;
    uint64_t first_pixel_ = 0, end_pixel_ = 0;  // the part held
};

// Progressive photon mapping's emission pass of `epoch`: the emission the camera sees, directly
// or through specular chains, from the epoch's own camera samples, with no hit points (photons
// gather at the fixed ones, direct light is sampled at the workers' StochasticCameraPass).
// Glass splits as in the fixed pass: one random branch would leave a light seen through glass
// much noisier.
CameraPassSettings EmissionCameraPass(const CameraPassSettings& film, const JobSpec& spec,
                                      uint64_t epoch);

// ppm's fixed hit points indexed by pixel, for a worker's share of each epoch's emission pass
// (TraceBatchEmission); `points` must outlive the index. INVALID_ARGUMENT where one lies in no
// pixel of `film` (they come from the coordinator).
absl::StatusOr<PixelHitPoints> IndexFixedHitPoints(std::span<const HitPoint> points,
                                                   const CameraPassSettings& film);

// ppm: each batch's share of its epoch's emission pass `pass` (EmissionCameraPass): the
// emission and the coverage of `fixed` at its SlicePixels (BatchResult::emission, coverage),
// the pixels of all of `results` traced as one part. The same, bit for bit, as the whole
// pass's at those pixels, whoever traces them.
void TraceBatchEmission(const Scene& scene, const Emitters& emitters, const Tracer& tracer,
                        const CameraPassSettings& pass, const PixelHitPoints& fixed,
                        std::span<BatchResult> results);

// The coordinator's camera pass of an epoch of sppm or rpm: the StochasticCameraPass, its
// emission and its slots, pixel * k + sample, where photons gather and direct light is sampled.
// (ppm's workers trace each epoch's emission and direct light, each batch its pixels'.)
using EpochCameraPass = std::function<CameraPassResult(uint64_t epoch)>;

// The radii a pass's slots call for, from their hit points and footprints (rpm's:
// core/pm/density_radii.h's DensityRadii, whose room is above this one's).
using SlotRadii = std::function<std::vector<float>(std::span<const HitPoint> hit_points,
                                                   std::span<const float> footprint)>;

// Each epoch's pass of `film` for job `spec` (sppm or rpm) over `scene` (lit by `emitters`)
// through `tracer`, which the function keeps alive; `scene` and `emitters` must outlive it.
// `radii`, where given, sets each pass's CameraPassResult::radius.
EpochCameraPass TracedCameraPasses(const Scene& scene, const Emitters& emitters,
                                   std::shared_ptr<const Tracer> tracer,
                                   const CameraPassSettings& film, const JobSpec& spec,
                                   SlotRadii radii = {});

// The initial search radius R0: the median pixel footprint over the hit points, capped at 1%
// of the scene's diagonal. A disk of that radius covers about pi pixels, so with k = 4 hit
// points per pixel a photon reaches about 12 hit points at first: enough overlap to smooth
// the first epochs, little enough blur to start near the image's resolution. Zero when there
// are no hit points.
// Film size: what was asked, else the scene's own (pbrt's Film), else 512 wide with the
// camera's aspect ratio; RESOURCE_EXHAUSTED if its hit points (path, pm: its pixels) would not fit.
absl::StatusOr<CameraPassSettings> FilmFor(const JobSpec& spec, const Scene& scene);

float DefaultInitialRadius(const CameraPassResult& camera_pass, const Scene& scene);

// The median of `radii` over the hit points with a footprint (a slot of a stochastic pass may
// have none); 0 where none has one. DefaultInitialRadius's median and a job's reported R0.
float MedianRadius(std::span<const float> radii, std::span<const float> footprint);

}  // namespace pf
