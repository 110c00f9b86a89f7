#version 460
// The path tracer as a wavefront, the design of pbrt-v4's GPU integrator: paths wait in a
// buffer between stages and each stage is a kernel over a queue of them. One stage finds the
// closest hits of the queued rays and sorts the vertices into a queue per class of material
// (kVertex*); a shading pipeline per class, compiled for that class alone, runs the vertex
// (path_vertex.glsl, the megakernel's own) and queues the paths that go on. A path a pixel of
// the batch, its samples one after another from the pixel's stream, as pixel_trace.comp and the
// CPU draw them: the two designs' images agree to rounding. Light samples' shadow rays are
// traced where the vertex is shaded (a coat's walk draws numbers only where its light is
// visible, so they cannot wait for a stage of their own without changing the numbers).
// The host records the stages round after round, the workgroup counts of each from the queue
// lengths the stage before wrote (indirect dispatches), until no path is left.
#include "common.glsl"
#include "trace.glsl"
#include "lights.glsl"
#include "bsdf.glsl"
#include "direct.glsl"
#include "path_vertex.glsl"

layout(local_size_x = kWorkgroupSize) in;

layout(constant_id = kSpecWavefrontStage) const uint kStage = kStageStart;

layout(std430, binding = kBindingCameraRays) readonly buffer CameraRays { GpuCameraRay camera_rays[]; };
layout(std430, binding = kBindingPathStates) buffer PathStates { GpuPathState paths[]; };
layout(std430, binding = kBindingPathQueues) buffer PathQueues { uint path_queues[]; };
layout(std430, binding = kBindingPathCounters) buffer PathCounters { uint path_counters[]; };

uint BatchPixels() { return params.end; }
uint NextRays() { return 1 - params.path_queue; }

void Enqueue(uint queue, uint counter, uint slot) {
    path_queues[queue * BatchPixels() + atomicAdd(path_counters[counter], 1)] = slot;
}

PathState LoadPath(uint slot) {
    const GpuPathState s = paths[slot];
    return PathState(s.origin.xyz, s.direction.xyz, s.radiance.xyz, s.throughput.xyz,
                     (s.flags & kPathSpecularBounce) != 0, (s.flags & kPathCoatExit) != 0, s.bsdf_pdf,
                     s.bounced_at.xyz, s.depth, s.throughput.w);
}

void StorePath(uint slot, PathState path, Pcg32 rng) {
    paths[slot].origin.xyz = path.origin;
    paths[slot].direction.xyz = path.direction;
    paths[slot].radiance.xyz = path.radiance;
    paths[slot].throughput = vec4(path.throughput, path.refraction);
    paths[slot].bounced_at.xyz = path.bounced_at;
    paths[slot].bsdf_pdf = path.bsdf_pdf;
    paths[slot].flags = (path.specular_bounce ? kPathSpecularBounce : 0) | (path.coat_exit ? kPathCoatExit : 0);
    paths[slot].depth = path.depth;
    paths[slot].rng_state = rng.state;
    paths[slot].rng_increment = rng.increment;
}

Pcg32 LoadRng(uint slot) { return Pcg32(paths[slot].rng_state, paths[slot].rng_increment); }

// Starts the pixel's sample `index` on its camera ray and queues it.
void StartSample(uint slot, uint index, Pcg32 rng) {
    const GpuCameraRay ray = camera_rays[slot * pixel_job.samples_per_pixel + index];
    paths[slot].traced_sample = index;
    StorePath(slot, BeginPath(ray.origin.xyz, ray.direction.xyz), rng);
    Enqueue(NextRays(), kPathCountRays + NextRays(), slot);
}

// The pixel's sample has ended with `radiance`: it is summed in (times its filter weight, or
// counted out where it is NaN or Inf) and the next sample started, or the pixel's mean written
// after the last, as pixel_trace.comp writes it.
void FinishSample(uint slot, vec3 radiance, Pcg32 rng) {
    const uint spp = pixel_job.samples_per_pixel, index = paths[slot].traced_sample;
    const vec3 value = radiance * camera_rays[slot * spp + index].origin.w;
    vec3 sum = paths[slot].sum.xyz;
    uint discarded = paths[slot].discarded;
    if (IsFinite(value)) sum += value;
    else ++discarded;
    paths[slot].sum.xyz = sum;
    paths[slot].discarded = discarded;
    if (index + 1 < spp) StartSample(slot, index + 1, rng);
    else direct[slot] = vec4(sum * (1.0 / float(spp)), float(discarded));
}

// The material a hit's vertex shades with: only a mix's choice needs the surface.
uint HitMaterial(RayHit hit) {
    if (kHasMixes) return SurfaceAt(hit).material;
    return SlotMaterial(hit.triangle);
}

void WriteGroups(uint at, uint threads) {
    path_counters[at] = min((threads + kWorkgroupSize - 1) / kWorkgroupSize, kPathMaxGroups);
    path_counters[at + 1] = 1;
    path_counters[at + 2] = 1;
}

void main() {
    const uint thread = gl_GlobalInvocationID.x, threads = gl_NumWorkGroups.x * kWorkgroupSize;
    if (kStage == kStageStart) {
        // A thread a pixel (params.first on); the host has set the first ray queue's length.
        const uint slot = params.first + thread;
        if (slot >= BatchPixels()) return;
        const GpuCameraRay ray = camera_rays[slot * pixel_job.samples_per_pixel];
        paths[slot].sum = vec4(0);
        paths[slot].discarded = 0;
        paths[slot].traced_sample = 0;
        StorePath(slot, BeginPath(ray.origin.xyz, ray.direction.xyz),
                  Pcg32Seeded(FamilySeed(params.seed_prefix, uint64_t(params.direct_begin + slot))));
        path_queues[params.path_queue * BatchPixels() + slot] = slot;
    } else if (kStage == kStageExtendArgs) {
        if (thread != 0) return;
        WriteGroups(kPathExtendArgs, path_counters[kPathCountRays + params.path_queue]);
        path_counters[kPathCountRays + NextRays()] = 0;
        for (uint c = 0; c < kVertexClasses; ++c) path_counters[kPathCountVertices + c] = 0;
    } else if (kStage == kStageExtend) {
        const uint queued = path_counters[kPathCountRays + params.path_queue];
        for (uint i = thread; i < queued; i += threads) {
            const uint slot = path_queues[params.path_queue * BatchPixels() + i];
            RayHit hit;
            if (TraceRay(paths[slot].origin.xyz, paths[slot].direction.xyz, kInfinity, false, hit)) {
                paths[slot].hit = vec4(hit.t, uintBitsToFloat(hit.triangle), hit.b1, hit.b2);
                const uint c = VertexClass(BsdfOf(materials[HitMaterial(hit)]));
                Enqueue(2 + c, kPathCountVertices + c, slot);
            } else {
                PathState path = LoadPath(slot);
                Pcg32 rng = LoadRng(slot);
                PathVertex(path, false, hit, rng);  // the environment, where the scene has one
                FinishSample(slot, path.radiance, rng);
            }
        }
    } else if (kStage == kStageShadeArgs) {
        if (thread != 0) return;
        for (uint c = 0; c < kVertexClasses; ++c)
            WriteGroups(kPathShadeArgs + 4 * c, path_counters[kPathCountVertices + c]);
    } else {  // kStageShade, the vertices of class kVertexClass
        const uint queued = path_counters[kPathCountVertices + kVertexClass];
        for (uint i = thread; i < queued; i += threads) {
            const uint slot = path_queues[(2 + kVertexClass) * BatchPixels() + i];
            const vec4 stored = paths[slot].hit;
            const RayHit hit = RayHit(stored.x, floatBitsToUint(stored.y), stored.z, stored.w,
                                      paths[slot].direction.xyz);
            PathState path = LoadPath(slot);
            Pcg32 rng = LoadRng(slot);
            if (PathVertex(path, true, hit, rng)) {
                StorePath(slot, path, rng);
                Enqueue(NextRays(), kPathCountRays + NextRays(), slot);
            } else {
                FinishSample(slot, path.radiance, rng);
            }
        }
    }
}
