// What every photonfarm kernel starts from: the shared structs, generator and sampling maths,
// the scene's feature switches (specialisation constants), the push constants and the
// descriptor set.
#extension GL_EXT_shader_explicit_arithmetic_types : require
#extension GL_EXT_shader_atomic_int64 : require

#include "core/shared/gpu_types.h"
#include "core/shared/rng.h"
#include "core/shared/path_sampling.h"
#include "core/shared/alpha.h"
#include "core/shared/texture_wrap.h"
#include "core/shared/shading_normal.h"
#include "core/shared/translucent.h"
#include "core/shared/photon_chain.h"
#include "core/shared/surface_edges.h"
#include "core/shared/photon_kinds.h"
#include "core/shared/curve.h"

#include "core/shared/features.h"
#include "core/shared/frame.h"

layout(push_constant, std430) uniform Push { GpuParams params; };

layout(std430, binding = kBindingBvhNodes) readonly buffer BvhNodes { GpuBvhNode bvh_nodes[]; };
layout(std430, binding = kBindingTriangles) readonly buffer Triangles { GpuTriangle triangles[]; };
layout(std430, binding = kBindingShading) readonly buffer Shading { GpuTriangleShading shading[]; };
layout(std430, binding = kBindingNormals) readonly buffer Normals { vec4 vertex_normals[]; };
layout(std430, binding = kBindingUvs) readonly buffer Uvs { vec2 vertex_uvs[]; };
layout(std430, binding = kBindingTangents) readonly buffer Tangents { vec4 vertex_tangents[]; };
layout(std430, binding = kBindingMaterials) readonly buffer Materials { GpuMaterial materials[]; };
layout(std430, binding = kBindingTextures) readonly buffer Textures { GpuTexture textures[]; };
layout(std430, binding = kBindingTexels) readonly buffer Texels { vec4 texels[]; };
layout(std430, binding = kBindingEmitters) readonly buffer Emitters { GpuEmitter emitters[]; };
layout(std430, binding = kBindingEmitterCdf) readonly buffer EmitterCdf { float emitter_cdf[]; };
layout(std430, binding = kBindingHitPoints) readonly buffer HitPoints { GpuHitPoint hit_points[]; };
layout(std430, binding = kBindingDirectPoints) readonly buffer DirectPoints { GpuHitPoint direct_points[]; };
layout(std430, binding = kBindingRadiusSq) readonly buffer RadiusSq { float radius_sq[]; };
layout(std430, binding = kBindingSurfaceEdges) readonly buffer SurfaceEdges { uint64_t surface_edges[]; };
layout(std430, binding = kBindingGridBegin) buffer GridBegin { uint grid_begin[]; };
layout(std430, binding = kBindingGridCursor) buffer GridCursor { uint grid_cursor[]; };
layout(std430, binding = kBindingGridEntries) buffer GridEntries { GpuGridEntry grid_entries[]; };
layout(std430, binding = kBindingScanBlocks) buffer ScanBlocks { uint scan_blocks[]; };
layout(std430, binding = kBindingTally) buffer Tally { GpuTallySum tally[]; };
layout(std430, binding = kBindingDirect) writeonly buffer Direct { vec4 direct[]; };
layout(std430, binding = kBindingCounters) buffer Counters { GpuCounters counters; };
layout(std430, binding = kBindingTallyOffsets) buffer TallyOffsets { uint tally_offsets[]; };
layout(std430, binding = kBindingTallyEntries) writeonly buffer TallyEntries { GpuTallyEntry tally_entries[]; };
layout(std430, binding = kBindingSheenTables) readonly buffer SheenTables { float sheen_tables[]; };
layout(std430, binding = kBindingPixelJob) readonly buffer PixelJob { GpuPixelJob pixel_job; };

const float kPi = 3.14159265358979323846;
const float kInfinity = 1.0 / 0.0;

bool IsFinite(vec3 v) { return !any(isnan(v)) && !any(isinf(v)); }
float MaxComponent(vec3 v) { return max(v.x, max(v.y, v.z)); }
