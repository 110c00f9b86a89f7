// Batch layout arithmetic.
#include "core/job/batch.h"

#include "core/util/check.h"

namespace pf {

BatchSpec MakeBatchSpec(const BatchLayout& layout, uint64_t epoch, uint32_t batch_in_epoch,
                        uint32_t hit_point_count) {
    PF_CHECK(batch_in_epoch < layout.batches_per_epoch);
    const uint64_t slice_begin =
        uint64_t{hit_point_count} * batch_in_epoch / layout.batches_per_epoch;
    const uint64_t slice_end =
        uint64_t{hit_point_count} * (batch_in_epoch + 1) / layout.batches_per_epoch;
    return {epoch * layout.batches_per_epoch + batch_in_epoch, epoch, layout.photons_per_batch,
            static_cast<uint32_t>(slice_begin), static_cast<uint32_t>(slice_end)};
}

}  // namespace pf
