// Adaptive photon tracing's loop on the CPU (Hachisuka & Jensen 2011; core/shared/photon_chain.h).
#include <span>
#include <utility>
#include <vector>

#include "core/ppm/photon_trace.h"
#include "core/shared/photon_chain.h"

namespace pf {
namespace photon_trace {
namespace {

// Whether some deposit lands within a hit point's radius, facing it: the photon's visibility.
bool Visible(const HashGrid& grid, std::span<const PhotonDeposit> deposits) {
    for (const PhotonDeposit& deposit : deposits)
        if (grid.Gathers(deposit.position, deposit.direction, deposit.normal, deposit.kind))
            return true;
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
            scratch.deposits.push_back({deposit.position, deposit.direction,
                                        deposit.flux * float(chain.held), deposit.normal,
                                        deposit.kind});
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

uint64_t TraceAdaptive(const PhotonPassInputs& inputs, const BatchSpec& spec, uint32_t begin,
                       uint32_t end, BatchScratch& scratch) {
    const SceneFeatures& features = inputs.features;
    const auto trace = features.GeneralSurfaces()
                           ? (features.VaryingBaseColor() ? TraceAdaptivePhotons<true, true>
                                                          : TraceAdaptivePhotons<true, false>)
                           : (features.VaryingBaseColor() ? TraceAdaptivePhotons<false, true>
                                                          : TraceAdaptivePhotons<false, false>);
    return trace(inputs, spec, begin, end, scratch);
}

}  // namespace photon_trace

SeedFamily ProposalSeeds(uint64_t seed, uint64_t batch_index) {
    constexpr uint64_t kProposalStream = 0x70686f746f6e0002ull;
    return SeedFamily(seed, kProposalStream, batch_index);
}

}  // namespace pf
