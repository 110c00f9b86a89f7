// Batch layout: epochs are numbered ranges of batches whose direct-light slices tile the
// hit points exactly.
#include "core/job/batch.h"

#include <gtest/gtest.h>

namespace pf {
namespace {

TEST(BatchTest, DirectSlicesTileTheHitPointsAndIndicesAreGlobal) {
    const BatchLayout layout{1000, 7};
    for (uint32_t hit_points : {0u, 1u, 6u, 7u, 1000u, 123457u}) {
        uint32_t next = 0;
        for (uint32_t j = 0; j < layout.batches_per_epoch; ++j) {
            const BatchSpec spec = MakeBatchSpec(layout, 3, j, hit_points);
            EXPECT_EQ(spec.index, 3u * 7u + j);
            EXPECT_EQ(spec.epoch, 3u);
            EXPECT_EQ(spec.photons, 1000u);
            EXPECT_EQ(spec.sample_begin, next);
            next = spec.sample_end;
        }
        EXPECT_EQ(next, hit_points);
    }
}

}  // namespace
}  // namespace pf
