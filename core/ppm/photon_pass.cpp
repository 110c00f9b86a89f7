// Photon tracing with Russian roulette and the gather into the hit-point grid
// (Hachisuka et al. 2008, section 4.2; Jensen 2001 for the photon random walk).
#include "core/ppm/photon_pass.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <algorithm>

#include "core/ppm/direct_light.h"
#include "core/ppm/photon_trace.h"
#include "core/sampling/frame.h"
#include "core/sampling/rng.h"
#include "core/sampling/sampling.h"
#include "core/util/check.h"
#include "core/util/radix_sort.h"

namespace pf {
namespace photon_trace {
namespace {

// Adds the sorted deposits to the hit points within their radius whose surface faces the
// photon, each as one photon; or, kCounted (adaptive tracing), as sorted_counts[i] photons.
// The uniform loop reads no counts.
template <bool kCounted>
void GatherSorted(const PhotonPassInputs& inputs, BatchScratch& scratch) {
    const std::vector<PhotonDeposit>& sorted = scratch.sorted_deposits;
    const uint32_t* counts = scratch.sorted_counts.data();
    if (!inputs.features.ShadingNormals()) {
        for (const PhotonDeposit& deposit : sorted) {
            const uint32_t count = kCounted ? *counts++ : 1;
            inputs.grid->ForEachGathering(
                deposit.position, deposit.direction, deposit.normal, deposit.kind,
                [&](uint32_t index, bool inner, const Vec3&) {
                    if constexpr (kCounted)
                        scratch.tally.Add(index, deposit.flux, inner, count);
                    else
                        scratch.tally.Add(index, deposit.flux, inner);
                });
        }
    } else {  // Veach's arrival factor at each hit point, by its own shading normal
        for (const PhotonDeposit& deposit : sorted) {
            const uint32_t count = kCounted ? *counts++ : 1;
            inputs.grid->ForEachGathering(
                deposit.position, deposit.direction, deposit.normal, deposit.kind,
                [&](uint32_t index, bool inner, const Vec3& normal) {
                    const float facing = -Dot(Normalize(normal), deposit.direction);
                    if constexpr (kCounted)
                        scratch.tally.Add(index, deposit.flux * facing, inner, count);
                    else
                        scratch.tally.Add(index, deposit.flux * facing, inner);
                });
        }
    }
}

}  // namespace

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

}  // namespace photon_trace

namespace {

using photon_trace::GatherDeposits;
using photon_trace::PhotonPath;
using photon_trace::ScatterPhoton;
using photon_trace::StartPhoton;

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

}  // namespace

SeedFamily PhotonSeeds(uint64_t seed, uint64_t batch_index) {
    // The stream id separates the random numbers of photons from those of direct light.
    constexpr uint64_t kPhotonStream = 0x70686f746f6e0001ull;
    return SeedFamily(seed, kPhotonStream, batch_index);
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
        inputs.adaptive ? photon_trace::TraceAdaptive
        : features.GeneralSurfaces()
            ? (features.VaryingBaseColor() ? TracePhotons<true, true> : TracePhotons<true, false>)
            : (features.VaryingBaseColor() ? TracePhotons<false, true>
                                           : TracePhotons<false, false>);
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
            inputs.direct_sequence ? &*inputs.direct_sequence : nullptr, result.samples,
            inputs.direct_points.empty() ? 0 : inputs.direct_offset);
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
