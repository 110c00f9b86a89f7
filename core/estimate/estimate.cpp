// Estimates of any kind: merging an epoch, and loading a saved one.
#include "core/estimate/estimate.h"

#include "core/estimate/pixel_estimate.h"
#include "core/estimate/progressive_estimate.h"
#include "core/util/check.h"

namespace pf {

void Estimate::MergeEpoch(std::span<const BatchResult> results) {
    PF_CHECK(BatchesFolded() == 0);
    for (const BatchResult& result : results) FoldBatch(result);
    FinishEpoch();
}

absl::StatusOr<std::unique_ptr<Estimate>> LoadEstimate(ByteReader& in, ByteReader* fixed) {
    ByteReader peek = in;
    uint32_t magic = 0;
    if (!peek.Value(&magic)) return absl::DataLossError("estimate state: empty");
    if (magic != kPixelEstimateMagic) return ProgressiveEstimate::Load(in, fixed);
    if (fixed != nullptr)
        return absl::DataLossError("estimate state: a fixed part given to a pixel estimate");
    return PixelEstimate::Load(in);
}

}  // namespace pf
