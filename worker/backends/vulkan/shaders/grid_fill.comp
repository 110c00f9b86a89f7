#version 460
// Grid build, step 3: every hit point copied into its bucket's range (grid_cursor starts as
// the buckets' offsets). Order within a bucket follows scheduling, which the integer tally
// sums do not see.
#include "common.glsl"
#include "grid.glsl"

layout(local_size_x = kWorkgroupSize) in;

void main() {
    const uint hit_point = gl_GlobalInvocationID.x;
    if (hit_point >= params.hit_point_count || !GridHolds(hit_point)) return;
    const GpuHitPoint point = hit_points[hit_point];
    const uint slot = atomicAdd(grid_cursor[GridBucket(GridCell(point.position.xyz))], 1u);
    grid_entries[slot].position = vec4(point.position.xyz, radius_sq[hit_point]);
    grid_entries[slot].normal = vec4(point.normal.xyz, uintBitsToFloat(hit_point));
}
