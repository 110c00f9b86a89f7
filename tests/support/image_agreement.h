// Whether an image is another independent draw of the estimator two reference images come
// from, channel by channel and block by block (the statistics derived in image_agreement.cpp).
// For comparing backends, scene formats and farms whose random streams differ.
#pragma once

#include <array>
#include <cmath>
#include <string>

#include "core/film/image.h"

namespace pf::testing {

// Each check below is set to fail a true draw with at most this probability (two-sided where
// it has two sides); a comparison runs nine (three per channel).
inline constexpr double kFalseAlarm = 1e-5;
// The relative bias of one channel's mean that every comparison of ExpectSameEstimator must be
// able to catch: the comparison's budget is too small where it could not.
inline constexpr double kBiasToCatch = 0.02;

// One channel's statistics (R, G or B). E = V - (A + B) / 2 and D = A - B, per pixel.
struct ChannelAgreement {
    double reference_mean = 0;  // (mean(A) + mean(B)) / 2
    double difference = 0;      // mean(V) minus reference_mean
    double sigma = 0;           // standard deviation of `difference` for a true draw
    double mean_dof = 0;        // degrees of freedom of `sigma` (blocks, Satterthwaite)
    double mean_limit = 0;      // |difference| allowed
    double block_ratio = 0;     // (4/3) sum over blocks of (sum E)^2 / the same of (sum D)^2
    double block_limit = 0;     // upper limit of block_ratio
    double spread_ratio = 0;    // (4/3) sum over pixels of E^2 / the same of D^2 (1 expected)
    double spread_t = 0;        // Student's t of the blocks' log((4/3) sum E^2 / sum D^2)
    double spread_limit = 0;    // |spread_t| allowed
    // A equals B in this channel (black, or emission alone): nothing random, so V must equal A
    // to float rounding, 1e-5 of the channel's largest value, and the checks above are not run.
    bool deterministic = false;
    double deterministic_error = 0, deterministic_tolerance = 0;  // largest |V - A|, allowed

    // Blocks where A equals B (a sky seen directly, emission alone) are deterministic parts of
    // a random image: V must equal A there to the same tolerance, and the spread check runs
    // over the other blocks.
    int deterministic_blocks = 0;
    double deterministic_blocks_error = 0;  // largest |V - A| in them

    bool MeanPassed() const {
        return deterministic ? deterministic_error <= deterministic_tolerance
                             : std::abs(difference) <= mean_limit;
    }
    bool BlocksPassed() const {
        return deterministic || (block_ratio <= block_limit &&
                                 deterministic_blocks_error <= deterministic_tolerance);
    }
    bool SpreadPassed() const { return deterministic || std::abs(spread_t) <= spread_limit; }
    bool Passed() const { return MeanPassed() && BlocksPassed() && SpreadPassed(); }
    // The smallest relative bias of this channel's mean that fails the mean check with
    // probability 0.999: (mean_limit + 3.1 sigma) / reference_mean. 0 for a deterministic
    // channel, +Inf for a black one.
    double DetectableBias() const;
};

struct ImageAgreement {
    std::string error;  // non-empty when the images cannot be compared (sizes, empty)
    int block_size = 0, blocks = 0;
    std::array<ChannelAgreement, 3> channels;

    bool Passed() const;
    // The largest DetectableBias over the channels whose reference mean is at least 1e-3 of
    // the brightest channel's (a relative bias of a black channel means nothing).
    double DetectableBias() const;
    // Every number above, one line per channel, with the checks that failed named.
    std::string Describe() const;
};

// Compares `image` (V) with `a` and `b`: two renders of the same seed, budget and batch
// layout, each with its own photon stream.
ImageAgreement CompareWithEstimator(const Image& image, const Image& a, const Image& b);

// Adds a test failure, with the numbers, unless CompareWithEstimator passes and can catch a
// bias of kBiasToCatch in every channel that is not black.
void ExpectSameEstimator(const Image& image, const Image& a, const Image& b);

// The mean over pixels and channels of the squared difference.
double MeanSquaredDifference(const Image& a, const Image& b);

// Upper-tail probabilities and quantiles of Student's t and Fisher's F with real degrees of
// freedom (through the regularised incomplete beta function).
double StudentTUpperTail(double t, double dof);
double FUpperTail(double f, double dof1, double dof2);
double StudentTQuantile(double upper_tail, double dof);
double FQuantile(double upper_tail, double dof1, double dof2);

}  // namespace pf::testing
