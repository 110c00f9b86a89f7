// Classic photon mapping's k-nearest density estimate on the device, over maps built on the
// host and uploaded as hashed uniform grids (core/pm/photon_grid.cpp, whose search this is:
// look in the cells within r of the point, doubling r from one cell until k photons lie within
// it or the search's limit is reached), filtered as core/pm/density_estimate.cpp does.
#include "core/shared/density_filter.h"

layout(std430, binding = kBindingPhotonPositions) readonly buffer PhotonPositions { vec4 photon_positions[]; };
layout(std430, binding = kBindingPhotonPowers) readonly buffer PhotonPowers { GpuPhotonPower photon_powers[]; };
layout(std430, binding = kBindingPhotonBuckets) readonly buffer PhotonBuckets { uint photon_buckets[]; };

// k: the job's --pm-nearest, which sizes each thread's heap.
layout(constant_id = kSpecNearest) const uint kNearest = 1;

// The nearest photons found so far (NearestPhotons): a max-heap on squared distance, the
// farthest first, and the search's limit, which shrinks to the k-th distance once k are found.
float heap_distance[kNearest];
uint heap_photon[kNearest];
uint heap_size;
float heap_limit;

void OfferPhoton(float distance_sq, uint photon) {
    uint i;
    if (heap_size < kNearest) {  // push, sifting up
        i = heap_size++;
        while (i > 0) {
            const uint parent = (i - 1) / 2;
            if (!(heap_distance[parent] < distance_sq)) break;
            heap_distance[i] = heap_distance[parent];
            heap_photon[i] = heap_photon[parent];
            i = parent;
        }
        heap_distance[i] = distance_sq;
        heap_photon[i] = photon;
        if (heap_size == kNearest) heap_limit = heap_distance[0];
        return;
    }
    if (!(distance_sq < heap_distance[0])) return;
    // Replace the farthest, sifting down.
    i = 0;
    while (true) {
        const uint left = 2 * i + 1, right = left + 1;
        if (left >= kNearest) break;
        const uint larger = right < kNearest && heap_distance[left] < heap_distance[right] ? right : left;
        if (!(distance_sq < heap_distance[larger])) break;
        heap_distance[i] = heap_distance[larger];
        heap_photon[i] = heap_photon[larger];
        i = larger;
    }
    heap_distance[i] = distance_sq;
    heap_photon[i] = photon;
    heap_limit = heap_distance[0];
}

// PhotonGrid::CellOf and Bucket.
i64vec3 PhotonCell(GpuPhotonMap map, vec3 p) {
    return i64vec3(floor(clamp(p * map.inverse_cell_size, vec3(-1e15), vec3(1e15))));
}

uint PhotonBucket(GpuPhotonMap map, i64vec3 cell) {
    const uint64_t h = (uint64_t(cell.x) * 73856093ul) ^ (uint64_t(cell.y) * 19349663ul) ^ (uint64_t(cell.z) * 83492791ul);
    return uint(h & uint64_t(map.bucket_mask));
}

// Offers every photon of the cells overlapping the sphere (p, radius) (PhotonGrid::Visit).
void VisitPhotons(GpuPhotonMap map, vec3 p, float radius) {
    const i64vec3 low = PhotonCell(map, p - vec3(radius)), high = PhotonCell(map, p + vec3(radius));
    for (int64_t x = low.x; x <= high.x; ++x)
        for (int64_t y = low.y; y <= high.y; ++y)
            for (int64_t z = low.z; z <= high.z; ++z) {
                const i64vec3 cell = i64vec3(x, y, z);
                const uint bucket = map.first_bucket + PhotonBucket(map, cell);
                const uint end = photon_buckets[bucket + 1];
                for (uint i = photon_buckets[bucket]; i < end; ++i) {
                    const vec3 position = photon_positions[map.first_photon + i].xyz;
                    const vec3 offset = position - p;
                    const float distance_sq = dot(offset, offset);
                    // Other cells may share the bucket: each photon counts in its own cell only.
                    if (distance_sq < heap_limit && PhotonCell(map, position) == cell) OfferPhoton(distance_sq, i);
                }
            }
}

// The k nearest photons of `map` to p within the job's search limit into the heap
// (PhotonGrid::Nearest).
void NearestPhotons(GpuPhotonMap map, vec3 p) {
    const float max_distance_sq = pixel_job.max_radius_sq;
    for (float radius = map.cell_size;; radius *= 2.0) {
        const float radius_sq = min(radius * radius, max_distance_sq);
        heap_size = 0;
        heap_limit = radius_sq;
        VisitPhotons(map, p, sqrt(radius_sq));
        if (heap_size == kNearest || radius_sq >= max_distance_sq) return;
    }
}

// Reflected radiance at p of a diffuse surface with unit normal n (on the side light is gathered
// from) and albedo rho, from the map's k nearest photons (EstimateDiffuseRadiance).
vec3 EstimateDiffuseRadiance(GpuPhotonMap map, vec3 p, vec3 n, vec3 albedo) {
    if (map.photon_count == 0) return vec3(0);
    NearestPhotons(map, p);
    const float radius_sq = heap_limit;
    if (heap_size == 0 || !(radius_sq > 0)) return vec3(0);
    vec3 flux = vec3(0);
    for (uint e = 0; e < heap_size; ++e) {
        const GpuPhotonPower photon = photon_powers[map.first_photon + heap_photon[e]];
        const float facing = -dot(photon.direction.xyz, n);
        if (!(facing > 0)) continue;  // from behind the surface
        const float weight = DensityFilterWeight(pixel_job.density_filter, heap_distance[e], radius_sq);
        flux += photon.power.xyz * (pixel_job.per_cosine != 0 ? weight * facing : weight);
    }
    const float area = kPi * radius_sq * pixel_job.filter_normalisation;
    return albedo * flux / (kPi * area);
}
