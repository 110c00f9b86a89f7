// A progressive estimate saved and loaded between any two folds goes on exactly as one never
// interrupted: the coordinator's checkpoints depend on it (server/job_checkpoint.cpp).
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "core/estimate/pixel_estimate.h"
#include "core/estimate/progressive_estimate.h"

namespace pf {
namespace {

constexpr uint32_t kHitPoints = 300;
constexpr int kEpochs = 5;

// Where a hit point's surface ends: some within the radius, some not at all.
SurfaceExtent EdgeOf(uint64_t i) {
    SurfaceExtent extent = SurfaceExtent::Unbounded();
    if (i % 3 != 0) extent.reach[i % gpu::kEdgeSectors] = 0.05f * float(i % 11);
    return extent;
}

// Each epoch's camera pass of a stochastic estimate: every slot (pixel * 3 + sample of a 10x10
// film) traced anew, a few black, weights and emission changing with the epoch.
CameraPassResult StochasticPass(uint64_t epoch) {
    CameraPassResult pass;
    pass.emission = Image(10, 10);
    pass.emission.At(int(epoch % 10), 4) = Rgb(2.0f, 1.0f, 0.5f);
    std::mt19937 rng(static_cast<uint32_t>(epoch + 3));
    for (uint32_t i = 0; i < kHitPoints; ++i) {
        const bool empty = rng() % 7 == 0;
        pass.hit_points.push_back(
            {Vec3(float(i) + 0.1f * float(epoch), 0, 0), Vec3(0, 0, 1),
             empty ? Rgb(0.0f) : Rgb(0.1f + 0.01f * float(rng() % 17), 0.2f, 0.3f), i / 3});
        pass.footprint.push_back(empty ? 0.0f : 0.5f);
        pass.extent.push_back(EdgeOf(i + epoch));
    }
    return pass;
}

ProgressiveEstimate MakeEstimate() {
    CameraPassResult camera_pass;
    camera_pass.emission = Image(10, 10);
    camera_pass.emission.At(3, 4) = Rgb(2.0f, 1.0f, 0.5f);
    std::mt19937 rng(7);
    for (uint32_t i = 0; i < kHitPoints; ++i) {
        camera_pass.hit_points.push_back({Vec3(float(i), 0, 0), Vec3(0, 0, 1),
                                          Rgb(0.1f + 0.001f * float(i % 17), 0.2f, 0.3f),
                                          uint32_t(rng() % 100)});
        camera_pass.extent.push_back(EdgeOf(i));
    }
    EstimateSettings settings;
    settings.initial_radius = 0.5;
    settings.samples_per_pixel = 3;
    // Each epoch's alpha from the error so far: a restored estimate must choose it alike.
    settings.balanced = true;
    // Epochs of 500, 1000, 2000, then 4000 photons (and 2, 4, 8, then 16 camera samples a
    // pixel): saved within the growing epochs and after them.
    settings.layout = {1000, 4, 500};
    return ProgressiveEstimate(std::move(camera_pass), settings, {});
}

// A made-up result for batch `spec` of `estimate`: random hit points, counts and flux, and for
// ppm its share of the emission pass, from a seed of its own.
BatchResult RandomBatch(const Estimate& estimate, const BatchSpec& spec) {
    std::mt19937 rng(static_cast<uint32_t>(spec.index * 7919 + 13));
    BatchResult result;
    result.spec = spec;
    for (uint32_t i = 0; i < kHitPoints; ++i) {
        if (rng() % 3 != 0) continue;
        const uint32_t photons = 1 + rng() % 5;
        result.tally.hit_point.push_back(i);
        result.tally.photons.push_back(photons);
        result.tally.inner_photons.push_back(rng() % (photons + 1));
        result.tally.flux.push_back(
            Rgb(float(rng() % 1000) * 1e-3f, float(rng() % 1000) * 1e-3f, 0.25f));
    }
    for (uint32_t i = spec.sample_begin; i < spec.sample_end; ++i)
        result.samples.push_back(Rgb(float(rng() % 100) * 1e-2f, 0.5f, 0.0f));
    result.photons_emitted = spec.photons;
    const auto [pixels, covered] = estimate.EmissionShape(spec);
    for (uint64_t p = 0; p < pixels; ++p)
        result.emission.push_back(p % 7 == 0 ? Rgb(2.0f, 1.0f, float(rng() % 10)) : Rgb(0.0f));
    for (uint64_t k = 0; k < covered; ++k)
        result.coverage.push_back(Rgb(0.02f * float(rng() % 10), 0.05f, 0.03f));
    return result;
}

void FoldNext(ProgressiveEstimate& estimate) {
    estimate.FoldBatch(RandomBatch(estimate, estimate.EpochBatches()[estimate.BatchesFolded()]));
    if (estimate.BatchesFolded() == estimate.Settings().layout.batches_per_epoch)
        estimate.FinishEpoch();
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
        absl::StatusOr<std::unique_ptr<ProgressiveEstimate>> loaded =
            ProgressiveEstimate::Load(reader);
        ASSERT_TRUE(loaded.ok()) << loaded.status();
        EXPECT_TRUE(reader.AtEnd());
        EXPECT_TRUE(SamePixels((*loaded)->Resolve(), current.Resolve())) << "after fold " << b;
        estimate = std::move(*loaded);
        FoldNext(*estimate);
    }
    EXPECT_EQ(estimate->Epoch(), uint64_t(kEpochs));
    ASSERT_EQ(estimate->HitPoints().size(), uninterrupted.HitPoints().size());
    EXPECT_EQ(std::memcmp(estimate->HitPoints().data(), uninterrupted.HitPoints().data(),
                          kHitPoints * sizeof(HitPoint)),
              0)
        << "hit points, pixels included, come back as they were";
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

// Every kind of estimate, fed made-up batches, saved and loaded through LoadEstimate after
// every fold, ends bit-identical to one never interrupted.
using EstimateFactory = std::unique_ptr<Estimate> (*)();
struct EstimateKind {
    const char* name;
    EstimateFactory make;
};

// A stochastic estimate of `samples` camera samples a pixel, each with `gather_rays` (rpm's,
// at alpha 1) besides, whose passes `passes` traces.
std::unique_ptr<Estimate> MakeStochasticOf(int samples, uint32_t gather_rays,
                                           EpochCameraPass passes) {
    EstimateSettings settings;
    settings.stochastic = true;
    if (gather_rays > 0) settings.alpha = 1;
    settings.gather_rays = gather_rays;
    settings.initial_radius = 0.5;
    settings.samples_per_pixel = samples;
    settings.layout = {1000, 4};
    CameraPassResult first = passes(0);
    return std::make_unique<ProgressiveEstimate>(std::move(first), settings, std::move(passes));
}

std::unique_ptr<Estimate> MakeStochastic() { return MakeStochasticOf(3, 0, StochasticPass); }

// rpm's passes: the stochastic ones, each slot with a radius of its epoch's (0 for some, which
// keep theirs).
CameraPassResult ReversePass(uint64_t epoch) {
    CameraPassResult pass = StochasticPass(epoch);
    for (uint32_t i = 0; i < kHitPoints; ++i)
        pass.radius.push_back((i + epoch) % 5 == 0 ? 0.0f : 0.2f + 0.05f * float((i + epoch) % 7));
    return pass;
}

// rpm's: one camera sample a pixel with two gather rays, the three slots of each pixel.
std::unique_ptr<Estimate> MakeReverse() { return MakeStochasticOf(1, 2, ReversePass); }

std::unique_ptr<Estimate> MakePpm() {
    return std::make_unique<ProgressiveEstimate>(MakeEstimate());
}

std::unique_ptr<Estimate> MakePixels() {
    return std::make_unique<PixelEstimate>(
        PixelEstimateSettings{Integrator::kPath, 10, 10, 2, 4, 0});
}

class AnyEstimateStateTest : public ::testing::TestWithParam<EstimateKind> {};

TEST_P(AnyEstimateStateTest, SavedAndLoadedAtEveryFoldItEndsBitIdentical) {
    const auto fold_next = [](Estimate& estimate) {
        BatchResult result =
            RandomBatch(estimate, estimate.EpochBatches()[estimate.BatchesFolded()]);
        if (!GathersAtHitPoints(estimate.Kind())) result.tally = {}, result.photons_emitted = 0;
        estimate.FoldBatch(result);
        if (estimate.BatchesFolded() == estimate.EpochBatches().size()) estimate.FinishEpoch();
    };
    std::unique_ptr<Estimate> uninterrupted = GetParam().make();
    for (int b = 0; b < kEpochs * 4; ++b) fold_next(*uninterrupted);
    std::unique_ptr<Estimate> estimate = GetParam().make();
    for (int b = 0; b < kEpochs * 4; ++b) {
        ByteWriter writer;
        estimate->Save(writer);
        ByteReader reader(writer.Bytes());
        absl::StatusOr<std::unique_ptr<Estimate>> loaded = LoadEstimate(reader);
        ASSERT_TRUE(loaded.ok()) << loaded.status();
        EXPECT_TRUE(reader.AtEnd());
        EXPECT_EQ((*loaded)->Kind(), estimate->Kind());
        EXPECT_TRUE(SamePixels((*loaded)->Resolve(), estimate->Resolve())) << "after fold " << b;
        if (TracesHitPointsEachEpoch((*loaded)->Kind()))  // its next epochs' camera passes, as
                                                          // the coordinator reattaches them
            static_cast<ProgressiveEstimate&>(**loaded).SetEpochCameraPass(
                (*loaded)->Kind() == Integrator::kRpm ? ReversePass : StochasticPass);
        estimate = std::move(*loaded);
        fold_next(*estimate);
    }
    EXPECT_EQ(estimate->Epoch(), uint64_t(kEpochs));
    EXPECT_EQ(estimate->CameraSamples(), uninterrupted->CameraSamples());
    EXPECT_TRUE(SamePixels(estimate->Resolve(), uninterrupted->Resolve()));
    EXPECT_EQ(estimate->EstimateError().rmse, uninterrupted->EstimateError().rmse);
}

INSTANTIATE_TEST_SUITE_P(Kinds, AnyEstimateStateTest,
                         ::testing::Values(EstimateKind{"ppm", MakePpm},
                                           EstimateKind{"sppm", MakeStochastic},
                                           EstimateKind{"rpm", MakeReverse},
                                           EstimateKind{"path", MakePixels}),
                         [](const auto& param_info) { return std::string(param_info.param.name); });

// A ppm estimate's hit points saved once, apart (SaveFixed), and at every fold only the rest
// (FixedPart::kApart): loaded from the two, every array comes back bit for bit (saved again,
// the same bytes as the whole state) and the render ends as one never interrupted. The part
// apart stays the same over the whole render.
TEST(EstimateStateTest, HitPointsKeptApartOnceItEndsBitIdentical) {
    ProgressiveEstimate uninterrupted = MakeEstimate();
    for (int b = 0; b < kEpochs * 4; ++b) FoldNext(uninterrupted);

    ProgressiveEstimate first = MakeEstimate();
    ByteWriter fixed;
    ASSERT_TRUE(first.SaveFixed(fixed));
    std::unique_ptr<ProgressiveEstimate> estimate;
    for (int b = 0; b < kEpochs * 4; ++b) {
        ProgressiveEstimate& current = estimate ? *estimate : first;
        ByteWriter fixed_now, apart, whole;
        ASSERT_TRUE(current.SaveFixed(fixed_now));
        EXPECT_EQ(fixed_now.Bytes(), fixed.Bytes()) << "after fold " << b;
        current.Save(apart, FixedPart::kApart);
        current.Save(whole);
        EXPECT_LT(apart.Bytes().size(), whole.Bytes().size());
        ByteReader reader(apart.Bytes()), fixed_reader(fixed.Bytes());
        absl::StatusOr<std::unique_ptr<ProgressiveEstimate>> loaded =
            ProgressiveEstimate::Load(reader, &fixed_reader);
        ASSERT_TRUE(loaded.ok()) << loaded.status();
        EXPECT_TRUE(reader.AtEnd() && fixed_reader.AtEnd());
        ByteWriter again;
        (*loaded)->Save(again);
        EXPECT_TRUE(again.Bytes() == whole.Bytes()) << "after fold " << b;
        estimate = std::move(*loaded);
        FoldNext(*estimate);
    }
    ASSERT_EQ(estimate->HitPoints().size(), uninterrupted.HitPoints().size());
    EXPECT_EQ(std::memcmp(estimate->HitPoints().data(), uninterrupted.HitPoints().data(),
                          kHitPoints * sizeof(HitPoint)),
              0);
    EXPECT_TRUE(SamePixels(estimate->Resolve(), uninterrupted.Resolve()));
    EXPECT_EQ(estimate->EstimateError().rmse, uninterrupted.EstimateError().rmse);
    for (uint32_t i = 0; i < kHitPoints; ++i) {
        EXPECT_EQ(estimate->Point(i).radius_sq, uninterrupted.Point(i).radius_sq);
        EXPECT_EQ(estimate->Point(i).flux.x, uninterrupted.Point(i).flux.x);
    }
}

// sppm and rpm trace their hit points anew every epoch and path has none: nothing of them is
// fixed,
// and a state saved "apart" is the whole state.
TEST(EstimateStateTest, OnlyPpmKeepsAPartApart) {
    std::vector<std::unique_ptr<Estimate>> estimates;
    estimates.push_back(MakeStochastic());
    estimates.push_back(MakeReverse());
    estimates.push_back(MakePixels());
    for (const std::unique_ptr<Estimate>& estimate : estimates) {
        ByteWriter fixed, apart, whole;
        EXPECT_FALSE(estimate->SaveFixed(fixed));
        EXPECT_TRUE(fixed.Bytes().empty());
        estimate->Save(apart, FixedPart::kApart);
        estimate->Save(whole);
        EXPECT_TRUE(apart.Bytes() == whole.Bytes()) << IntegratorName(estimate->Kind());
    }
}

// The state's arrays are packed: those of a fresh estimate (N = 0, R = R0, tau = 0 at every
// hit point; ~210 bytes a hit point unpacked) take almost nothing.
TEST(EstimateStateTest, AStateIsPacked) {
    const ProgressiveEstimate estimate = MakeEstimate();
    ByteWriter apart;
    estimate.Save(apart, FixedPart::kApart);
    EXPECT_LT(apart.Bytes().size(), 5 * kHitPoints) << apart.Bytes().size() << " bytes";
}

TEST(EstimateStateTest, TruncatedOrAlteredStatesAreRefused) {
    ProgressiveEstimate estimate = MakeEstimate();
    FoldNext(estimate);
    ByteWriter writer;
    estimate.Save(writer);
    const std::string bytes = writer.Bytes();
    for (size_t length : {size_t{0}, size_t{7}, bytes.size() / 2, bytes.size() - 1}) {
        ByteReader reader(std::string_view(bytes).substr(0, length));
        const absl::StatusOr<std::unique_ptr<ProgressiveEstimate>> loaded =
            ProgressiveEstimate::Load(reader);
        ASSERT_FALSE(loaded.ok()) << length << " bytes";
        EXPECT_TRUE(absl::IsDataLoss(loaded.status())) << loaded.status();
    }
    // A hit point count that does not match the arrays after it.
    std::string altered = bytes;
    const uint64_t fewer = estimate.HitPoints().size() - 1;
    std::memcpy(altered.data() + 8, &fewer, sizeof(fewer));
    ByteReader reader(altered);
    EXPECT_TRUE(absl::IsDataLoss(ProgressiveEstimate::Load(reader).status()));
    // Bytes of its packed arrays (its second half) altered: refused, or where zstd ignores the
    // change, the same state; never other numbers.
    size_t refused = 0, tried = 0;
    for (size_t at = bytes.size() / 2; at < bytes.size(); at += 7, ++tried) {
        std::string flipped = bytes;
        flipped[at] = static_cast<char>(flipped[at] ^ 0x10);
        ByteReader flipped_reader(flipped);
        absl::StatusOr<std::unique_ptr<ProgressiveEstimate>> loaded =
            ProgressiveEstimate::Load(flipped_reader);
        if (!loaded.ok()) {
            EXPECT_TRUE(absl::IsDataLoss(loaded.status())) << loaded.status();
            ++refused;
            continue;
        }
        ByteWriter again;
        (*loaded)->Save(again);
        EXPECT_TRUE(again.Bytes() == bytes) << "byte " << at << " altered, read as other numbers";
    }
    EXPECT_GT(refused, tried * 9 / 10);
}

// Hit points kept apart: a state without them, or given hit points it does not hold apart,
// or another count of them, or them cut short, is refused.
TEST(EstimateStateTest, MissingOrForeignHitPointsAreRefused) {
    ProgressiveEstimate estimate = MakeEstimate();
    FoldNext(estimate);
    ByteWriter fixed, apart, whole;
    ASSERT_TRUE(estimate.SaveFixed(fixed));
    estimate.Save(apart, FixedPart::kApart);
    estimate.Save(whole);
    const auto load = [](const std::string& state, const std::string* hit_points) {
        ByteReader reader(state);
        ByteReader fixed_reader(hit_points ? std::string_view(*hit_points) : "");
        return LoadEstimate(reader, hit_points ? &fixed_reader : nullptr).status();
    };
    ASSERT_TRUE(load(apart.Bytes(), &fixed.Bytes()).ok());
    const absl::Status missing = load(apart.Bytes(), nullptr);
    EXPECT_TRUE(absl::IsDataLoss(missing));
    EXPECT_NE(missing.message().find("kept apart"), std::string_view::npos) << missing;
    EXPECT_TRUE(absl::IsDataLoss(load(whole.Bytes(), &fixed.Bytes())));
    std::string other_count = fixed.Bytes();
    const uint64_t more = kHitPoints + 1;
    std::memcpy(other_count.data() + 8, &more, sizeof(more));  // after magic and version
    EXPECT_TRUE(absl::IsDataLoss(load(apart.Bytes(), &other_count)));
    for (size_t length :
         {size_t{0}, size_t{4}, fixed.Bytes().size() / 2, fixed.Bytes().size() - 1}) {
        const std::string cut = fixed.Bytes().substr(0, length);
        EXPECT_TRUE(absl::IsDataLoss(load(apart.Bytes(), &cut))) << length << " bytes";
    }
    const std::string longer = fixed.Bytes() + "x";
    EXPECT_TRUE(absl::IsDataLoss(load(apart.Bytes(), &longer))) << "bytes after the hit points";
    ByteWriter pixel_state;
    MakePixels()->Save(pixel_state);
    EXPECT_TRUE(absl::IsDataLoss(load(pixel_state.Bytes(), &fixed.Bytes())));
}

}  // namespace
}  // namespace pf
