// Merging epochs into the per-hit-point estimates and resolving the image.
#include "core/estimate/progressive_estimate.h"

#include <spdlog/spdlog.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "core/util/check.h"

namespace pf {

ProgressiveEstimate::ProgressiveEstimate(CameraPassResult camera_pass,
                                         const EstimateSettings& settings,
                                         EpochCameraPass next_passes,
                                         std::span<const float> initial_radii)
    : next_passes_(std::move(next_passes)), settings_(settings) {
    PF_CHECK(next_passes_ || !settings.stochastic);
    PF_CHECK(settings.alpha > 0 && settings.alpha <= 1);
    PF_CHECK(settings.initial_radius > 0 && std::isfinite(settings.initial_radius));
    PF_CHECK(settings.min_radius >= 0 && settings.min_radius <= settings.initial_radius);
    PF_CHECK(settings.samples_per_pixel > 0);
    const size_t pixels = camera_pass.emission.pixels.size();
    emission_sum_.assign(pixels, Rgbd(0.0));
    emission_even_.assign(pixels, Rgbd(0.0));
    direct_sum_.assign(pixels, Rgbd(0.0));
    direct_even_.assign(pixels, Rgbd(0.0));
    PF_CHECK(settings.gather_rays == 0 || (settings.stochastic && settings.alpha == 1));
    epoch_direct_.assign(pixels * size_t(EpochPass(0).per_pixel) * settings.SlotsPerSample(),
                         Rgb(0.0f));
    // rpm's first pass brings its slots' radii (before any photon: nothing to rescale).
    std::vector<float> pass_radii;
    if (settings.stochastic && initial_radii.empty() && !camera_pass.radius.empty()) {
        pass_radii = std::move(camera_pass.radius);
        initial_radii = pass_radii;
    }
    if (settings.stochastic) {
        BeginEpochPass(std::move(camera_pass));
    } else {
        SetHitPoints(
            std::make_shared<const std::vector<HitPoint>>(std::move(camera_pass.hit_points)));
        extent_ = std::move(camera_pass.extent);
        coverage_sum_.assign(HitPoints().size(), Rgbd(0.0));
        coverage_even_.assign(HitPoints().size(), Rgbd(0.0));
        // Each epoch's emission pass comes with its batches (BatchResult::emission).
        epoch_emission_ = Image(camera_pass.emission.width, camera_pass.emission.height);
        epoch_coverage_.assign(HitPoints().size(), Rgb(0.0f));
    }
    PF_CHECK(extent_.empty() || extent_.size() == HitPoints().size());
    const size_t n = HitPoints().size();
    const double radius_sq = settings.initial_radius * settings.initial_radius;
    points_.assign(n, PointEstimate{0.0, radius_sq, Rgbd(0.0)});
    if (!initial_radii.empty()) {
        PF_CHECK(initial_radii.size() == points_.size());
        for (size_t i = 0; i < points_.size(); ++i) {
            const double radius = std::max(double(initial_radii[i]), settings.min_radius);
            PF_CHECK(std::isfinite(radius));
            points_[i].radius_sq = radius * radius;
        }
    }
    flux_even_.assign(n, Rgbd(0.0));
    counts_.assign(n, GatherCounts{});
    epoch_photons_.assign(n, EpochPhotons{});
    epoch_flux_.assign(n, Rgbd(0.0));
    epoch_flux_even_.assign(n, Rgbd(0.0));
}

void ProgressiveEstimate::BeginEpochPass(CameraPassResult camera_pass) {
    PF_CHECK(settings_.stochastic && camera_pass.emission.pixels.size() == direct_sum_.size());
    if (!camera_pass.radius.empty() && !points_.empty()) TakeSlotRadii(camera_pass.radius);
    PF_CHECK(camera_pass.hit_points.size() == epoch_direct_.size());
    PF_CHECK(camera_pass.extent.empty() ||
             camera_pass.extent.size() == camera_pass.hit_points.size());
    SetHitPoints(std::make_shared<const std::vector<HitPoint>>(std::move(camera_pass.hit_points)));
    extent_ = std::move(camera_pass.extent);
    epoch_emission_ = std::move(camera_pass.emission);
}

std::pair<uint64_t, uint64_t> ProgressiveEstimate::EmissionShape(const BatchSpec& spec) const {
    if (settings_.stochastic) return {0, 0};
    const auto [begin, end] = SlicePixels(spec, EpochPass(spec.epoch).per_pixel);
    if (begin >= end || end > direct_sum_.size()) return {0, 0};
    return {end - begin, by_pixel_->begin[end] - by_pixel_->begin[begin]};
}

void ProgressiveEstimate::TakeSlotRadii(std::span<const float> radii) {
    PF_CHECK(radii.size() == points_.size());
    const double min_radius_sq = settings_.min_radius * settings_.min_radius;
    for (size_t i = 0; i < points_.size(); ++i) {
        if (!(radii[i] > 0)) continue;  // an empty slot keeps its radius
        const double radius_sq = std::max(double(radii[i]) * double(radii[i]), min_radius_sq);
        PF_CHECK(std::isfinite(radius_sq));
        // The sums count what lies within the radius: the new one's share of them (none
        // where it had no radius: it gathered nothing).
        const double scale = points_[i].radius_sq > 0 ? radius_sq / points_[i].radius_sq : 0.0;
        points_[i].photon_count *= scale;
        points_[i].flux *= scale;
        points_[i].radius_sq = radius_sq;
        flux_even_[i] *= scale;
        counts_[i].Fold(EpochPhotons{}, scale);
    }
}

void ProgressiveEstimate::SetHitPoints(std::shared_ptr<const std::vector<HitPoint>> hit_points) {
    by_pixel_ = std::make_shared<const PixelHitPoints>(
        PixelHitPoints::Index(std::move(hit_points), direct_sum_.size()));
}

Rgbd ProgressiveEstimate::Share(size_t i, const std::vector<Rgbd>& coverage, double samples) const {
    if (settings_.stochastic || !(samples > 0)) return Rgbd(1.0 / settings_.samples_per_pixel);
    const Rgb& weight = HitPoints()[i].weight;
    Rgbd share(0.0);
    for (int c = 0; c < 3; ++c)
        if (weight[c] != 0) share[c] = coverage[i][c] / (samples * double(weight[c]));
    return share;
}

template <typename Block>
void ProgressiveEstimate::ForEachPixelBlock(Block&& block) const {
    const size_t pixels = direct_sum_.size();
    tbb::parallel_for(size_t{0}, (pixels + kPixelBlock - 1) / kPixelBlock, [&](size_t index) {
        block(index, index * kPixelBlock, std::min(pixels, (index + 1) * kPixelBlock));
    });
}

EpochSamples ProgressiveEstimate::EpochPass(uint64_t epoch) const {
    return EpochCameraSamples(Kind(), settings_.samples_per_pixel, settings_.layout,
                              direct_sum_.size(), epoch);
}

uint64_t ProgressiveEstimate::MergedSamples(uint64_t parity) const {
    // Those of the epochs before the first one of that parity not merged yet.
    return EpochPass(epoch_ + ((epoch_ ^ parity) & 1)).first;
}

Rgbd ProgressiveEstimate::EmissionAndDirect(size_t p) const {
    if (epoch_ == 0) return Rgbd(0.0);
    return (emission_sum_[p] + direct_sum_[p]) /
           static_cast<double>(MergedSamples(0) + MergedSamples(1));
}

GatherRegions ProgressiveEstimate::Regions() const {
    GatherRegions regions;
    regions.radius_sq.resize(points_.size());
    for (size_t i = 0; i < points_.size(); ++i)
        regions.radius_sq[i] = static_cast<float>(points_[i].radius_sq);
    if (!extent_.empty()) {
        regions.edges.resize(points_.size());
        for (size_t i = 0; i < points_.size(); ++i)
            regions.edges[i] = extent_[i].Edges(std::sqrt(points_[i].radius_sq));
    }
    return regions;
}

std::vector<BatchSpec> ProgressiveEstimate::EpochBatches() const {
    std::vector<BatchSpec> specs;
    for (uint32_t j = 0; j < settings_.layout.batches_per_epoch; ++j)
        specs.push_back(MakeBatchSpec(settings_.layout, epoch_, j,
                                      static_cast<uint32_t>(epoch_direct_.size())));
    return specs;
}

void ProgressiveEstimate::FoldBatch(const BatchResult& result) {
    const uint32_t j = batches_folded_;
    PF_CHECK(j < settings_.layout.batches_per_epoch && result.spec.epoch == epoch_ &&
             result.spec.index == epoch_ * settings_.layout.batches_per_epoch + j);
    const std::span<const HitPoint> hit_points = HitPoints();
    const Tally& tally = result.tally;
    PF_CHECK(tally.Size() == 0 || tally.hit_point.back() < hit_points.size());
    PF_CHECK(tally.photons.size() == tally.Size() && tally.inner_photons.size() == tally.Size() &&
             tally.flux.size() == tally.Size());
    const bool even = result.spec.index % 2 == 0;
    // Entries are sorted by hit point and each names a hit point once, so disjoint ranges of
    // entries touch disjoint sums: folded in parallel, each sum still gets its batches in
    // batch-index order, and the result does not depend on the thread count.
    tbb::parallel_for(tbb::blocked_range<size_t>(0, tally.Size(), 1 << 14),
                      [&](const tbb::blocked_range<size_t>& r) {
                          for (size_t e = r.begin(); e < r.end(); ++e) {
                              const uint32_t i = tally.hit_point[e];
                              EpochPhotons& found = epoch_photons_[i];
                              found.all += tally.photons[e];
                              found.inner += tally.inner_photons[e];
                              // Phi_M: the photons' flux times the BSDF weight (a float product,
                              // exact in double).
                              const Rgbd flux = Rgbd(tally.flux[e]) * Rgbd(hit_points[i].weight);
                              epoch_flux_[i] += flux;
                              if (even) {
                                  epoch_flux_even_[i] += flux;
                                  found.all_even += tally.photons[e];
                                  found.inner_even += tally.inner_photons[e];
                              }
                          }
                      });
    PF_CHECK(result.samples.size() == result.spec.sample_end - result.spec.sample_begin &&
             result.spec.sample_end <= epoch_direct_.size());
    // The epoch's direct slices are disjoint and cover every slot of its pass once.
    std::copy(result.samples.begin(), result.samples.end(),
              epoch_direct_.begin() + result.spec.sample_begin);
    epoch_photons_emitted_ += result.photons_emitted;
    epoch_nonfinite_discarded_ += result.nonfinite_discarded;
    epoch_light_reached_ = epoch_light_reached_ || tally.Size() > 0 ||
                           std::any_of(result.samples.begin(), result.samples.end(),
                                       [](const Rgb& d) { return !IsBlack(d); });
    if (even) epoch_photons_emitted_even_ += result.photons_emitted;
    if (!settings_.stochastic) {  // the batch's share of the epoch's emission pass
        const auto [begin, end] = SlicePixels(result.spec, EpochPass(epoch_).per_pixel);
        PF_CHECK(std::pair(result.emission.size(), result.coverage.size()) ==
                 EmissionShape(result.spec));
        std::ranges::copy(result.emission,
                          epoch_emission_.pixels.begin() + static_cast<ptrdiff_t>(begin));
        const uint32_t first = begin < end ? by_pixel_->begin[begin] : 0;
        for (size_t k = 0; k < result.coverage.size(); ++k)
            epoch_coverage_[by_pixel_->At(first + k)] = result.coverage[k];
    }
    ++batches_folded_;
}

void ProgressiveEstimate::FinishEpoch() {
    PF_CHECK(batches_folded_ == settings_.layout.batches_per_epoch);
    // The growing epochs (BatchLayout::GrowingEpochs) together are the first pass: radii hold
    // through them (alpha 1: every photon kept at R0), and the last of them shrinks them as a
    // first pass does, by alpha over all their photons. Shrunk once an epoch, the small epochs
    // would shrink radii as much as so many full passes (R^2 to a quarter by the first full
    // epoch rather than alpha): too little blur for the photons there are.
    const uint64_t growing = settings_.layout.GrowingEpochs();
    const bool holding = epoch_ + 1 < growing;
    const bool closing = growing > 1 && epoch_ + 1 == growing;
    const double alpha = holding ? 1.0 : BalancedAlpha();
    const double min_radius_sq = settings_.min_radius * settings_.min_radius;
    const bool even_epoch = epoch_ % 2 == 0;
    // The epoch's slots a pixel, and its camera samples.
    const size_t slots = epoch_direct_.size() / emission_sum_.size();
    const size_t k = slots / settings_.SlotsPerSample();
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, points_.size()), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t i = r.begin(); i < r.end(); ++i) {
                const double photons = static_cast<double>(epoch_photons_[i].all);
                PointEstimate point = points_[i];
                double pass_photons = photons;
                if (closing) {  // the pass's photons so far, as if they all came now
                    pass_photons += point.photon_count;
                    point.photon_count = 0;
                }
                const double shrink = ShrinkRatio(point, pass_photons, alpha, min_radius_sq);
                // The epoch's photons over the area of the hit point's surface within R: as
                // if its surface filled the disc, which the estimate divides by.
                double area = 1.0, inner_scale = 1.0;
                if (!extent_.empty()) {
                    const double radius = std::sqrt(point.radius_sq);
                    area = extent_[i].AreaFraction(radius);
                    inner_scale = area / extent_[i].AreaFraction(radius * std::sqrt(0.5));
                }
                flux_even_[i] = (flux_even_[i] + epoch_flux_even_[i] / area) * shrink;
                counts_[i].Fold(epoch_photons_[i], shrink, inner_scale);
                points_[i] = UpdateEstimate(point, pass_photons, epoch_flux_[i] / area, alpha,
                                            min_radius_sq);
                epoch_photons_[i] = EpochPhotons{};
                epoch_flux_[i] = Rgbd(0.0);
                epoch_flux_even_[i] = Rgbd(0.0);
                if (!settings_.stochastic) {
                    const Rgbd covered = Rgbd(epoch_coverage_[i]) * static_cast<double>(k);
                    coverage_sum_[i] += covered;
                    if (even_epoch) coverage_even_[i] += covered;
                }
            }
        });
    photons_emitted_ += epoch_photons_emitted_;
    nonfinite_discarded_ += epoch_nonfinite_discarded_;
    epoch_nonfinite_discarded_ = 0;
    light_reached_ = light_reached_ || epoch_light_reached_;
    epoch_light_reached_ = false;
    photons_emitted_even_ += epoch_photons_emitted_even_;
    epoch_photons_emitted_ = 0;
    epoch_photons_emitted_even_ = 0;
    batches_folded_ = 0;
    // Each pixel's emission and its slots' direct samples: the epoch's estimate of what photons
    // do not carry, summed over its camera samples (a growing epoch has fewer than later ones).
    for (size_t p = 0; p < emission_sum_.size(); ++p) {
        Rgbd direct(0.0);
        for (size_t s = p * slots; s < (p + 1) * slots; ++s) direct += Rgbd(epoch_direct_[s]);
        const Rgbd emission = Rgbd(epoch_emission_.pixels[p]) * static_cast<double>(k);
        emission_sum_[p] += emission;
        direct_sum_[p] += direct;
        if (even_epoch) emission_even_[p] += emission, direct_even_[p] += direct;
    }
    ++epoch_;
    epoch_direct_.assign(
        emission_sum_.size() * size_t(EpochPass(epoch_).per_pixel) * settings_.SlotsPerSample(),
        Rgb(0.0f));
    // ppm's next emission pass comes with the next epoch's batches.
    if (settings_.stochastic) BeginEpochPass(next_passes_(epoch_));
}

Image ProgressiveEstimate::Resolve() const {
    const double photons = static_cast<double>(photons_emitted_);
    const double samples = static_cast<double>(MergedSamples(0) + MergedSamples(1));
    Image image(epoch_emission_.width, epoch_emission_.height);
    ForEachPixelBlock([&](size_t, size_t begin, size_t end) {
        for (size_t p = begin; p < end; ++p) {
            Rgbd sum(0.0);
            ForEachHitPointOf(p, [&](uint32_t i) {
                sum += EstimateRadiance(points_[i], photons) * Share(i, coverage_sum_, samples);
            });
            image.pixels[p] = Rgb(EmissionAndDirect(p) + sum);
        }
    });
    return image;
}

namespace {

// A disc estimate L's bias from the fraction f = inner / all of its photons within R / sqrt(2)
// (1/2 where the density is flat): the inner disc's estimate is 2 f L and has half the bias,
// so bias = 2 (L - 2 f L). At most L: the radiance is not negative, so the estimate cannot
// exceed it by more than itself; the quadratic model would claim up to 2 L where a caustic's
// focus, narrower than the disc, lies in its outer ring (f near 0).
Rgbd InnerDiscBias(const Rgbd& estimate, double inner, double all) {
    if (!(all > 0)) return Rgbd(0.0);
    return estimate * std::min(2 * (1 - 2 * inner / all), 1.0);
}

}  // namespace

ProgressiveEstimate::ErrorSums ProgressiveEstimate::SumErrors() const {
    const double photons = static_cast<double>(photons_emitted_);
    const double photons_even = static_cast<double>(photons_emitted_even_);
    const double photons_odd = photons - photons_even;
    // Camera samples a pixel over the even epochs and the odd.
    const double samples_even = static_cast<double>(MergedSamples(0)),
                 samples_odd = static_cast<double>(MergedSamples(1));
    ErrorSums total;
    if (!(photons_even > 0 && photons_odd > 0 && samples_odd > 0)) return total;
    const size_t pixels = direct_sum_.size();
    const double variance_scale = photons_even * photons_odd / (photons * photons);
    // Sums over pixels and channels, per block of pixels, added in block order below.
    std::vector<ErrorSums> block_sums((pixels + kPixelBlock - 1) / kPixelBlock);
    ForEachPixelBlock([&](size_t block, size_t begin, size_t end) {
        ErrorSums& sums = block_sums[block];
        for (size_t p = begin; p < end; ++p) {
            // Summed over the pixel's hit points, each times its share of the pixel: the photon
            // estimate, the difference of its halves, and the bias estimate 2 (L - L_inner) of
            // each half. For ppm also the photon estimate times the share of the even epochs'
            // camera samples and of all (not divided by their counts).
            Rgbd value(0.0), difference(0.0), bias_even(0.0), bias_odd(0.0);
            Rgbd covered_even(0.0), covered_all(0.0);
            ForEachHitPointOf(p, [&](uint32_t i) {
                const PointEstimate& point = points_[i];
                const Rgbd share = Share(i, coverage_sum_, samples_even + samples_odd);
                const Rgbd even =
                    EstimateRadiance({0, point.radius_sq, flux_even_[i]}, photons_even);
                const Rgbd odd =
                    EstimateRadiance({0, point.radius_sq, point.flux - flux_even_[i]}, photons_odd);
                const Rgbd estimate = EstimateRadiance(point, photons);
                value += estimate * share;
                difference += (even - odd) * share;
                const GatherCounts& counts = counts_[i];
                bias_even += InnerDiscBias(even, counts.inner_even, counts.all_even) * share;
                bias_odd += InnerDiscBias(odd, counts.inner - counts.inner_even,
                                          counts.all - counts.all_even) *
                            share;
                if (!settings_.stochastic) {
                    covered_even += estimate * Share(i, coverage_even_, 1.0);
                    covered_all += estimate * Share(i, coverage_sum_, 1.0);
                }
            });
            for (int c = 0; c < 3; ++c) {
                // Emission, direct light and (ppm) the hit points' shares of the pixel differ
                // between even and odd epochs as photons do between even and odd batches.
                const double seen_even =
                                 emission_even_[p][c] + direct_even_[p][c] + covered_even[c],
                             seen_all = emission_sum_[p][c] + direct_sum_[p][c] + covered_all[c];
                const double photon_difference = difference[c];
                const double d = photon_difference + seen_even / samples_even -
                                 (seen_all - seen_even) / samples_odd;
                const double v = EmissionAndDirect(p)[c] + value[c];
                AddHalfVariance(v, d, variance_scale, &sums.squared, &sums.relative);
                sums.photon_squared += photon_difference * photon_difference * variance_scale;
                // The product of two independent estimates of the bias is an unbiased estimate
                // of its square, whatever the hit points' photons share (b^2 less the sum of
                // each hit point's variance is not: discs of one pixel overlap). The sum over
                // pixels is clamped at zero by the callers, not each pixel, to stay unbiased.
                const double b_squared = bias_even[c] * bias_odd[c];
                sums.bias_squared += b_squared;
                sums.bias_relative += b_squared / (v * v + 0.01);
            }
        }
    });
    for (const ErrorSums& sums : block_sums) {
        total.squared += sums.squared;
        total.relative += sums.relative;
        total.photon_squared += sums.photon_squared;
        total.bias_squared += sums.bias_squared;
        total.bias_relative += sums.bias_relative;
    }
    total.samples = 3.0 * static_cast<double>(pixels);
    return total;
}

ErrorEstimate ProgressiveEstimate::EstimateError() const {
    const ErrorSums sums = SumErrors();
    ErrorEstimate error;
    if (!(sums.samples > 0)) return error;
    const double bias_squared = std::max(sums.bias_squared, 0.0) / sums.samples;
    error.known = true;
    error.rmse = std::sqrt(sums.squared / sums.samples + bias_squared);
    error.rel_mse = sums.relative / sums.samples + std::max(sums.bias_relative, 0.0) / sums.samples;
    error.bias_rmse = std::sqrt(bias_squared);
    return error;
}

double ProgressiveEstimate::BalancedAlpha() const {
    if (!settings_.balanced) return settings_.alpha;
    const ErrorSums sums = SumErrors();
    if (!(sums.samples > 0)) return settings_.alpha;
    const double bias_squared = std::max(sums.bias_squared, 0.0);
    if (!(bias_squared > 0)) return kBalancedAlphaMost;
    if (!(sums.photon_squared > 0)) return kBalancedAlphaLeast;
    const double r = bias_squared / (0.5 * sums.photon_squared);
    return std::clamp(1 - (1 - settings_.alpha) * std::sqrt(r), kBalancedAlphaLeast,
                      kBalancedAlphaMost);
}

EstimateSettings EstimateFor(const JobSpec& spec, const CameraPassResult& camera_pass,
                             const Scene& scene, const std::string& scene_name) {
    EstimateSettings estimate{spec.alpha == 0 ? kDefaultAlpha : spec.alpha, spec.alpha == 0,
                              spec.initial_radius, spec.samples_per_pixel,
                              ResolvedLayout(spec, camera_pass.emission.pixels.size())};
    estimate.stochastic = TracesHitPointsEachEpoch(spec.integrator);
    if (spec.integrator == Integrator::kRpm) {  // radii never shrink, as classic pm's
        estimate.alpha = 1;
        estimate.balanced = false;
        estimate.gather_rays = RpmGatherRays(spec.photon_map);
    }
    if (estimate.initial_radius == 0) estimate.initial_radius = scene.hints.initial_radius;
    if (estimate.initial_radius == 0)
        estimate.initial_radius = DefaultInitialRadius(camera_pass, scene);
    if (camera_pass.hit_points.empty() || !(estimate.initial_radius > 0)) {
        // Not a warning: the camera's paths still find light directly and through glossy and
        // specular bounces (glTF's default material is a rough metal); Job warns where the
        // image comes out black.
        spdlog::info(
            "{}: the camera sees no diffuse surface: photons add nothing, and the image is the "
            "light its paths find directly and through glossy and specular bounces",
            scene_name);
        estimate.initial_radius = std::max(estimate.initial_radius, 1e-3 * scene.bounds.Diagonal());
    }
    // 2^-20 of the scene's largest coordinate is 16 float steps of a position there: radii
    // below it gather by rounding error, not by distance.
    estimate.min_radius =
        std::min(estimate.initial_radius, std::ldexp(double(scene.bounds.Magnitude()), -20));
    return estimate;
}

}  // namespace pf
