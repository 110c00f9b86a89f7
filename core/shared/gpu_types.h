// Every structure the Vulkan photon backend shares between C++ and its shaders, with the
// descriptor bindings and specialisation constant ids: their only definition
// (worker/backends/vulkan/ fills them, worker/backends/vulkan/shaders/ reads them).
// Only vec2/vec4/uvec4 and 32/64-bit scalars, so std430 and C++ agree; sizes are asserted.
#ifndef PF_CORE_SHARED_GPU_TYPES_H
#define PF_CORE_SHARED_GPU_TYPES_H

#include "core/shared/gpu_prelude.h"

PF_GPU_BEGIN

// The BVH's depth limit (embree/bvh_builder.cpp builds no leaf deeper) and the shaders'
// traversal stack (trace.glsl), which must hold a pointer for every level: one definition
// ties them.
PF_CONST(uint32_t) kMaxBvhDepth = 60;
PF_CONST(uint32_t) kBvhStackSize = kMaxBvhDepth + 4;

// Descriptor set 0, one layout for every pipeline.
PF_CONST(uint32_t) kBindingBvhNodes = 0;   // GpuBvhNode[]
PF_CONST(uint32_t) kBindingTriangles = 1;  // GpuTriangle[], in BVH leaf order
PF_CONST(uint32_t) kBindingShading = 2;    // GpuTriangleShading[], in scene order
PF_CONST(uint32_t) kBindingNormals = 3;    // vec4[], per vertex
PF_CONST(uint32_t) kBindingUvs = 4;        // vec2[], per vertex
PF_CONST(uint32_t) kBindingMaterials = 5;  // GpuMaterial[]
PF_CONST(uint32_t) kBindingTextures = 6;   // GpuTexture[]
// vec4[]: every texture's texels, and procedural textures' programs (procedural_texture.h),
// after the noise permutation (noise.h) in scenes with procedural textures.
PF_CONST(uint32_t) kBindingTexels = 7;
PF_CONST(uint32_t) kBindingEmitters = 8;      // GpuEmitter[]
PF_CONST(uint32_t) kBindingEmitterCdf = 9;    // float[]: cdf[i] = P(emitter <= i)
PF_CONST(uint32_t) kBindingHitPoints = 10;    // GpuHitPoint[]
PF_CONST(uint32_t) kBindingRadiusSq = 11;     // float[], per hit point, this epoch
PF_CONST(uint32_t) kBindingGridBegin = 12;    // uint[buckets + 1]: counts, then CSR offsets
PF_CONST(uint32_t) kBindingGridCursor = 13;   // uint[buckets]: next free slot while filling
PF_CONST(uint32_t) kBindingGridEntries = 14;  // GpuGridEntry[]
PF_CONST(uint32_t) kBindingScanBlocks = 15;   // uint[]: per-block sums of the prefix scan
PF_CONST(uint32_t) kBindingTally = 16;        // GpuTallySum[], per hit point
PF_CONST(uint32_t)
kBindingDirect = 17;  // vec4[], a batch's direct-light samples, or camera samples' radiance
PF_CONST(uint32_t) kBindingCounters = 18;      // GpuCounters
PF_CONST(uint32_t) kBindingTallyOffsets = 19;  // uint[hit points + 1]: flags, then offsets
PF_CONST(uint32_t) kBindingTallyEntries = 20;  // GpuTallyEntry[]: the sparse tally, host-visible
// The images of the lights that have one (the environment, goniometric and projection
// lights), one after another, each from its emitter's first texel (GpuEmitter::texture.x).
PF_CONST(uint32_t) kBindingLightImageTexels = 21;  // vec4[]
// float[]: those lights' sampling tables, one light's after another's, each from its emitter's
// first entry (GpuEmitter::texture.y). An environment or goniometric light's
// (EnvironmentSampler): the rows' cumulative sums (height + 1), each row's texels' (height x
// (width + 1)), and each texel's probability (width x height). A projection light's: its
// texels' cumulative sums (width x height + 1), then each texel's probability.
PF_CONST(uint32_t) kBindingLightImageTables = 22;
// vec4[], per vertex: xyz Scene::tangents (normal or bump maps); and, in scenes with vertex
// colours, each vertex's colour (rgb, alpha: Scene::colors) after its tangent, or alone where
// there are no tangents (TangentSlot, ColorSlot in trace.glsl): no binding is left for them.
PF_CONST(uint32_t) kBindingTangents = 23;
PF_CONST(uint32_t) kBindingSheenTables = 24;  // float[kSheenTableSize]: kSheenTables (sheen.h)
// GpuHitPoint[]: where the batches' direct light is sampled, the epoch's camera pass (ppm); the
// hit points' own buffer where they are the same (sppm) or no pass is traced.
PF_CONST(uint32_t) kBindingDirectPoints = 25;
// uint64_t[], per hit point, this epoch: where its surface ends within its radius
// (core/shared/surface_edges.h).
PF_CONST(uint32_t) kBindingSurfaceEdges = 26;
// The integrators that render pixels (path, pm; pixel_trace.comp): a batch's camera rays
// (GpuCameraRay[], one a camera sample; their radiance goes to kBindingDirect), the job's
// constants (GpuPixelJob), and pm's two photon maps, one after the other, each a hashed grid
// (PhotonGrid's own arrays): the photons' positions (vec4[], what the search reads), their
// directions and powers (GpuPhotonPower[], read for the k nearest alone) and each map's bucket
// offsets (uint[], buckets + 1 a map). 32 bindings in all: lavapipe's limit
// (maxPerStageDescriptorStorageBuffers; Vulkan assures only 4, every GPU here allows more).
PF_CONST(uint32_t) kBindingCameraRays = 27;
PF_CONST(uint32_t) kBindingPixelJob = 28;
PF_CONST(uint32_t) kBindingPhotonPositions = 29;
PF_CONST(uint32_t) kBindingPhotonPowers = 30;
PF_CONST(uint32_t) kBindingPhotonBuckets = 31;
PF_CONST(uint32_t) kBindingCount = 32;
// The path tracer's wavefront holds its paths (GpuPathState[], one a pixel of the batch), its
// queues and counters in pm's map bindings, which path jobs leave free.
PF_CONST(uint32_t) kBindingPathStates = kBindingPhotonPositions;
PF_CONST(uint32_t) kBindingPathQueues = kBindingPhotonPowers;
PF_CONST(uint32_t) kBindingPathCounters = kBindingPhotonBuckets;

// What the prefix-sum kernels scan (GpuParams.scan_target).
PF_CONST(uint32_t) kScanGridBegin = 0;
PF_CONST(uint32_t) kScanTallyOffsets = 1;

// Specialisation constants: the scene's features, so that code for materials and lights it
// does not use is compiled out (booleans, 0 or 1).
PF_CONST(uint32_t) kSpecHasMirror = 0;
PF_CONST(uint32_t) kSpecHasDielectric = 1;
PF_CONST(uint32_t) kSpecHasThinDielectric = 2;
PF_CONST(uint32_t) kSpecHasTextures = 3;
PF_CONST(uint32_t) kSpecHasSmoothNormals = 4;
PF_CONST(uint32_t) kSpecHasTriangleLights = 5;
PF_CONST(uint32_t) kSpecHasPointLights = 6;
PF_CONST(uint32_t) kSpecHasSpotLights = 7;
PF_CONST(uint32_t) kSpecHasDirectionalLights = 8;
PF_CONST(uint32_t) kSpecHasRoughConductor = 9;
PF_CONST(uint32_t) kSpecHasRoughDielectric = 10;
PF_CONST(uint32_t) kSpecHasEnvironment = 11;
PF_CONST(uint32_t) kSpecHasTexturedLights = 12;
PF_CONST(uint32_t) kSpecHasImageLights = 13;        // goniometric or projection lights
PF_CONST(uint32_t) kSpecHasCoats = 14;              // coated diffuse or conductor materials
PF_CONST(uint32_t) kSpecHasCutOuts = 15;            // alpha cut-outs (core/shared/alpha.h)
PF_CONST(uint32_t) kSpecHasMixes = 16;              // mix materials (Material::kMix)
PF_CONST(uint32_t) kSpecHasRoughnessTextures = 17;  // Material::roughness_texture
PF_CONST(uint32_t) kSpecHasMixTextures = 18;        // Material::mix_texture
PF_CONST(uint32_t) kSpecHasConductorFresnel = 19;   // Material::conductor other than the tint
PF_CONST(uint32_t) kSpecHasAbsorption = 20;         // Material::absorption inside glass
PF_CONST(uint32_t) kSpecHasShadingDetail = 21;      // normal or bump maps
PF_CONST(uint32_t) kSpecHasTranslucency = 22;       // Material::transmittance
PF_CONST(uint32_t) kSpecHasSheen = 23;              // Material::sheen_color, its textures
// Not the scene's but the job's: its hit points gather kinds of photon of their own
// (GpuHitPoint::weight.w; core/shared/photon_kinds.h), direct light's among them (rpm's).
PF_CONST(uint32_t) kSpecPhotonKinds = 24;
// The job's, for pixel_trace.comp: classic photon mapping (1) or the path tracer (0), and pm's
// k nearest photons (the size of each thread's search heap; not a boolean).
PF_CONST(uint32_t) kSpecPhotonMapping = 25;
PF_CONST(uint32_t) kSpecNearest = 26;
// The path tracer's, for path_wavefront.comp: the stage a pipeline runs (kStage*), and the class
// of vertex it shades (kVertex*, path_vertex.glsl; kVertexAny in the megakernel). Not booleans.
PF_CONST(uint32_t) kSpecWavefrontStage = 27;
PF_CONST(uint32_t) kSpecVertexClass = 28;
PF_CONST(uint32_t) kSpecHasVertexColors = 29;  // Scene::colors (glTF's COLOR_0)
// Procedural textures (Texture::program; core/shared/procedural_texture.h).
PF_CONST(uint32_t) kSpecHasProceduralTextures = 30;
// The scene's again: curve shapes (core/shared/curve.h) in the BVH's leaves.
PF_CONST(uint32_t) kSpecHasCurves = 31;
PF_CONST(uint32_t) kSpecCount = 32;

// The path tracer's wavefront (path_wavefront.comp): its stages, and the classes of vertex,
// each shaded by a pipeline of its own from a queue of its own.
PF_CONST(uint32_t) kStageStart = 0;       // a path a pixel, its first camera sample queued
PF_CONST(uint32_t) kStageExtendArgs = 1;  // the extend stage's workgroups, from its queue
PF_CONST(uint32_t) kStageExtend = 2;      // closest hits; vertices queued by class
PF_CONST(uint32_t) kStageShadeArgs = 3;   // each shading pipeline's workgroups
PF_CONST(uint32_t) kStageShade = 4;       // a class's vertices; paths going on queued
PF_CONST(uint32_t) kVertexDiffuse = 0;    // diffuse, translucent or not, uncoated
PF_CONST(uint32_t) kVertexCoated = 1;     // coated diffuse
PF_CONST(uint32_t) kVertexRough = 2;      // rough conductor, uncoated
PF_CONST(uint32_t) kVertexSpecular = 3;   // every other: found by its own sampling alone
PF_CONST(uint32_t) kVertexClasses = 4;
PF_CONST(uint32_t) kVertexAny = 4;
// The wavefront's counters (uint[kPathCounterWords], kBindingPathCounters): each queue's
// length, then dispatch arguments (VkDispatchIndirectCommand) for the extend stage and for
// each class's shading.
PF_CONST(uint32_t) kPathCountRays = 0;      // two: the ray queues read and written in turn
PF_CONST(uint32_t) kPathCountVertices = 2;  // kVertexClasses: each class's queue
PF_CONST(uint32_t) kPathExtendArgs = 8;
PF_CONST(uint32_t) kPathShadeArgs = 12;  // 4 words a class (three used)
PF_CONST(uint32_t) kPathCounterWords = 28;
// Queues, each a path slot per pixel (uint[kPathQueues * pixels], kBindingPathQueues): the two
// ray queues, then a vertex queue a class.
PF_CONST(uint32_t) kPathQueues = 6;
// Workgroups a wavefront dispatch takes at most (Vulkan assures 65535 in x); its threads loop
// over the rest of their queue.
PF_CONST(uint32_t) kPathMaxGroups = 65535;

// Threads per workgroup of every kernel but the scan; the scan's workgroup covers
// kScanBlock elements, kScanPerThread per thread.
PF_CONST(uint32_t) kWorkgroupSize = 64;
PF_CONST(uint32_t) kScanThreads = 256;
PF_CONST(uint32_t) kScanPerThread = 8;
PF_CONST(uint32_t) kScanBlock = 2048;  // kScanThreads * kScanPerThread

// Material and emitter kinds, as core/scene/material.h and emitters.h number them.
PF_CONST(uint32_t) kMaterialDiffuse = 0;
PF_CONST(uint32_t) kMaterialMirror = 1;
PF_CONST(uint32_t) kMaterialDielectric = 2;
PF_CONST(uint32_t) kMaterialThinDielectric = 3;
PF_CONST(uint32_t) kMaterialRoughConductor = 4;
PF_CONST(uint32_t) kMaterialRoughDielectric = 5;
PF_CONST(uint32_t) kMaterialMix = 6;
// Material::surface_flags (GpuMaterial::alpha.w, uint bits): what a surface does beyond its
// material. Single-sided: its back faces let every ray through (glTF's doubleSided false on an
// open mesh; core/shared/alpha.h). Vertex alpha: its alpha is times the vertex colours' (glTF's
// COLOR_0 under alphaMode MASK or BLEND). Vertex emission: its emission is times the vertex
// colours (KHR_materials_unlit's base colour).
PF_CONST(uint32_t) kSurfaceSingleSided = 1;
PF_CONST(uint32_t) kSurfaceVertexAlpha = 2;
PF_CONST(uint32_t) kSurfaceVertexEmission = 4;
PF_CONST(uint32_t) kSurfaceFlags = 7;  // every flag
PF_CONST(uint32_t) kEmitterTriangle = 0;
PF_CONST(uint32_t) kEmitterPoint = 1;
PF_CONST(uint32_t) kEmitterSpot = 2;
PF_CONST(uint32_t) kEmitterDirectional = 3;
PF_CONST(uint32_t) kEmitterEnvironment = 4;
PF_CONST(uint32_t) kEmitterGoniometric = 5;
PF_CONST(uint32_t) kEmitterProjection = 6;

// A two-wide BVH node holding both children's boxes (Embree's builder, flattened). A child
// is a node index where its count is 0, else `count` triangles from `first`.
struct GpuBvhNode {
    vec4 left_lower;   // xyz; w: the left child (uint bits)
    vec4 left_upper;   // xyz; w: the left child's triangle count (uint bits)
    vec4 right_lower;  // xyz; w: the right child
    vec4 right_upper;  // xyz; w: the right child's triangle count
};
PF_GPU_LAYOUT(GpuBvhNode, 64);

// A triangle as the intersection test wants it, in leaf order. A leaf's slot may instead be a
// curve's (kCurveBit set in p0.w's bits, core/shared/curve.h): p0.w's other bits then index the
// first of its two records, which follow the slots in the same binding: the first (cp0, w0),
// (cp1, w1), (cp2, material), the second (cp3, type), (n0, the curve's index), (n1, 0) -- its
// Bezier control points cp, widths at its ends w, a ribbon's end normals n (Curve in
// core/scene/scene.h; material, type and index as uint bits).
struct GpuTriangle {
    vec4 p0;     // xyz; w: the scene triangle's index (uint bits)
    vec4 edge1;  // p1 - p0; w: 1 where its material has cut-outs (trace.glsl's MeetsSurface
                 // runs for those alone), else 0
    vec4 edge2;  // p2 - p0
};
PF_GPU_LAYOUT(GpuTriangle, 48);

// What shading a hit needs beyond its position, in scene triangle order.
struct GpuTriangleShading {
    vec4 normal;     // unit geometric normal (the winding's front); w: the index of the
                     // triangle's emitter (uint bits), or kNoEmitter
    uvec4 vertices;  // xyz: vertex indices (normals, uvs); w: material | kSmoothBit
};
PF_GPU_LAYOUT(GpuTriangleShading, 32);
PF_CONST(uint32_t) kSmoothBit = 0x80000000u;
PF_CONST(uint32_t) kNoEmitter = 0xffffffffu;
PF_CONST(uint32_t) kNoCoat = 0xffffffffu;  // a hit point under no coat (core/job/hit_point.h)

struct GpuMaterial {
    vec4 base_color;            // xyz; w: index of refraction
    uint32_t type;              // kMaterial*
    int32_t texture;            // base colour texture, or -1
    float roughness;            // GGX alpha of the rough materials
    int32_t roughness_texture;  // scales roughness and coat.y where set, or -1
    vec4 coat;   // a coat's index of refraction (0: none), GGX alpha, optical thickness;
                 // w: the most bounces under it (uint bits); core/shared/coat.h
    vec4 layer;  // the coat's kind (kCoat*, uint bits), y: a Fresnel mix's weight; z, w: the
                 // sheen's colour and roughness textures, or -1 (int bits)
    vec4 alpha;  // x: alpha (1 without cut-outs), y: its cutoff (0: stochastic); z: the alpha
                 // texture, or -1 (int bits); core/shared/alpha.h; w: kSurface* flags (uint bits)
    uvec4 mix;   // kMaterialMix: x, y the two materials; z the second's probability (float
                 // bits), w: a texture scaling it, or -1 (int bits)
    vec4 conductor_eta;  // a conductor's complex index, xyz: eta; w: its Fresnel kind
                         // (kConductor*, uint bits); core/shared/conductor.h
    vec4 conductor_k;    // xyz: k; w: the coat's samples (Material::coat_samples), its bits
    vec4 absorption;     // xyz: the absorption coefficient of the medium behind (BeerLambert)
    vec4 detail;         // x: the normal map's texture, or -1 (int bits), y: its scale; z: the bump
                  // map's texture, or -1 (int bits), w: its scale (core/shared/shading_normal.h)
    vec4 transmittance;  // xyz: a diffuse surface's diffuse transmission (translucent.h); w: its
                         // texture, or -1 (int bits)
    vec4 sheen;          // xyz: the sheen's colour (black: none), w: its roughness (sheen.h)
    vec4 outside_absorption;  // xyz: ... and of the medium in front (Material's)
};
PF_GPU_LAYOUT(GpuMaterial, 208);

// An image; or, where width is 0, a procedural texture's program: its first word in the texels
// binding and its length (height).
struct GpuTexture {
    uint32_t first_texel;  // into the texels binding
    int32_t width, height;
    uint32_t wrap;  // kWrap* of u, and of v shifted left by 16 (core/shared/texture_wrap.h)
};
PF_GPU_LAYOUT(GpuTexture, 16);

// One light: an emissive triangle, a punctual light or the environment, with what emission
// and light sampling need precomputed (core/scene/emitters.cpp computes the same on the CPU).
// The lights with an image (environment, goniometric, projection) keep it and its sampling
// tables in the light-image bindings.
struct GpuEmitter {
    vec4 position;   // triangle: p0; point, spot, goniometric, projection: position;
                     // environment: its portal's corner; w: kind (uint bits)
    vec4 edge1;      // triangle: p1 - p0; w: area. Lights with an image: x, y the image's
                     // width and height (uint bits); environment, goniometric: z its mapping
                     // (kMapping*, uint bits); projection: w a texel's area on the plane z = 1
    vec4 edge2;      // triangle: p2 - p0, w: 1 if cut out everywhere (found by light sampling
                     // alone, Emitters::EmissiveTriangle::invisible). Lights with an image: the
                     // first row of the rotation
                     // from the world into the image's frame (Environment::to_map,
                     // PunctualLight::to_light)
    vec4 direction;  // triangle: unit emitting normal, w: 1 if it emits from both faces; spot,
                     // directional: direction of travel. Lights with an image: the rotation's
                     // second row
    vec4 power;      // a photon's flux before selection and falloff (triangle: Le pi area;
                     // point: 4 pi I; spot: I x cone solid angle; directional: E pi r^2;
                     // environment: pi r^2 x the radiance's integral; goniometric, projection:
                     // the intensity integrated over the sphere); w: 1 / selection probability
    vec4 radiance;   // triangle: Le; point, spot: intensity I, w: range (0: none);
                     // directional: irradiance E; environment: its scale (a uniform one's
                     // radiance); goniometric, projection: the intensity scaling the image
    vec4 cone;  // spot: cos_inner, cos_outer, 1 / max(0.001, cos_inner - cos_outer), smoothstep (1)
                // or quadratic (0). Lights with an image: the rotation's third row
    vec4 texture;   // triangle: xy the texture coordinates at p0, z the emission texture
                    // (int bits), -1 for none; radiance and power are then times its texel;
                    // w the triangle whose vertex colours scale them too, or kNoEmitter (uint
                    // bits).
                    // Lights with an image: x its first texel, y its first table entry (uint
                    // bits); projection: zw the image's half-width and half-height on the
                    // plane z = 1
    vec4 uv_edges;  // triangle: xy uv1 - uv0, zw uv2 - uv0
    // Environment with a portal (EnvironmentPortal), whose corner is `position`: xyz its edges;
    // portal_u.w its area (0: no portal); portal_v.w the first table entry (uint bits) of the
    // photons' sampling over the hemisphere outside it (EnvironmentSampler facing its normal).
    vec4 portal_u;
    vec4 portal_v;
};
PF_GPU_LAYOUT(GpuEmitter, 176);

struct GpuHitPoint {
    vec4 position;  // xyz; w: the material whose coat covers it, or kNoCoat (uint bits)
    vec4 normal;    // xyz unit, toward the camera path's side; w: its pixel (uint bits)
    vec4 weight;    // xyz camera throughput x BSDF, 1/sr; w: the photons it gathers (uint bits)
};
PF_GPU_LAYOUT(GpuHitPoint, 48);

// A hit point in a grid bucket: its centre, R^2 and normal copied, so the gather reads
// one contiguous run of entries per bucket.
struct GpuGridEntry {
    vec4 position;  // xyz; w: R^2
    vec4 normal;    // xyz; w: the hit point's index (uint bits)
};
PF_GPU_LAYOUT(GpuGridEntry, 32);

// A batch's photons at one hit point, summed with integer atomics so that the sums do not
// depend on the order threads reach them: flux in fixed point, units of
// 1 / GpuParams.flux_to_fixed watts (see vulkan_backend.cpp for the range argument).
struct GpuTallySum {
    uint64_t flux[3];
    uint32_t photons;        // M
    uint32_t inner_photons;  // within R / sqrt(2)
};
PF_GPU_LAYOUT(GpuTallySum, 32);

// One hit point's entry of the sparse tally a batch returns (Tally in core/job/batch.h),
// written in hit point order by tally_compact.comp.
struct GpuTallyEntry {
    uint32_t hit_point;
    uint32_t photons;
    uint32_t inner_photons;
    float flux[3];  // W, converted from the fixed-point sums
};
PF_GPU_LAYOUT(GpuTallyEntry, 24);

struct GpuCounters {
    uint64_t segments;             // photon rays traced
    uint64_t nonfinite_discarded;  // photon paths and direct samples dropped as NaN or Inf
    uint64_t tally_entries;        // hit points the batch's photons reached
    // Adaptive tracing: fresh photons found visible, and chain steps that traced a state.
    uint64_t visible_photons;
    uint64_t chain_steps;
    uint64_t pad;
};
PF_GPU_LAYOUT(GpuCounters, 48);

// A camera sample's ray, made on the host (core/camera/pixel_sample.h: the pixel's filter, the
// lens), and the weight its radiance takes in its pixel's mean.
struct GpuCameraRay {
    vec4 origin;     // xyz; w: the weight (PixelSampleRay's)
    vec4 direction;  // xyz unit
};
PF_GPU_LAYOUT(GpuCameraRay, 32);

// One of classic photon mapping's maps as a hashed uniform grid (core/pm/photon_grid.h, whose
// arrays are uploaded as they are): its photons from first_photon, its bucket offsets from
// first_bucket (bucket_mask + 2 of them).
struct GpuPhotonMap {
    uint32_t first_photon;
    uint32_t photon_count;
    uint32_t first_bucket;
    uint32_t bucket_mask;
    float cell_size;
    float inverse_cell_size;
    uint32_t pad0, pad1;
};
PF_GPU_LAYOUT(GpuPhotonMap, 32);

// A stored photon's direction of travel and power (W, over the photons emitted for its map).
struct GpuPhotonPower {
    vec4 direction;  // xyz unit
    vec4 power;      // xyz
};
PF_GPU_LAYOUT(GpuPhotonPower, 32);

// What every camera sample of a pixel job reads (path, pm), fixed for the job.
struct GpuPixelJob {
    uint32_t samples_per_pixel;
    uint32_t max_depth;          // path: surfaces a path scatters at; pm: a camera path's surfaces
    uint32_t roulette_depth;     // Russian roulette from this bounce on (kPathRouletteDepth, ...)
    uint32_t gather_depth;       // pm: surfaces a gather ray follows at most (kMaxGatherDepth)
    uint32_t final_gather;       // pm: gather rays at a diffuse hit (0: the global map there)
    uint32_t density_filter;     // pm: the density filter (core/shared/density_filter.h)
    float max_radius_sq;         // pm: the k-nearest search's limit (MaxSearchRadius squared)
    float filter_normalisation;  // pm: DensityFilterNormalisation(density_filter)
    uint32_t per_cosine;  // pm: the photons' power is per unit of their cosine (shading normals)
    uint32_t pad0, pad1, pad2;
    GpuPhotonMap global_map, caustic_map;
};
PF_GPU_LAYOUT(GpuPixelJob, 112);

// A path of the wavefront between stages (PathState in path_vertex.glsl, with the pixel's
// samples so far): a slot a pixel of the batch, its samples traced one after another.
struct GpuPathState {
    vec4 origin, direction;     // xyz: the ray the path follows next
    vec4 radiance, throughput;  // xyz: of the sample being traced; throughput.w its refraction
    vec4 bounced_at;            // xyz: its last diffuse or rough vertex
    vec4 sum;                   // xyz: the pixel's finished samples, each times its filter weight
    vec4 hit;                   // the extend stage's closest hit: t, triangle (its bits), b1, b2
    uint64_t rng_state, rng_increment;  // the pixel's stream (Pcg32)
    float bsdf_pdf;
    uint32_t flags;          // kPathSpecularBounce, kPathCoatExit
    uint32_t depth;          // surfaces the sample's path has met
    uint32_t traced_sample;  // the pixel's sample being traced
    uint32_t discarded;      // the pixel's samples left out (NaN or Inf)
    uint32_t pad0, pad1, pad2;
};
PF_GPU_LAYOUT(GpuPathState, 160);
PF_CONST(uint32_t) kPathSpecularBounce = 1;
PF_CONST(uint32_t) kPathCoatExit = 2;

// Push constants, the same block for every pipeline.
struct GpuParams {
    vec4 scene_sphere;          // xyz centre, w radius: the bounding sphere (directional lights)
    float scene_magnitude;      // Bounds::Magnitude, for ray offsets
    float grid_inverse_cell;    // 1 / grid cell size
    uint32_t grid_bucket_mask;  // buckets - 1
    uint32_t hit_point_count;
    float flux_to_fixed;  // fixed-point units per watt of photon flux
    uint32_t emitter_count;
    // photons: first photon of this dispatch; direct: first hit point; pixels: the first of the
    // batch's camera samples (pixel by pixel, each pixel's in order) of this dispatch
    uint32_t first;
    uint32_t end;  // photons: one past the batch's last photon; direct: of the slice; pixels: of
                   // the batch's samples
    uint64_t seed_prefix;  // the stream family of the batch's photons, direct samples or pixels
    uint32_t scan_count;   // elements the scan covers
    uint32_t max_bounces;
    uint32_t direct_begin;  // direct: the slice's first hit point (output index 0); pixels: the
                            // batch's first pixel
    uint32_t scan_target;   // kScanGridBegin or kScanTallyOffsets
    uint32_t environment_emitter;  // the environment's index into the emitters, if any
    // direct: the points are the epoch's camera pass in slot order, this many a pixel, and take
    // its samples' numbers (core/ppm/direct_light.h, DirectLightSequence); 0: a stream each.
    uint32_t direct_samples_per_pixel;
    uint64_t direct_sequences;     // direct: FamilyPartial of the pixels' direct-light sequences
    uint64_t direct_first_sample;  // direct: the pass's first index in each sequence
    uint32_t epoch_parity;         // direct: epoch & 1, which of a pixel's two sequences
    // photons: adaptive tracing's steps a chain (one chain a thread); 0: uniform tracing
    uint32_t chain_steps;
    uint64_t proposal_prefix;  // photons, adaptive: the stream family of the chains' mutations
    // direct: the pass's slots a camera sample (1 + rpm's gather rays; DirectLightSequence)
    uint32_t direct_slots_per_sample;
    uint32_t path_queue;  // the path tracer's wavefront: the ray queue its stages read (0 or 1)
    // 120 bytes, padded to 128 (the vec4's alignment): all the 128 bytes Vulkan assures; a
    // field more must take a pad's place below or share one.
};
PF_GPU_LAYOUT(GpuParams, 128);

PF_GPU_END

#endif  // PF_CORE_SHARED_GPU_TYPES_H
