// The schedule of a job's epochs: small epochs first, growing to full ones, and the camera
// samples each epoch's pass takes, stratified across epochs of each parity.
#include <gtest/gtest.h>

#include "core/job/batch.h"
#include "core/job/job_spec.h"

namespace pf {
namespace {

TEST(EpochScheduleTest, EpochsGrowByDoublingFromTheFirstToAFullEpoch) {
    const BatchLayout layout{1u << 19, 8, 1u << 18};
    EXPECT_EQ(layout.GrowingEpochs(), 4u);
    for (uint64_t epoch = 0; epoch < 4; ++epoch)
        EXPECT_EQ(layout.PhotonsInEpoch(epoch), uint64_t{1} << (18 + epoch)) << epoch;
    for (uint64_t epoch : {4ull, 5ull, 1000ull})
        EXPECT_EQ(layout.PhotonsInEpoch(epoch), layout.PhotonsPerEpoch());
    for (uint32_t j = 0; j < 8; ++j) {
        const BatchSpec spec = MakeBatchSpec(layout, 1, j, 64);
        EXPECT_EQ(spec.index, 8u + j);  // indices stay epoch * batches + j
        EXPECT_EQ(spec.photons, 1u << 16);
    }
}

TEST(EpochScheduleTest, TheFirstEpochHasAtLeastTheFirstPhotonsAndUnderTwiceAsMany) {
    for (uint32_t per_batch : {1u, 3u, 1000u, 12345u, 1u << 19})
        for (uint32_t batches : {1u, 7u, 8u})
            for (uint64_t first : {1ull, 1000ull, 1ull << 18, 1ull << 40}) {
                const BatchLayout layout{per_batch, batches, first};
                const uint64_t photons = layout.PhotonsInEpoch(0);
                EXPECT_GE(layout.PhotonsPerBatch(0), 1u);
                if (layout.GrowingEpochs() > 0) {
                    EXPECT_GE(photons, first);
                    EXPECT_LT(photons, 2 * first + batches);  // floor per batch
                } else {
                    EXPECT_EQ(photons, layout.PhotonsPerEpoch());
                }
            }
}

TEST(EpochScheduleTest, NoFirstEpochGivenMeansFullEpochs) {
    const BatchLayout layout{1000, 7};
    EXPECT_EQ(layout.GrowingEpochs(), 0u);
    EXPECT_EQ(layout.PhotonsInEpoch(0), 7000u);
}

JobSpec Ppm(int width, int height) {
    JobSpec spec;
    spec.integrator = Integrator::kPpm;
    spec.width = width;
    spec.height = height;
    return spec;
}

TEST(EpochScheduleTest, PpmLeftOpenStartsSmallAndAGivenLayoutStaysFull) {
    const BatchLayout open = ResolvedLayout(Ppm(128, 128), 128 * 128);
    EXPECT_EQ(open.PhotonsPerEpoch(), uint64_t{kDefaultPhotonsPerBatch} * kDefaultBatchesPerEpoch);
    EXPECT_EQ(open.PhotonsInEpoch(0), kFirstEpochPhotons);
    EXPECT_EQ(ResolvedLayout(Ppm(128, 128), 128 * 128).first_epoch_photons,
              open.first_epoch_photons);  // resolving again changes nothing
    JobSpec given = Ppm(128, 128);
    given.layout.photons_per_batch = 1u << 16;
    const BatchLayout full = ResolvedLayout(given, 128 * 128);
    EXPECT_EQ(full.GrowingEpochs(), 0u);
    JobSpec asked = Ppm(128, 128);
    asked.layout.first_epoch_photons = 1u << 20;
    EXPECT_EQ(ResolvedLayout(asked, 128 * 128).PhotonsInEpoch(0), uint64_t{1} << 20);
    asked.layout.first_epoch_photons = uint64_t{1} << 40;  // more than an epoch: full ones
    EXPECT_EQ(ResolvedLayout(asked, 128 * 128).first_epoch_photons,
              uint64_t{kDefaultPhotonsPerBatch} * kDefaultBatchesPerEpoch);
    JobSpec sppm = Ppm(128, 128);
    sppm.integrator = Integrator::kSppm;
    EXPECT_EQ(ResolvedLayout(sppm, 128 * 128).GrowingEpochs(), 0u);
}

TEST(EpochScheduleTest, PpmSamplesGrowWithItsEpochsAndCountOnPerParity) {
    const JobSpec spec = Ppm(128, 128);
    const uint64_t pixels = 128 * 128;
    const BatchLayout layout = ResolvedLayout(spec, pixels);
    uint64_t sums[2] = {0, 0};
    int last = 0;
    for (uint64_t epoch = 0; epoch < 40; ++epoch) {
        const EpochSamples samples = EpochCameraSamples(spec, epoch);
        // One sample per two photons of the epoch, a power of two in [1, 64].
        const uint64_t per_two = layout.PhotonsInEpoch(epoch) / (2 * pixels);
        EXPECT_LE(uint64_t(samples.per_pixel), std::max<uint64_t>(per_two, 1)) << epoch;
        EXPECT_TRUE(samples.per_pixel == 64 || uint64_t(2 * samples.per_pixel) > per_two) << epoch;
        EXPECT_GE(samples.per_pixel, last);
        last = samples.per_pixel;
        // Each parity's samples continue where its last epoch's ended.
        EXPECT_EQ(samples.first, sums[epoch & 1]) << epoch;
        sums[epoch & 1] += uint64_t(samples.per_pixel);
    }
    EXPECT_EQ(EpochCameraSamples(spec, 0).per_pixel, 8);  // 2^18 photons over 2 x 16384
    EXPECT_EQ(MaxEpochSamplesPerPixel(spec), 64);
}

TEST(EpochScheduleTest, SppmTakesItsKEveryEpoch) {
    JobSpec spec = Ppm(64, 48);
    spec.integrator = Integrator::kSppm;
    spec.samples_per_pixel = 3;
    spec.layout.first_epoch_photons = 100;  // growing photons; the hit points stay k a pixel
    for (uint64_t epoch = 0; epoch < 9; ++epoch) {
        const EpochSamples samples = EpochCameraSamples(spec, epoch);
        EXPECT_EQ(samples.per_pixel, 3);
        EXPECT_EQ(samples.first, (epoch >> 1) * 3);
    }
}

}  // namespace
}  // namespace pf
