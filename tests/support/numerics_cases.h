// The stiff and extreme cases of docs/numerics.md, each with its pass criterion stated and its
// measurement returned: run one by one by tests/integration/numerics_test.cpp, and all in a
// row by bench/numerics_report, which prints them as a table.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/film/image.h"
#include "core/job/job_spec.h"
#include "core/math/vec3.h"
#include "embedded/local_render.h"

namespace pf::testing {

struct NumericsResult {
    double measured = 0;  // the quantity the criterion bounds
    double bound = 0;     // pass when measured <= bound (and `ok`)
    bool ok = true;  // everything else the case checks held (finite images, monotone radii, ...)
    std::string detail;  // what failed, or a note on what was seen
    // The case's criterion applied again to its own measurement given a known bias (2%
    // brighter, 2% darker, one channel tinted, red and blue swapped): every one must fail, or
    // the criterion could not tell a biased render from a right one. How many were tried (0
    // where the criterion is not about a mean), and the names of those that passed.
    int biased_checks = 0;
    std::string biased_that_passed;
    bool Passed() const { return ok && measured <= bound; }
};

struct NumericsCase {
    std::string group;      // stiff, scale, power, estimator
    std::string name;       // unique, usable as a test name
    std::string criterion;  // the pass criterion in words, with its derivation's result
    std::function<NumericsResult()> run;
};

std::vector<NumericsCase> NumericsCases();

// The pixels of a `width` x `height` render of an axis-aligned box seen from inside through a
// pinhole (the furnaces) whose every camera sample meets one face farther than `radius` from
// its edges, so that every gather sphere about their hit points cuts that face alone, in a full
// disc; and the fraction of the box's surface their footprints cover.
struct BoxInterior {
    std::vector<bool> pixels;  // row-major, as Image::pixels
    size_t count = 0;
    double area_fraction = 0;
};
BoxInterior BoxInteriorPixels(const std::string& scene_path, int width, int height, double radius);

// The standard deviation, relative to L = Le / (1 - rho), of a white furnace render's mean over
// BoxInterior pixels, derived at Furnace in numerics_cases.cpp: `photons` emitted, whose
// deposits from the second hit on make the photon part (rho^2 of L), `area_fraction` of the
// box's surface under the interior, and `direct_samples` direct-light samples taken there.
double FurnaceMeanSigma(double rho, double photons, double area_fraction, double direct_samples);

// A white furnace render checked on its BoxInterior pixels against the value `expected` there.
// Each channel's mean must lie within 4 sigma (sigma relative to `expected`; a true render
// fails with probability 6e-5). The median of the pixels (channel averages) is checked too,
// for pixels wrong in opposite directions that the mean averages away; it needs more room than
// the mean: a pixel's noise is skewed (photons in a small disc, light samples near the
// emitting edges), so the pixels' median sits off their mean by up to one standard deviation s
// of a pixel (|median - mean| <= s for every distribution), and the sample median has a
// standard error of about 1.2533 s / sqrt(n) of its own: allowed s (1 + 4 x 1.2533 / sqrt(n)),
// s measured over the n pixels (1 to 2.5% of L in the tests, so 1 to 3%). A bias of the whole
// image is the mean's to catch, at 2% and less: the tests apply the check again to the render
// made 2% brighter, 2% darker and green 2% brighter (`bias`), which must fail.
struct FurnaceCheck {
    Rgbd mean{0.0};
    double expected = 0, sigma = 0;                            // sigma relative to `expected`
    double median = 0, pixel_deviation = 0, median_bound = 0;  // relative
    size_t pixels = 0;

    double MeanError() const;  // the worst channel's |mean / expected - 1|
    bool Passed() const;
    std::string Describe() const;
};

// `sigma` < 0: the pixels are independent (a path tracer's), so sigma is measured from them.
FurnaceCheck CheckFurnace(const Image& image, const BoxInterior& interior, double expected,
                          double sigma, const Rgbd& bias = Rgbd(1.0));

// A furnace seen through glass (furnace-glass.gltf: a closed box of albedo rho emitting Le
// everywhere, with a clear glass sphere in it). Lossless glass leaves the uniform radiance
// L = Le / (1 - rho) uniform, so a pixel is L times the throughput of its camera paths, which is
// what the pass's emission image holds (Le carried to the pixel through the glass): given its
// camera pass, a pixel's expectation is emission / (1 - rho), wherever its hit points' gather
// discs lie flat within one wall (PPM's estimate is unbiased on a flat density, derived at
// Furnace in numerics_cases.cpp). The camera pass is the job's own, traced again here (the same
// film and seed: the hit points are the same, checked by their count and R0); renders with the
// same seed and other photon streams share it.
struct FurnacePass {
    Image emission;                   // the pass's emission image: Le through specular chains
    std::vector<bool> flat;           // every hit point of the pixel farther than `radius`
                                      // from the box's edges (row-major, as Image::pixels)
    std::vector<bool> through_glass;  // all its camera rays (corners, centre) meet glass first
    uint64_t hit_points = 0;
    double initial_radius = 0;  // R0 the job takes from the pass (DefaultInitialRadius)
};
FurnacePass TraceFurnacePass(const std::string& scene_path, const JobSpec& job, double radius);

// The median over the pixels of `region` of each channel of the pass's emission. Where no
// camera path met Russian roulette (after kCameraRouletteDepth specular bounces; a few pixels in
// a hundred), a pixel's throughputs sum to exactly 1 (Fresnel's R + T at every split or choice),
// so the median is Le to float rounding unless the glass loses or makes light.
Rgbd MedianEmission(const FurnacePass& pass, const std::vector<bool>& region);

// K renders sharing `pass` (one seed, photon streams of their own) checked on the pixels of
// `region` against their expectation given the pass, per channel: each render's
// e_k = sum over the region of (pixel x bias) / sum of emission / (1 - rho), minus 1, is an
// independent draw of mean 0 (the photons and light samples are the stream's own), so
// mean(e) / (sd(e) / sqrt(K)) is Student's t with K - 1 degrees of freedom, allowed to its
// two-sided kFalseAlarm quantile, plus `known_bias` (relative). A channel off by b fails with
// probability 0.999 when (limit + 3.1 sigma) <= b (DetectableBias).
struct FurnaceStreamsCheck {
    size_t pixels = 0;
    int renders = 0;
    Rgbd error{0.0}, sigma{0.0};  // mean(e) and its standard error, per channel
    double quantile = 0, known_bias = 0;

    double Limit(int channel) const { return quantile * sigma[channel] + known_bias; }
    bool Passed() const;
    double DetectableBias() const;  // the worst channel's
    std::string Describe() const;
};
FurnaceStreamsCheck CheckFurnaceStreams(const std::vector<Image>& renders, const FurnacePass& pass,
                                        const std::vector<bool>& region, double rho,
                                        double known_bias, const Rgbd& bias = Rgbd(1.0));

// One ppm render whose epochs are the independent draws CheckFurnaceStreams takes, in place of
// K renders on photon streams of their own (each of which builds its backend and traces its
// camera pass again: on lavapipe about 10 s of pipeline set-up a render). At alpha = 1 a
// radius never shrinks and ppm's estimate is the plain mean of its epochs' estimates: after
// epoch k of P photons and k camera samples a pixel (the same P and k every epoch), the image
// is I_k = (x_1 + ... + x_k) / k, where x_e is epoch e's own estimate (its photons over the
// fixed discs, its direct-light samples and its emission pass), so x_k = k I_k - (k - 1) I_k-1.
// The x_e are independent given the camera pass (each epoch's photons and camera samples are
// drawn from their own numbers), each of expectation what one render's is: the streams' K
// renders become one render's K epochs. `settings` must ask for ppm with alpha = 1 and a
// budget of whole epochs (all full: none of the small first epochs). The outcome is the render's,
// `epochs` its epochs' own images.
struct EpochDraws {
    RenderOutcome outcome;
    std::vector<Image> epochs;
};
absl::StatusOr<EpochDraws> RenderEpochDraws(RenderSettings settings);

}  // namespace pf::testing
