// Batch layout arithmetic.
#include "core/job/batch.h"

#include "core/util/check.h"

namespace pf {

uint32_t BatchLayout::GrowingEpochs() const {
    // Halvings of a full epoch that keep at least first_epoch_photons; a batch keeps a photon.
    uint32_t growing = 0;
    while (first_epoch_photons > 0 && (photons_per_batch >> (growing + 1)) > 0 &&
           uint64_t{photons_per_batch >> (growing + 1)} * batches_per_epoch >= first_epoch_photons)
        ++growing;
    return growing;
}

BatchSpec MakeBatchSpec(const BatchLayout& layout, uint64_t epoch, uint32_t batch_in_epoch,
                        uint32_t hit_point_count) {
    PF_CHECK(batch_in_epoch < layout.batches_per_epoch);
    const uint64_t slice_begin =
        uint64_t{hit_point_count} * batch_in_epoch / layout.batches_per_epoch;
    const uint64_t slice_end =
        uint64_t{hit_point_count} * (batch_in_epoch + 1) / layout.batches_per_epoch;
    return {epoch * layout.batches_per_epoch + batch_in_epoch, epoch, layout.PhotonsPerBatch(epoch),
            static_cast<uint32_t>(slice_begin), static_cast<uint32_t>(slice_end)};
}

std::pair<uint64_t, uint64_t> SlicePixels(const BatchSpec& spec, uint64_t slots_per_pixel) {
    PF_CHECK(slots_per_pixel > 0);
    const auto first_at_or_after = [&](uint64_t slot) {
        return (slot + slots_per_pixel - 1) / slots_per_pixel;
    };
    return {first_at_or_after(spec.sample_begin), first_at_or_after(spec.sample_end)};
}

}  // namespace pf
