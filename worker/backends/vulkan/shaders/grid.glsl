// The hit-point hash grid's cells and buckets (grid_count, grid_fill and the gather agree on
// them). Cells are twice the largest radius wide, each hit point is stored once, in the
// bucket of its centre's cell, and a photon looks in the 2x2x2 cells its sphere of the
// largest radius can reach (Hachisuka's GPU PPM: one entry a hit point, eight lookups a
// photon, where the CPU grid stores up to eight entries and looks once).
ivec3 GridCell(vec3 p) {
    // Clamped so that shrinking radii or distant photons cannot overflow the conversion;
    // clamped cells only merge, which costs candidates, never correctness.
    const float kLimit = 1073741824.0;  // 2^30
    return ivec3(floor(clamp(p * params.grid_inverse_cell, vec3(-kLimit), vec3(kLimit))));
}

// Teschner et al. 2003, "Optimized Spatial Hashing for Collision Detection".
uint GridBucket(ivec3 cell) {
    return (uint(cell.x) * 73856093u ^ uint(cell.y) * 19349663u ^ uint(cell.z) * 83492791u) & params.grid_bucket_mask;
}

// A hit point takes part in this epoch's gather: a radius, and a weight photons can change.
bool GridHolds(uint hit_point) {
    return radius_sq[hit_point] > 0 && MaxComponent(hit_points[hit_point].weight.xyz) > 0;
}
