// A progressive estimate saved and loaded between any two folds goes on exactly as one never
// interrupted: the coordinator's checkpoints depend on it (server/job_checkpoint.cpp).
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "core/ppm/progressive_estimate.h"

namespace pf {
namespace {

constexpr uint32_t kHitPoints = 300;
constexpr int kEpochs = 5;

ProgressiveEstimate MakeEstimate() {
    CameraPassResult camera_pass;
    camera_pass.emission = Image(10, 10);
    camera_pass.emission.At(3, 4) = Rgb(2.0f, 1.0f, 0.5f);
    std::mt19937 rng(7);
    for (uint32_t i = 0; i < kHitPoints; ++i)
        camera_pass.hit_points.push_back({Vec3(float(i), 0, 0), Vec3(0, 0, 1),
                                          Rgb(0.1f + 0.001f * float(i % 17), 0.2f, 0.3f), uint32_t(rng() % 100)});
    EstimateSettings settings;
    settings.initial_radius = 0.5;
    settings.samples_per_pixel = 3;
    settings.layout = {1000, 4};
    return ProgressiveEstimate(std::move(camera_pass), settings);
}

// A made-up result for the next batch: random hit points, counts and flux, from a seed of its own.
BatchResult RandomBatch(const BatchSpec& spec) {
    std::mt19937 rng(static_cast<uint32_t>(spec.index * 7919 + 13));
    BatchResult result;
    result.spec = spec;
    for (uint32_t i = 0; i < kHitPoints; ++i) {
        if (rng() % 3 != 0) continue;
        const uint32_t photons = 1 + rng() % 5;
        result.tally.hit_point.push_back(i);
        result.tally.photons.push_back(photons);
        result.tally.inner_photons.push_back(rng() % (photons + 1));
        result.tally.flux.push_back(Rgb(float(rng() % 1000) * 1e-3f, float(rng() % 1000) * 1e-3f, 0.25f));
    }
    for (uint32_t i = spec.sample_begin; i < spec.sample_end; ++i)
        result.samples.push_back(Rgb(float(rng() % 100) * 1e-2f, 0.5f, 0.0f));
    result.photons_emitted = spec.photons;
    return result;
}

void FoldNext(ProgressiveEstimate& estimate) {
    estimate.FoldBatch(RandomBatch(estimate.EpochBatches()[estimate.BatchesFolded()]));
    if (estimate.BatchesFolded() == estimate.Settings().layout.batches_per_epoch) estimate.FinishEpoch();
}

bool SamePixels(const Image& a, const Image& b) {
    return a.width == b.width && a.pixels.size() == b.pixels.size() &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Rgb)) == 0;
}

TEST(EstimateStateTest, SavedAndLoadedAtEveryFoldItEndsBitIdentical) {
    ProgressiveEstimate uninterrupted = MakeEstimate();
    for (int b = 0; b < kEpochs * 4; ++b) FoldNext(uninterrupted);
    const Image expected = uninterrupted.Resolve();
    const ErrorEstimate expected_error = uninterrupted.EstimateError();

    ProgressiveEstimate first = MakeEstimate();
    std::unique_ptr<ProgressiveEstimate> estimate;
    for (int b = 0; b < kEpochs * 4; ++b) {
        ProgressiveEstimate& current = estimate ? *estimate : first;
        ByteWriter writer;
        current.Save(writer);
        ByteReader reader(writer.Bytes());
        absl::StatusOr<std::unique_ptr<ProgressiveEstimate>> loaded = ProgressiveEstimate::Load(reader);
        ASSERT_TRUE(loaded.ok()) << loaded.status();
        EXPECT_TRUE(reader.AtEnd());
        EXPECT_TRUE(SamePixels((*loaded)->Resolve(), current.Resolve())) << "after fold " << b;
        estimate = std::move(*loaded);
        FoldNext(*estimate);
    }
    EXPECT_EQ(estimate->Epoch(), uint64_t(kEpochs));
    ASSERT_EQ(estimate->HitPoints().size(), uninterrupted.HitPoints().size());
    EXPECT_EQ(std::memcmp(estimate->HitPoints().data(), uninterrupted.HitPoints().data(),
                          kHitPoints * sizeof(HitPoint)), 0) << "hit points, pixels included, come back as they were";
    EXPECT_EQ(estimate->PhotonsEmitted(), uninterrupted.PhotonsEmitted());
    EXPECT_TRUE(SamePixels(estimate->Resolve(), expected));
    const ErrorEstimate error = estimate->EstimateError();
    EXPECT_EQ(error.rmse, expected_error.rmse);
    EXPECT_EQ(error.bias_rmse, expected_error.bias_rmse);
    for (uint32_t i = 0; i < kHitPoints; ++i) {
        EXPECT_EQ(estimate->Point(i).radius_sq, uninterrupted.Point(i).radius_sq);
        EXPECT_EQ(estimate->Point(i).photon_count, uninterrupted.Point(i).photon_count);
    }
}

TEST(EstimateStateTest, TruncatedOrAlteredStatesAreRefused) {
    ProgressiveEstimate estimate = MakeEstimate();
    FoldNext(estimate);
    ByteWriter writer;
    estimate.Save(writer);
    const std::string bytes = writer.Bytes();
    for (size_t length : {size_t{0}, size_t{7}, bytes.size() / 2, bytes.size() - 1}) {
        ByteReader reader(std::string_view(bytes).substr(0, length));
        const absl::StatusOr<std::unique_ptr<ProgressiveEstimate>> loaded = ProgressiveEstimate::Load(reader);
        ASSERT_FALSE(loaded.ok()) << length << " bytes";
        EXPECT_TRUE(absl::IsDataLoss(loaded.status())) << loaded.status();
    }
    // A hit point count that does not match the arrays after it.
    std::string altered = bytes;
    const uint64_t fewer = estimate.HitPoints().size() - 1;
    std::memcpy(altered.data() + 8, &fewer, sizeof(fewer));
    ByteReader reader(altered);
    EXPECT_TRUE(absl::IsDataLoss(ProgressiveEstimate::Load(reader).status()));
}

}  // namespace
}  // namespace pf
