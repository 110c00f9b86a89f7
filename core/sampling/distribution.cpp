// Discrete distribution sampling by binary search on the CDF.
#include "core/sampling/distribution.h"

#include <algorithm>
#include <cmath>

#include "core/util/check.h"

namespace pf {

DiscreteDistribution::DiscreteDistribution(std::span<const double> weights) {
    PF_CHECK(!weights.empty());
    cdf_.resize(weights.size());
    probabilities_.resize(weights.size());
    double running = 0;
    for (size_t i = 0; i < weights.size(); ++i) {
        PF_CHECK(std::isfinite(weights[i]) && weights[i] >= 0);
        running += weights[i];
        cdf_[i] = running;
    }
    PF_CHECK(running > 0);
    total_ = running;
    for (size_t i = 0; i < weights.size(); ++i) {
        cdf_[i] /= running;
        probabilities_[i] = weights[i] / running;
    }
    cdf_.back() = 1.0;
}

DiscreteDistribution::Sample DiscreteDistribution::Draw(float u) const {
    // The first item whose CDF exceeds u; items of zero weight share their predecessor's
    // CDF value, so they are never chosen. Few items (a scene's lights, typically): count the
    // CDF values not above u, without branches the predictor would lose on random u.
    size_t index = 0;
    if (cdf_.size() <= kLinearSearchLimit) {
        for (double value : cdf_) index += value <= u;
    } else {
        index = static_cast<size_t>(
            std::upper_bound(cdf_.begin(), cdf_.end(), static_cast<double>(u)) - cdf_.begin());
    }
    index = std::min(index, cdf_.size() - 1);
    return {static_cast<uint32_t>(index), probabilities_[index]};
}

float DiscreteDistribution::Remap(float u, uint32_t index) const {
    const double below = index == 0 ? 0.0 : cdf_[index - 1];
    const double remapped = (double(u) - below) / probabilities_[index];
    return std::clamp(static_cast<float>(remapped), 0.0f, 0x1.fffffep-1f);
}

double DiscreteDistribution::Probability(uint32_t index) const { return probabilities_[index]; }

}  // namespace pf
