// A discrete distribution over weighted items, sampled by inverting its CDF. Used to pick
// emitters in proportion to their power.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace pf {

class DiscreteDistribution {
public:
    DiscreteDistribution() = default;
    // Weights must be finite and non-negative with a positive sum (checked).
    explicit DiscreteDistribution(std::span<const double> weights);

    struct Sample {
        uint32_t index;
        double probability;
    };
    // Maps u in [0, 1) to an item with probability weight / total; never returns an item
    // of zero weight.
    Sample Draw(float u) const;
    // Where u lies within item `index`'s share of [0, 1) (the one Draw(u) chose), rescaled to
    // [0, 1): a number as uniform as u and independent of the choice, for a second use.
    float Remap(float u, uint32_t index) const;
    double Probability(uint32_t index) const;
    double Total() const { return total_; }
    size_t Size() const { return probabilities_.size(); }

private:
    static constexpr size_t kLinearSearchLimit = 32;
    std::vector<double> cdf_;            // cdf_[i] = sum of weights [0, i] / total
    std::vector<double> probabilities_;  // weight / total
    double total_ = 0;
};

}  // namespace pf
