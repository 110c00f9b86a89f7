// Photon tracing with Russian roulette and the gather into the hit-point grid
// (Hachisuka et al. 2008, section 4.2; Jensen 2001 for the photon random walk).
#include "core/ppm/photon_pass.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <algorithm>

#include "core/ppm/direct_light.h"
#include "core/ppm/photon_walk.h"
#include "core/sampling/frame.h"
#include "core/sampling/rng.h"
#include "core/sampling/sampling.h"
#include "core/util/check.h"
#include "core/util/radix_sort.h"

namespace pf {
namespace {

// A photon path in flight.
struct PhotonPath {
    Ray ray;
    Rgb flux;
    Rng rng;
    bool scattered = false;  // the first hit of an unscattered photon is direct light
    int bounces = 0;
    const PunctualLight* ranged = nullptr;  // the light's window is still to apply at the first hit
};

// A photon emitted by `numbers` whose walk draws from `rng`.
PhotonPath StartPhotonFrom(const PhotonPassInputs& inputs, const EmissionNumbers& numbers,
                           const Rng& rng) {
    PhotonPath path;
    path.rng = rng;
    const EmittedPhoton emitted = inputs.emitters->Emit(numbers);
    path.ray = emitted.ray;
    path.flux = emitted.flux;
    path.ranged = emitted.ranged;
    return path;
}

// Photon `photon` of the batch whose streams `seeds` holds: its random numbers are a function
// of (job seed, batch index, photon index) alone.
PhotonPath StartPhoton(const PhotonPassInputs& inputs, const SeedFamily& seeds, uint32_t photon) {
    Rng rng(seeds.Seed(photon));
    const EmissionNumbers numbers = EmissionNumbers::Draw(rng);
    return StartPhotonFrom(inputs, numbers, rng);
}

// Continues a path at its hit (ScatterPhotonAt): a deposit at every diffuse hit after the
// first scattering (a coat turning a photon back to its base is a scattering). Returns false where
// the path ends.
template <bool kSpecular, bool kTextures>
bool ScatterPhoton(const PhotonPassInputs& inputs, const RayHit& hit, PhotonPath& path,
                   std::vector<PhotonDeposit>& deposits) {
    if (path.ranged != nullptr) {  // the light's range, over the first segment
        path.flux *= path.ranged->RangeWindow(hit.t);
        path.ranged = nullptr;
    }
    const PhotonEvent event = ScatterPhotonAt<kSpecular, kTextures>(
        *inputs.scene, hit, path.ray, path.flux, path.rng,
        [&](const Vec3& position, const Vec3& direction, const Rgb& flux, bool returned,
            float cosine) {
            if (!path.scattered && !returned) return;
            // With shading normals, the flux per unit of its cosine: hit points weigh it by
            // theirs (GatherDeposits).
            if (!inputs.features.ShadingNormals())
                deposits.push_back({position, direction, flux});
            else if (cosine > 0)
                deposits.push_back({position, direction, flux / cosine});
        });
    if (event == PhotonEvent::kEnded) return false;
    path.scattered = true;
    return ++path.bounces < inputs.max_bounces;
}

// Adds the sorted deposits to the hit points within their radius whose surface faces the
// photon; each counts `counts[i]` photons where kCounted (adaptive tracing), one otherwise.
template <bool kCounted>
void GatherSorted(const PhotonPassInputs& inputs, BatchScratch& scratch) {
    const std::vector<PhotonDeposit>& sorted = scratch.sorted_deposits;
    const auto add = [&](size_t i, uint32_t index, const Rgb& flux, bool inner) {
        if constexpr (kCounted)
            scratch.tally.Add(index, flux, inner, scratch.sorted_counts[i]);
        else
            scratch.tally.Add(index, flux, inner);
    };
    if (!inputs.features.ShadingNormals()) {
        for (size_t i = 0; i < sorted.size(); ++i)
            inputs.grid->ForEachGathering(sorted[i].position, sorted[i].direction,
                                          [&](uint32_t index, bool inner, const Vec3&) {
                                              add(i, index, sorted[i].flux, inner);
                                          });
    } else {  // Veach's arrival factor at each hit point, by its own shading normal
        for (size_t i = 0; i < sorted.size(); ++i)
            inputs.grid->ForEachGathering(sorted[i].position, sorted[i].direction,
                                          [&](uint32_t index, bool inner, const Vec3& normal) {
                                              const float facing =
                                                  -Dot(Normalize(normal), sorted[i].direction);
                                              add(i, index, sorted[i].flux * facing, inner);
                                          });
    }
}

// Adds every deposit to the hit points within their radius whose surface faces the photon.
// Deposits are visited in the order of their grid bucket (ties in path order), so the grid's
// arrays are read front to back instead of at random: a deterministic order, and a much
// faster one once the hit points no longer fit in cache.
void GatherDeposits(const PhotonPassInputs& inputs, BatchScratch& scratch) {
    const std::vector<PhotonDeposit>& deposits = scratch.deposits;
    std::vector<uint64_t>& keys = scratch.sort_keys;
    keys.resize(deposits.size());
    for (size_t i = 0; i < deposits.size(); ++i)
        keys[i] = uint64_t{inputs.grid->BucketOf(deposits[i].position)} << 32 | i;
    // Keys are already in deposit order: a stable sort by bucket alone orders them fully.
    RadixSortBits(keys, scratch.sort_scratch, 32, inputs.grid->BucketBits());
    // Permute in a loop of its own: its loads are independent and overlap, where inside the
    // gather each would stall the loop.
    std::vector<PhotonDeposit>& sorted = scratch.sorted_deposits;
    sorted.resize(deposits.size());
    for (size_t i = 0; i < keys.size(); ++i) sorted[i] = deposits[static_cast<uint32_t>(keys[i])];
    if (scratch.deposit_counts.empty()) {
        GatherSorted<false>(inputs, scratch);
    } else {
        scratch.sorted_counts.resize(keys.size());
        for (size_t i = 0; i < keys.size(); ++i)
            scratch.sorted_counts[i] = scratch.deposit_counts[static_cast<uint32_t>(keys[i])];
        GatherSorted<true>(inputs, scratch);
        scratch.deposit_counts.clear();
    }
    scratch.deposits.clear();
}

// Traces photons [begin, end) of the batch a packet at a time: each lane carries one path,
// and a lane whose path ends takes the next photon, so packets stay full. Every photon's
// random numbers depend on its index alone, and lanes are filled in a fixed order, so the
// deposits (and their order) depend only on the batch. Returns the segments traced.
template <bool kSpecular, bool kTextures>
uint64_t TracePhotons(const PhotonPassInputs& inputs, const BatchSpec& spec, uint32_t begin,
                      uint32_t end, BatchScratch& scratch) {
    constexpr int kLanes = Tracer::kPacketSize;
    PhotonPath paths[kLanes];
    Ray rays[kLanes] = {};
    RayHit hits[kLanes];
    bool active[kLanes], found[kLanes];
    const SeedFamily seeds = PhotonSeeds(inputs.seed, spec.index);
    uint32_t next = begin;
    int live = 0;
    for (int lane = 0; lane < kLanes; ++lane) {
        active[lane] = next < end;
        if (active[lane]) paths[lane] = StartPhoton(inputs, seeds, next++), ++live;
    }
    uint64_t segments = 0;
    while (live > 0) {
        for (int lane = 0; lane < kLanes; ++lane)
            if (active[lane]) rays[lane] = paths[lane].ray;
        inputs.tracer->IntersectPacket(rays, active, hits, found);
        for (int lane = 0; lane < kLanes; ++lane) {
            if (!active[lane]) continue;
            ++segments;
            // A path whose flux is NaN or Inf would poison every sum it reached: it ends here,
            // counted, before it deposits anything.
            const bool finite = IsFinite(paths[lane].flux);
            scratch.nonfinite_discarded += !finite;
            if (finite && found[lane] &&
                ScatterPhoton<kSpecular, kTextures>(inputs, hits[lane], paths[lane],
                                                    scratch.deposits))
                continue;
            if (next < end) {
                paths[lane] = StartPhoton(inputs, seeds, next++);
            } else {
                active[lane] = false;
                --live;
            }
        }
        // Bounded memory however long the paths (albedo near 1): gather in parts, at points
        // fixed by the chunk alone, so the sums stay deterministic.
        if (scratch.deposits.size() >= kMaxPendingDeposits) GatherDeposits(inputs, scratch);
    }
    return segments;
}

// Whether some deposit lands within a hit point's radius, facing it: the photon's visibility.
bool Visible(const HashGrid& grid, std::span<const PhotonDeposit> deposits) {
    for (const PhotonDeposit& deposit : deposits)
        if (grid.Gathers(deposit.position, deposit.direction)) return true;
    return false;
}

// Photons [begin, end) of the batch as steps of Markov chains (core/shared/photon_chain.h), one
// chain a lane: lane c takes steps begin + c, begin + c + kLanes, ...; a step traces the
// step's fresh photon (the one uniform tracing would trace) and, where that is not visible
// and the chain holds a state, a mutation of its state's emission walked with the state's own
// stream, so that its bounces follow the state's and its deposits land near them (with fresh
// walks, a state whose deposits fall within small radii was seldom left: chains stuck, and at
// equal time the error doubled). The state of each step, if any, counts once more. Every number is
// the step's, so the deposits depend only on the batch. Returns the segments traced; counts into
// scratch.
template <bool kSpecular, bool kTextures>
uint64_t TraceAdaptivePhotons(const PhotonPassInputs& inputs, const BatchSpec& spec, uint32_t begin,
                              uint32_t end, BatchScratch& scratch) {
    constexpr int kLanes = Tracer::kPacketSize;
    struct Chain {
        bool started = false;   // holds a visible state
        EmissionNumbers state;  // the state: its emission, and the stream its walk drew from
        Rng tail;
        uint32_t held = 0;  // steps the state has stood for since its deposits were last added
        float size = gpu::kFirstMutationSize;
        uint32_t mutated = 0, accepted = 0;
    };
    struct Lane {
        PhotonPath path;
        uint32_t photon = 0;  // the step
        bool proposal = false;
        EmissionNumbers numbers;  // the path's, and its walk's stream
        Rng tail;
    };
    Chain chains[kLanes];
    Lane lanes[kLanes];
    Ray rays[kLanes] = {};
    RayHit hits[kLanes];
    bool active[kLanes], found[kLanes];
    const SeedFamily fresh_seeds = PhotonSeeds(inputs.seed, spec.index);
    const SeedFamily proposal_seeds = ProposalSeeds(inputs.seed, spec.index);
    for (int lane = 0; lane < kLanes; ++lane) scratch.chain_state[lane].clear();
    // A state's deposits go to the gather once for all the steps it stood for, its flux and
    // photon count times their number (replaying them every step cost four times as much).
    const auto add_state = [&](int lane) {
        Chain& chain = chains[lane];
        if (chain.held == 0) return;
        for (const PhotonDeposit& deposit : scratch.chain_state[lane]) {
            scratch.deposits.push_back(
                {deposit.position, deposit.direction, deposit.flux * float(chain.held)});
            scratch.deposit_counts.push_back(chain.held);
        }
        chain.held = 0;
    };
    // The step's fresh photon on the lane, if the chain has steps left.
    const auto start_step = [&](int lane, uint32_t photon) {
        if (photon >= end) return false;
        Lane& l = lanes[lane];
        Rng rng(fresh_seeds.Seed(photon));
        l.photon = photon;
        l.proposal = false;
        l.numbers = EmissionNumbers::Draw(rng);
        l.tail = rng;
        l.path = StartPhotonFrom(inputs, l.numbers, rng);
        scratch.chain_candidate[lane].clear();
        return true;
    };
    // The path on the lane has ended: the chain moves, or proposes; true while the step goes on.
    const auto path_ended = [&](int lane) {
        Lane& l = lanes[lane];
        Chain& chain = chains[lane];
        std::vector<PhotonDeposit>& candidate = scratch.chain_candidate[lane];
        std::vector<PhotonDeposit>& state = scratch.chain_state[lane];
        const bool visible = Visible(*inputs.grid, candidate);
        if (!l.proposal) scratch.visible_photons += visible;
        if (l.proposal) {
            ++chain.mutated;
            chain.accepted += visible;
            chain.size = gpu::AdaptMutationSize(chain.size, chain.accepted, chain.mutated);
        }
        if (visible) {  // a fresh photon replaces the state (the exchange), a mutation is taken
            add_state(lane);
            chain.started = true;
            chain.state = l.numbers;
            chain.tail = l.tail;
            std::swap(state, candidate);
        } else if (!l.proposal && chain.started) {
            Rng rng(proposal_seeds.Seed(l.photon));
            for (uint32_t k = 0; k < gpu::kEmissionNumbers; ++k)
                l.numbers.u[k] = gpu::MutateNumber(chain.state.u[k], rng.NextFloat(), chain.size);
            l.proposal = true;
            l.tail = chain.tail;
            l.path = StartPhotonFrom(inputs, l.numbers, chain.tail);
            candidate.clear();
            return true;
        }
        if (chain.started) {
            ++chain.held;
            ++scratch.chain_steps;
        }
        return false;
    };
    int live = 0;
    for (int lane = 0; lane < kLanes; ++lane) {
        active[lane] = start_step(lane, begin + lane);
        live += active[lane];
    }
    uint64_t segments = 0;
    while (live > 0) {
        for (int lane = 0; lane < kLanes; ++lane)
            if (active[lane]) rays[lane] = lanes[lane].path.ray;
        inputs.tracer->IntersectPacket(rays, active, hits, found);
        for (int lane = 0; lane < kLanes; ++lane) {
            if (!active[lane]) continue;
            ++segments;
            PhotonPath& path = lanes[lane].path;
            const bool finite = IsFinite(path.flux);
            scratch.nonfinite_discarded += !finite;
            if (finite && found[lane] &&
                ScatterPhoton<kSpecular, kTextures>(inputs, hits[lane], path,
                                                    scratch.chain_candidate[lane]))
                continue;
            if (path_ended(lane)) continue;
            if (!start_step(lane, lanes[lane].photon + kLanes)) {
                add_state(lane);
                active[lane] = false;
                --live;
            }
        }
        if (scratch.deposits.size() >= kMaxPendingDeposits) GatherDeposits(inputs, scratch);
    }
    return segments;
}

}  // namespace

SeedFamily PhotonSeeds(uint64_t seed, uint64_t batch_index) {
    // The stream id separates the random numbers of photons from those of direct light.
    constexpr uint64_t kPhotonStream = 0x70686f746f6e0001ull;
    return SeedFamily(seed, kPhotonStream, batch_index);
}

SeedFamily ProposalSeeds(uint64_t seed, uint64_t batch_index) {
    constexpr uint64_t kProposalStream = 0x70686f746f6e0002ull;
    return SeedFamily(seed, kProposalStream, batch_index);
}

ChunkResult RunPhotonChunk(const PhotonPassInputs& inputs, const BatchSpec& spec, uint32_t chunk,
                           BatchScratch& scratch) {
    PF_CHECK(chunk < ChunkCount(spec));
    const uint32_t begin = chunk * kPhotonsPerChunk;
    const uint32_t end = std::min(spec.photons, begin + kPhotonsPerChunk);
    scratch.tally.Resize(inputs.hit_points.size());
    scratch.deposits.clear();
    scratch.deposit_counts.clear();
    scratch.nonfinite_discarded = 0;
    scratch.visible_photons = scratch.chain_steps = 0;
    ChunkResult result;
    // The photon loop for the scene's features and the tracing, chosen once per chunk.
    const SceneFeatures& features = inputs.features;
    const auto trace =
        inputs.adaptive ? (features.GeneralSurfaces()
                               ? (features.textures ? TraceAdaptivePhotons<true, true>
                                                    : TraceAdaptivePhotons<true, false>)
                               : (features.textures ? TraceAdaptivePhotons<false, true>
                                                    : TraceAdaptivePhotons<false, false>))
        : features.GeneralSurfaces()
            ? (features.textures ? TracePhotons<true, true> : TracePhotons<true, false>)
            : (features.textures ? TracePhotons<false, true> : TracePhotons<false, false>);
    result.segments_traced = trace(inputs, spec, begin, end, scratch);
    result.nonfinite_discarded = scratch.nonfinite_discarded;
    result.visible_photons = scratch.visible_photons;
    result.chain_steps = scratch.chain_steps;
    GatherDeposits(inputs, scratch);
    result.tally = scratch.tally.Extract();
    // The chains' states are drawn from the visible photons alone: their sum, over the steps
    // that had one, estimates the photons' mean over the visible ones, which times V_c (the
    // fresh photons' visible share) is the mean over all photons. The tally sums photons for
    // the chunk's count, so each state counts V_c x photons / steps.
    if (inputs.adaptive && result.chain_steps > 0) {
        const float scale =
            static_cast<float>(double(result.visible_photons) / double(result.chain_steps));
        for (Rgb& flux : result.tally.flux) flux *= scale;
    }
    return result;
}

std::vector<BatchResult> RunPhotonBatches(const PhotonPassInputs& inputs,
                                          std::span<const BatchSpec> specs,
                                          PhotonPassScratch& scratch) {
    std::vector<BatchResult> results(specs.size());
    // Chunks flow through a pipeline: handed out in (batch, chunk) order, run in parallel,
    // and summed into their batch in that same order by one stage at a time. A batch of one
    // chunk keeps its chunk's tally as it is. At most a few chunks per thread are in flight.
    struct Item {
        size_t batch = 0;
        uint32_t chunk = 0;
        ChunkResult result;
    };
    size_t next_batch = 0;
    uint32_t next_chunk = 0;
    const size_t tokens = 2 * static_cast<size_t>(tbb::this_task_arena::max_concurrency());
    tbb::parallel_pipeline(
        tokens,
        tbb::make_filter<void, Item>(tbb::filter_mode::serial_in_order, [&](tbb::flow_control&
                                                                                control) {
            while (next_batch < specs.size() && next_chunk >= ChunkCount(specs[next_batch]))
                ++next_batch, next_chunk = 0;
            if (next_batch == specs.size()) {
                control.stop();
                return Item{};
            }
            return Item{next_batch, next_chunk++, {}};
        }) & tbb::make_filter<Item, Item>(tbb::filter_mode::parallel, [&](Item item) {
            item.result =
                RunPhotonChunk(inputs, specs[item.batch], item.chunk, scratch.threads.local());
            return item;
        }) & tbb::make_filter<Item, void>(tbb::filter_mode::serial_in_order, [&](Item item) {
            BatchResult& result = results[item.batch];
            const uint32_t chunks = ChunkCount(specs[item.batch]);
            result.segments_traced += item.result.segments_traced;
            result.nonfinite_discarded += item.result.nonfinite_discarded;
            if (chunks == 1) {
                result.tally = std::move(item.result.tally);
                return;
            }
            scratch.combined.Resize(inputs.hit_points.size());
            scratch.combined.Add(item.result.tally);
            if (item.chunk + 1 == chunks) result.tally = scratch.combined.Extract();
        }));
    tbb::parallel_for(size_t{0}, specs.size(), [&](size_t i) {
        const BatchSpec& spec = specs[i];
        BatchResult& result = results[i];
        result.spec = spec;
        result.photons_emitted = spec.photons;
        result.samples.resize(spec.sample_end - spec.sample_begin);
        result.nonfinite_discarded += SampleDirectLight(
            *inputs.emitters, *inputs.tracer, inputs.scene->materials, inputs.DirectPoints(),
            spec.sample_begin, inputs.seed, spec.epoch,
            inputs.direct_sequence ? &*inputs.direct_sequence : nullptr, result.samples);
    });
    return results;
}

double VisiblePhotonShare(const PhotonPassInputs& inputs, uint32_t photons) {
    PhotonPassInputs adaptive = inputs;
    adaptive.adaptive = true;
    BatchSpec spec;
    spec.index = ~uint64_t{0};  // no batch of a job has it
    spec.photons = photons;
    BatchScratch scratch;
    uint64_t visible = 0;
    for (uint32_t chunk = 0; chunk < ChunkCount(spec); ++chunk)
        visible += RunPhotonChunk(adaptive, spec, chunk, scratch).visible_photons;
    return photons == 0 ? 0.0 : double(visible) / photons;
}

}  // namespace pf
