// The photon pass: runs one batch (photon paths from the lights, gathered at the hit points
// within their current radius, plus the batch's slice of direct-light samples at the epoch's
// camera samples).
#pragma once

#include <tbb/enumerable_thread_specific.h>

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/geometry/tracer.h"
#include "core/job/batch.h"
#include "core/job/hit_point.h"
#include "core/ppm/direct_light.h"
#include "core/ppm/hash_grid.h"
#include "core/ppm/tally_accumulator.h"
#include "core/sampling/rng.h"
#include "core/scene/emitters.h"
#include "core/scene/scene.h"
#include "core/scene/scene_features.h"

namespace pf {

// Longest photon path followed; Russian roulette ends paths long before it (with albedo
// 0.999 the chance of reaching it is about e^-65).
inline constexpr int kMaxPhotonBounces = 1 << 16;

// Everything a batch reads; fixed for the duration of an epoch and shared by all threads.
struct PhotonPassInputs {
    const Scene* scene = nullptr;
    const Emitters* emitters = nullptr;
    const Tracer* tracer = nullptr;
    std::span<const HitPoint> hit_points;  // where photons gather
    const HashGrid* grid = nullptr;        // built over hit_points with this epoch's radii
    uint64_t seed = 0;
    // What the scene uses (AnalyseFeatures): chunks run the photon loop instantiated for it,
    // so a scene without specular materials or textures runs no code for them. All by default.
    SceneFeatures features = SceneFeatures::All();
    // Surfaces a photon reaches at most (JobSpec::max_depth, as DepthLimit gives it).
    int max_bounces = kMaxPhotonBounces;
    // Where the batches' direct-light slices sample: the epoch's camera pass (for sppm the
    // hit points themselves); empty: the hit points.
    std::span<const HitPoint> direct_points;
    uint64_t direct_offset = 0;  // the slot of direct_points[0] in the pass (a part of it)
    std::span<const HitPoint> DirectPoints() const {
        return direct_points.empty() ? hit_points : direct_points;
    }
    // Given, the direct points are that pass's slots and take its camera samples' numbers
    // (DirectLightSequence); otherwise a stream per point.
    std::optional<DirectLightSequence> direct_sequence;
    // Adaptive photon tracing (core/shared/photon_chain.h): each chunk runs Markov chains
    // toward the photons that reach a hit point instead of tracing independent photons.
    bool adaptive = false;
    // Photons deposit at their first surface too (kDirectPhoton), for hit points that gather
    // direct light (rpm's gather hits); otherwise only once they have scattered.
    bool direct_photons = false;
};

// A batch gathers its deposits once this many are pending (about 80 MB of deposits and keys
// per thread), so memory stays bounded however many bounces the photons make.
inline constexpr size_t kMaxPendingDeposits = size_t{1} << 20;

// The streams of batch `batch_index`'s photons: photon p draws from
// Rng(PhotonSeeds(seed, batch_index).Seed(p)), on every backend.
SeedFamily PhotonSeeds(uint64_t seed, uint64_t batch_index);
// The streams of batch `batch_index`'s chain mutations in adaptive tracing, one a step (the
// step's photon index), apart from its photons'.
SeedFamily ProposalSeeds(uint64_t seed, uint64_t batch_index);

// Where a photon landed on a diffuse surface (after scattering at least once, but where
// PhotonPassInputs::direct_photons).
struct PhotonDeposit {
    Vec3 position;
    Vec3 direction;  // of travel, unit
    Rgb flux;        // W x N_emitted
    Vec3 normal;     // the surface's where it landed, toward the side it arrived from
    uint32_t kind;   // how it came there: kDirectPhoton, kCausticPhoton or kDiffusePhoton
};

// One thread's reusable working memory for batches; not thread-safe.
struct BatchScratch {
    TallyAccumulator tally;
    std::vector<PhotonDeposit> deposits;  // in path order
    // Adaptive tracing: how many steps each deposit stands for (its flux their sum); empty in
    // uniform tracing, where each stands for one.
    std::vector<uint32_t> deposit_counts;
    std::vector<PhotonDeposit> sorted_deposits;  // in gather order
    std::vector<uint32_t> sorted_counts;
    std::vector<uint64_t> sort_keys;  // grid bucket << 32 | deposit index
    std::vector<uint64_t> sort_scratch;
    uint64_t nonfinite_discarded = 0;  // of the chunk being traced
    // Adaptive tracing: each chain's state's deposits and its candidate's (one chain a lane),
    // and the chunk's counts (ChunkResult).
    std::vector<PhotonDeposit> chain_state[Tracer::kPacketSize];
    std::vector<PhotonDeposit> chain_candidate[Tracer::kPacketSize];
    uint64_t visible_photons = 0, chain_steps = 0;
};

// Working memory for RunPhotonBatches, kept across calls: one BatchScratch per thread, and
// the sums of the batch whose chunks are being combined.
struct PhotonPassScratch {
    tbb::enumerable_thread_specific<BatchScratch> threads;
    TallyAccumulator combined;
};

// What one chunk of a batch found.
struct ChunkResult {
    Tally tally;
    uint64_t segments_traced = 0;
    uint64_t nonfinite_discarded = 0;  // paths ended because their flux was NaN or Inf
    // Adaptive tracing: of the chunk's fresh photons, those visible (the visible share V_c
    // times the photons); the steps where a chain held a state and contributed it.
    uint64_t visible_photons = 0, chain_steps = 0;
};

// Chunk `chunk` of batch `spec` (photons [chunk, chunk + 1) x kPhotonsPerChunk of it): traces
// its photons, then gathers their deposits at the hit points.
ChunkResult RunPhotonChunk(const PhotonPassInputs& inputs, const BatchSpec& spec, uint32_t chunk,
                           BatchScratch& scratch);

// The share of photons whose deposits reach some hit point within its radius: adaptive
// tracing's V_c, measured over `photons` fresh photons of a stream apart from every batch's.
// `inputs.grid` built.
double VisiblePhotonShare(const PhotonPassInputs& inputs, uint32_t photons);

// Auto photon tracing: adaptive where under this share of a pilot's kVisibilityPilotPhotons
// reach a hit point at their first radii. A chain's step costs two to three uniform photons
// (the fresh photon, the mutation, the visibility tests), so the chains must find several
// times as many photons that count to pay. At 128x128, 20 s on two cores (docs/integrators.md):
// adaptive ahead on light-gap (0.8% visible) and caustic-glass (1.4%), behind on caustic-room
// (23%) and cornell-box (40%).
inline constexpr double kAdaptiveBelowVisibleShare = 0.05;
inline constexpr uint32_t kVisibilityPilotPhotons = 1u << 15;

// Runs the batches on the calling TBB arena: every chunk of every batch in parallel, each
// batch's chunk tallies summed in chunk order, and each batch's slice of direct-light
// samples. Results in the order of `specs`, each a pure function of its spec.
std::vector<BatchResult> RunPhotonBatches(const PhotonPassInputs& inputs,
                                          std::span<const BatchSpec> specs,
                                          PhotonPassScratch& scratch);

}  // namespace pf
