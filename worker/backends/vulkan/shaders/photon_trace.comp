#version 460
// The photon pass (core/ppm/photon_pass.cpp on the CPU): one thread a photon path, from a
// light through specular and diffuse bounces (and through coats, as core/ppm/photon_walk.h)
// with Russian roulette; at every diffuse hit after the first scattering (and at the first too
// where hit points gather kinds of photon of their own: kPhotonKinds, rpm's) the photon is
// gathered at once by the hit points whose sphere holds it and that gather its kind, into
// integer sums (GpuTallySum) that do not depend on thread order. Adaptive tracing (params.chain_steps > 0): one thread a Markov chain
// (core/shared/photon_chain.h) whose steps test photons for visibility without gathering, then
// trace the chain's state again, gathering.
#include "common.glsl"
#include "trace.glsl"
#include "lights.glsl"
#include "bsdf.glsl"
#include "grid.glsl"

layout(local_size_x = kWorkgroupSize) in;

shared uint group_segments;
shared uint group_discarded;
shared uint group_visible;
shared uint group_steps;

// Fixed-point flux of one deposit: the clamp keeps every addend below 2^31 units, so a sum
// of the at most 2^32 - 1 photons a tally counts stays below 2^63.
uint64_t ToFixed(float flux) { return uint64_t(min(flux * params.flux_to_fixed + 0.5, 2147483648.0)); }

// Whether the hit point of grid entry `entry` takes a photon of `kind` (photon_kinds.h) at p
// arriving along `direction` onto a surface of normal `landed` (toward the side it arrived
// from), as HashGrid::Takes: its sphere holds p, its surface faces the photon, it gathers that
// kind, and its gather region holds it (WithinSurfaceEdges).
bool Takes(GpuGridEntry entry, vec3 p, vec3 direction, vec3 landed, uint kind) {
    const vec3 offset = p - entry.position.xyz;
    if (dot(offset, offset) > entry.position.w || !(dot(entry.normal.xyz, direction) < 0.0))
        return false;
    const uint index = floatBitsToUint(entry.normal.w);
    if (kPhotonKinds && (floatBitsToUint(hit_points[index].weight.w) & kind) == 0u) return false;
    return WithinSurfaceEdges(surface_edges[index], entry.normal.xyz, landed, offset, entry.position.w);
}

// Adds a deposit to the hit points that take it (Takes). `flux` is per unit of its cosine
// where some shading normal differs from its surface's (kShadingNormals): each hit point then
// weighs it by its own (Veach's arrival factor, as GatherDeposits on the CPU).
void Gather(vec3 p, vec3 direction, vec3 landed, vec3 flux, uint kind) {
    const ivec3 cell = GridCell(p);
    // The neighbour on the nearer side in each axis: cells are two radii wide.
    const vec3 within = p * params.grid_inverse_cell - vec3(cell);
    const ivec3 step = mix(ivec3(-1), ivec3(1), greaterThanEqual(within, vec3(0.5)));
    const uint64_t fixed_r = ToFixed(flux.r), fixed_g = ToFixed(flux.g), fixed_b = ToFixed(flux.b);
    uint visited[8];
    for (uint corner = 0; corner < 8; ++corner) {
        const ivec3 offset = ivec3(corner & 1, (corner >> 1) & 1, corner >> 2) * step;
        const uint bucket = GridBucket(cell + offset);
        // Distinct cells may share a bucket: each bucket is searched once.
        bool seen = false;
        for (uint k = 0; k < corner; ++k) seen = seen || visited[k] == bucket;
        visited[corner] = bucket;
        if (seen) continue;
        const uint end = grid_begin[bucket + 1];
        for (uint e = grid_begin[bucket]; e < end; ++e) {
            const GpuGridEntry entry = grid_entries[e];
            if (!Takes(entry, p, direction, landed, kind)) continue;
            const vec3 offset_to = entry.position.xyz - p;
            const float distance_sq = dot(offset_to, offset_to);
            const float facing = -dot(entry.normal.xyz, direction);
            const uint index = floatBitsToUint(entry.normal.w);
            atomicAdd(tally[index].photons, 1u);
            if (2.0 * distance_sq <= entry.position.w) atomicAdd(tally[index].inner_photons, 1u);
            if (kShadingNormals) {
                atomicAdd(tally[index].flux[0], ToFixed(flux.r * facing));
                atomicAdd(tally[index].flux[1], ToFixed(flux.g * facing));
                atomicAdd(tally[index].flux[2], ToFixed(flux.b * facing));
            } else {
                atomicAdd(tally[index].flux[0], fixed_r);
                atomicAdd(tally[index].flux[1], fixed_g);
                atomicAdd(tally[index].flux[2], fixed_b);
            }
        }
    }
}

// Whether some hit point takes a photon of `kind` at p arriving along `direction` onto a surface
// of normal `landed` (Takes).
bool Reaches(vec3 p, vec3 direction, vec3 landed, uint kind) {
    const ivec3 cell = GridCell(p);
    const vec3 within = p * params.grid_inverse_cell - vec3(cell);
    const ivec3 step = mix(ivec3(-1), ivec3(1), greaterThanEqual(within, vec3(0.5)));
    for (uint corner = 0; corner < 8; ++corner) {
        const uint bucket = GridBucket(cell + ivec3(corner & 1, (corner >> 1) & 1, corner >> 2) * step);
        const uint end = grid_begin[bucket + 1];
        for (uint e = grid_begin[bucket]; e < end; ++e) {
            if (Takes(grid_entries[e], p, direction, landed, kind)) return true;
        }
    }
    return false;
}

// Follows the photon emitted by `u` whose walk draws from `rng`; returns the rays traced.
// Gathering (`gather`), its deposits go to the hit points; otherwise the walk stops at the first
// one a hit point holds, setting `visible`. Sets `discarded` where its flux turned NaN or Inf (the
// path ends there, before depositing).
uint TracePath(const float u[kEmissionNumbers], Pcg32 rng, bool gather, out bool visible, out bool discarded) {
    discarded = false;
    visible = false;
    const Photon emitted = EmitPhotonFrom(u);
    vec3 origin = emitted.origin, direction = emitted.direction, flux = emitted.flux;
    bool scattered = false;
    bool diffused = false;  // it has left a diffuse surface: no longer a caustic
    uint segments = 0;
    for (uint bounce = 0; bounce < params.max_bounces; ++bounce) {
        ++segments;
        if (!IsFinite(flux)) {
            discarded = true;
            break;
        }
        RayHit hit;
        if (!TraceRay(origin, direction, kInfinity, false, hit)) break;
        if (bounce == 0) flux *= RangeWindow(hit.t, emitted.range);  // the light's range
        const Surface surface = SurfaceAt(hit);
        const GpuMaterial material = ShadingMaterial(surface);
        const Bsdf bsdf = BsdfOf(material);
        const bool front_facing = dot(direction, surface.geometric_normal) < 0;
        // Out of an absorbing glass's inside.
        if (kHasAbsorption)
            flux *= SegmentTransmittance(material.absorption.xyz, material.outside_absorption.xyz, front_facing, hit.t);
        // Veach's adjoint for shading normals, as ScatterPhotonAt: arriving here (after landing),
        // and leaving.
        const bool shaded = kShadingNormals && surface.shading_normal != surface.geometric_normal;
        const float arrival = shaded ? ShadingArrival(direction, surface.shading_normal, surface.geometric_normal) : 1.0;
        // What lands: per unit of its cosine, with shading normals (Gather).
        const float across = kShadingNormals ? abs(dot(direction, surface.geometric_normal)) : 1.0;
        SpecularBounce scatter = SpecularBounce(direction, vec3(0.0), false);  // absorbed
        if (material.type == kMaterialDiffuse) {
            const vec3 normal = front_facing ? surface.shading_normal : -surface.shading_normal;
            const Frame frame = FrameFromNormal(normal);
            const bool coated = IsCoated(bsdf);
            // The coat reflects the photon or lets it in.
            const CoatArrival at_coat = ArriveAtCoat(bsdf, direction, surface.shading_normal, front_facing, rng);
            if (at_coat.at_base) flux *= at_coat.weight;
            else scatter = at_coat.reflected;
            if (at_coat.at_base) {
                // The surface it landed on, toward the side it arrived from (HashGrid::Takes).
                const vec3 landed = front_facing ? surface.geometric_normal : -surface.geometric_normal;
                const uint kind = PhotonKind(scattered, diffused, false);
                if ((scattered || kPhotonKinds) && across > 0.0) {
                    if (gather) Gather(surface.position, direction, landed, flux / across, kind);
                    else if (Reaches(surface.position, direction, landed, kind)) {
                        visible = true;
                        break;
                    }
                }
                if (!(arrival > 0.0)) break;  // from below the shading normal
                flux *= arrival;
                // Back to its side or, through a translucent surface, on to the other.
                const DiffuseSide side = ChooseDiffuseSide(bsdf, surface.base_color, rng);
                const vec3 albedo = side.albedo;
                const bool through = side.through;
                const bool toward = front_facing != through;
                bool escaped = false;
                for (int returns = 0;; ++returns) {
                    // Russian roulette by albedo (Jensen 2001, 2.3.3).
                    const float survive = min(1.0, MaxComponent(albedo));
                    if (!(Pcg32NextFloat(rng) < survive)) break;
                    flux *= albedo / survive;
                    const float u1 = Pcg32NextFloat(rng), u2 = Pcg32NextFloat(rng);
                    const vec3 local = SampleCosineHemisphere(u1, u2);
                    if (!coated) {
                        // By the surface's own cosine, as ScatterPhotonAt: Lambertian reflection
                        // (and transmission) is the same toward every direction on its side.
                        direction = ToWorld(shaded || through ? FrameFromNormal(toward ? surface.geometric_normal
                                                                                        : -surface.geometric_normal)
                                                               : frame,
                                            local);
                        escaped = true;
                        break;
                    }
                    // Out through the coat, or back down to the base.
                    const CoatLeaving leaving = LeaveCoatAt(bsdf.coat, frame, local, rng);
                    flux *= leaving.weight;
                    direction = leaving.direction;
                    if (leaving.escaped) {
                        escaped = true;
                        break;
                    }
                    if (MaxComponent(flux) <= 0.0 || returns + 1 >= int(bsdf.coat.depth)) break;
                    const float inside = kShadingNormals ? abs(dot(direction, normal)) : 1.0;
                    if (inside > 0.0) {
                        if (gather) Gather(surface.position, direction, normal, flux / inside, kDiffusePhoton);
                        else if (Reaches(surface.position, direction, normal, kDiffusePhoton)) {
                            visible = true;
                            break;
                        }
                    }
                }
                if (visible) break;
                if (!escaped) break;
                const vec3 geometric = toward ? surface.geometric_normal : -surface.geometric_normal;
                if (!(dot(direction, geometric) > 0)) break;  // the shading normal pointed it inside
                if (shaded && coated) flux *= ShadingDeparture(direction, surface.shading_normal, surface.geometric_normal);
                origin = OffsetRayOrigin(surface.position, geometric);
                scattered = true;
                diffused = true;
                continue;
            }
        } else if (kHasMirror || kHasDielectric || kHasThinDielectric || kHasRoughConductor || kHasRoughDielectric) {
            scatter = ScatterNonDiffuse(bsdf, direction, surface.shading_normal, front_facing, surface.base_color, rng,
                                        kCarriesFlux);
        }
        const float survive = min(1.0, MaxComponent(scatter.weight));
        if (!(Pcg32NextFloat(rng) < survive) || !(arrival > 0.0)) break;
        flux *= scatter.weight * (arrival / survive);
        if (shaded) flux *= ShadingDeparture(scatter.direction, surface.shading_normal, surface.geometric_normal);
        const vec3 side = front_facing == scatter.transmitted ? -surface.geometric_normal : surface.geometric_normal;
        origin = OffsetRayOrigin(surface.position, side);
        direction = scatter.direction;
        scattered = true;
    }
    return segments;
}

// Photon `photon` of the batch, traced and gathered (uniform tracing).
uint TracePhoton(uint photon, out bool discarded) {
    Pcg32 rng = Pcg32Seeded(FamilySeed(params.seed_prefix, photon));
    const float u[kEmissionNumbers] = DrawEmissionNumbers(rng);
    bool visible;
    return TracePath(u, rng, true, visible, discarded);
}

// Chain `chain` of the batch's params.end / params.chain_steps (rounded up), over photons chain,
// chain + chains, ...: each step tests the step's fresh photon (the one uniform tracing traces)
// and, where it is not visible and the chain holds a state, a mutation of the state's emission
// walked with the state's stream; then traces the state, gathering. As TraceAdaptivePhotons on
// the CPU, whose chains are fewer and longer (kChainSteps here): the same estimate, not the same
// photons.
uint RunChain(uint chain, out uint discarded, out uint visible_photons, out uint steps) {
    const uint chains = (params.end + params.chain_steps - 1) / params.chain_steps;
    bool started = false;  // the state is read only once it has started
    float state[kEmissionNumbers];
    for (uint k = 0; k < kEmissionNumbers; ++k) state[k] = 0.0;
    Pcg32 state_rng = Pcg32Seeded(0ul);
    float size = kFirstMutationSize;
    uint mutated = 0, accepted = 0, segments = 0;
    discarded = 0, visible_photons = 0, steps = 0;
    for (uint photon = chain; photon < params.end; photon += chains) {
        Pcg32 rng = Pcg32Seeded(FamilySeed(params.seed_prefix, photon));
        const float u[kEmissionNumbers] = DrawEmissionNumbers(rng);
        bool visible, lost;
        segments += TracePath(u, rng, false, visible, lost);
        discarded += uint(lost);
        if (visible) {  // the exchange: the chain moves to the fresh photon
            ++visible_photons;
            started = true;
            state = u;
            state_rng = rng;
        } else if (started) {
            Pcg32 proposal = Pcg32Seeded(FamilySeed(params.proposal_prefix, photon));
            float v[kEmissionNumbers];
            for (uint k = 0; k < kEmissionNumbers; ++k)
                v[k] = MutateNumber(state[k], Pcg32NextFloat(proposal), size);
            segments += TracePath(v, state_rng, false, visible, lost);
            discarded += uint(lost);
            ++mutated;
            if (visible) {
                ++accepted;
                state = v;
            }
            size = AdaptMutationSize(size, accepted, mutated);
        }
        if (started) {
            ++steps;
            segments += TracePath(state, state_rng, true, visible, lost);
        }
    }
    return segments;
}

void main() {
    if (gl_LocalInvocationIndex == 0) group_segments = 0, group_discarded = 0, group_visible = 0, group_steps = 0;
    barrier();
    const uint index = params.first + gl_GlobalInvocationID.x;
    if (params.chain_steps == 0 && index < params.end) {
        bool discarded;
        atomicAdd(group_segments, TracePhoton(index, discarded));
        if (discarded) atomicAdd(group_discarded, 1u);
    } else if (params.chain_steps > 0 && index < (params.end + params.chain_steps - 1) / params.chain_steps) {
        uint discarded, visible, steps;
        atomicAdd(group_segments, RunChain(index, discarded, visible, steps));
        atomicAdd(group_discarded, discarded);
        atomicAdd(group_visible, visible);
        atomicAdd(group_steps, steps);
    }
    barrier();
    if (gl_LocalInvocationIndex == 0) {
        atomicAdd(counters.segments, uint64_t(group_segments));
        atomicAdd(counters.nonfinite_discarded, uint64_t(group_discarded));
        atomicAdd(counters.visible_photons, uint64_t(group_visible));
        atomicAdd(counters.chain_steps, uint64_t(group_steps));
    }
}
